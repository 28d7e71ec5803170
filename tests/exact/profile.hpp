#pragma once
/// Exact profiles s(X) at a time t, built from exact waves (exact/riemann.hpp), and the
/// exact L1 distance of a piecewise-constant numerical profile from them: what the
/// convergence tests and the work-precision driver measure errors against.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "exact/riemann.hpp"

namespace rigidity::exact {

/// A centred fan of a wave at time t: the label X sees the characteristic of speed (X − Xc)/t.
struct FanPiece {
  Wave<double> wave;
  double centre = 0.0;
  double time = 0.0;

  [[nodiscard]] double stretch_at(double X) const { return wave.at((X - centre) / time).stretch; }
  /// The label where the fan's stretch is s; NaN if s is not inside the fan.
  [[nodiscard]] double label_at_stretch(double s) const {
    const double lo = std::min(wave.left().stretch, wave.right().stretch);
    const double hi = std::max(wave.left().stretch, wave.right().stretch);
    if (!(s > lo && s < hi)) return std::nan("");
    const State<double> u = wave.on_curve(wave.law->psi(s));
    return centre + time * characteristic_speed(*wave.law, u, wave.family);
  }
};

/// s on [X0, X1]: the constant `stretch`, or the fan.
struct ProfilePiece {
  double X0 = 0.0, X1 = 0.0;
  double stretch = 1.0;
  std::optional<FanPiece> fan = std::nullopt;
};
using Profile = std::vector<ProfilePiece>;

/// Appends the pieces of `profile` cut to [a, b].
inline void append_clipped(Profile& out, const Profile& profile, double a, double b) {
  for (ProfilePiece p : profile) {
    p.X0 = std::max(p.X0, a);
    p.X1 = std::min(p.X1, b);
    if (p.X1 > p.X0) out.push_back(p);
  }
}

/// One wave centred at label `centre` at time t (> 0) on [X_from, X_to].
inline Profile wave_profile(const Wave<double>& wave, double centre, double t, double X_from, double X_to) {
  Profile all;
  const double left_edge = centre + t * wave.left_edge_speed(), right_edge = centre + t * wave.right_edge_speed();
  if (wave.kind == WaveKind::none) {
    all.push_back({X_from, X_to, wave.outer.stretch});
  } else {
    all.push_back({X_from, left_edge, wave.left().stretch});
    if (wave.kind == WaveKind::fan) all.push_back({left_edge, right_edge, 0.0, FanPiece{wave, centre, t}});
    all.push_back({right_edge, X_to, wave.right().stretch});
  }
  Profile out;
  append_clipped(out, all, X_from, X_to);
  return out;
}

/// A Riemann (or wall) solution centred at the label X_interface at time t, on [X_from, X_to]:
/// the left wave's side below X_interface, the right wave's above.
inline Profile solution_profile(const Solution<double>& sol, double X_interface, double t, double X_from, double X_to) {
  Profile out;
  if (X_from < X_interface)
    append_clipped(out, wave_profile(sol.left, X_interface, t, X_from, X_interface), X_from, X_to);
  if (X_to > X_interface) append_clipped(out, wave_profile(sol.right, X_interface, t, X_interface, X_to), X_from, X_to);
  return out;
}

/// The exact stretch of a profile at X (the right piece at a piece boundary).
inline double stretch_at(const Profile& profile, double X) {
  for (auto it = profile.rbegin(); it != profile.rend(); ++it)
    if (X >= it->X0) return it->fan ? it->fan->stretch_at(X) : it->stretch;
  return profile.empty() ? std::nan("") : profile.front().stretch;
}

// ---- the L1 distance ----------------------------------------------------------------------------

/// A constant piece of a numerical profile: s = value on [X0, X1].
struct Piece {
  double X0, X1, value;
};

namespace detail {

/// ∫ (s(X) − c) dX over [a, b] inside a fan, composite 8-point Gauss–Legendre on panels no
/// wider than 1e-3 (s is analytic inside the fan).
inline double fan_integral(const FanPiece& fan, double c, double a, double b) {
  static constexpr std::array<double, 4> node = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                                 0.9602898564975363};
  static constexpr std::array<double, 4> weight = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                                   0.1012285362903763};
  if (!(b > a)) return 0.0;
  const int panels = std::max(1, static_cast<int>(std::ceil((b - a) / 1e-3)));
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int k = 0; k < panels; ++k) {
    const double mid = a + (k + 0.5) * h, half = 0.5 * h;
    for (std::size_t i = 0; i < node.size(); ++i) {
      sum += weight[i] * half * (fan.stretch_at(mid - half * node[i]) - c);
      sum += weight[i] * half * (fan.stretch_at(mid + half * node[i]) - c);
    }
  }
  return sum;
}

/// ∫ |s(X) − c| dX over [a, b] inside a fan, split where s crosses c (s is monotone in a fan).
inline double fan_l1(const FanPiece& fan, double c, double a, double b) {
  const double crossing = fan.label_at_stretch(c);
  if (crossing > a && crossing < b)
    return std::abs(fan_integral(fan, c, a, crossing)) + std::abs(fan_integral(fan, c, crossing, b));
  return std::abs(fan_integral(fan, c, a, b));
}

}  // namespace detail

/// ∫ |s_h − s| dX of a piecewise-constant numerical profile (pieces sorted) against an exact
/// one, integrated exactly piece by piece: constants in closed form, fans by Gauss–Legendre
/// on either side of the crossing.
inline double l1_distance(const std::vector<Piece>& numerical, const Profile& exact) {
  double sum = 0.0;
  std::size_t j = 0;
  for (const Piece& p : numerical) {
    while (j < exact.size() && exact[j].X1 <= p.X0) ++j;
    for (std::size_t k = j; k < exact.size() && exact[k].X0 < p.X1; ++k) {
      const double a = std::max(p.X0, exact[k].X0), b = std::min(p.X1, exact[k].X1);
      if (!(b > a)) continue;
      sum +=
          exact[k].fan ? detail::fan_l1(*exact[k].fan, p.value, a, b) : std::abs(p.value - exact[k].stretch) * (b - a);
    }
  }
  return sum;
}

}  // namespace rigidity::exact
