#pragma once
/// Exact solutions of the work-precision scenes and the exact L1 distance of a
/// piecewise-constant numerical profile from them.
///
/// Everything here is written out from SPEC §1–2 and the paper with closed forms and
/// plain bisection; nothing calls rigidity's materials or Riemann solver, so the
/// reference is independent of the solvers it measures. Units c = 1, labels X.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace rigidity::work_precision {

/// A constant piece of a numerical profile: s = value on [X0, X1].
struct Piece {
  double X0, X1, value;
};

/// A centred C− rarefaction fan of the constant_sound_speed material (dp/de = V²),
/// centred at label Xc at time 0, entering the state (φL, sL) on its left.
/// Across a C− wave J+ = φ + Ψ(s) is constant, with Ψ(s) = −V ln s (c_s = V):
///   s(φ) = sL exp((φ − φL)/V);
/// a point of the fan moves at its C− speed dX/dt = −c_s / (s γ (1 − v c_s)) (SPEC §1).
struct ConstantSoundSpeedFan {
  double sound_speed = 0.5;    ///< V
  double rapidity_left = 0.0;  ///< φL, the state the head enters
  double stretch_left = 1.0;   ///< sL
  double rapidity_tail = 0.0;  ///< φ* at the tail
  double centre = 0.0;         ///< Xc
  double time = 0.0;           ///< t since the fan formed

  [[nodiscard]] double stretch(double phi) const {
    return stretch_left * std::exp((phi - rapidity_left) / sound_speed);
  }
  [[nodiscard]] double rapidity(double s) const { return rapidity_left + sound_speed * std::log(s / stretch_left); }
  /// Lagrangian C− speed at rapidity φ on the fan (increasing in φ).
  [[nodiscard]] double speed(double phi) const {
    const double V = sound_speed;
    return -V / (stretch(phi) * (std::cosh(phi) - V * std::sinh(phi)));
  }
  [[nodiscard]] double label(double phi) const { return centre + time * speed(phi); }
  [[nodiscard]] double head() const { return label(rapidity_left); }
  [[nodiscard]] double tail() const { return label(rapidity_tail); }
  /// s at label X in [head, tail], by bisection on φ.
  [[nodiscard]] double stretch_at(double X) const {
    double lo = rapidity_left, hi = rapidity_tail;
    for (int i = 0; i < 200 && lo < hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (label(mid) < X ? lo : hi) = mid;
    }
    return stretch(0.5 * (lo + hi));
  }
};

/// A piece of an exact profile on [X0, X1]: the constant `value`, or the fan.
struct ExactPiece {
  double X0, X1;
  double value = 0.0;
  std::optional<ConstantSoundSpeedFan> fan = std::nullopt;
};
using ExactProfile = std::vector<ExactPiece>;

// =====================================================================================
// (a) the paper's wall impact

/// A rigid bar of natural length l0 at velocity v hits a wall at its right end at t = 0.
/// Behind the compression front s = sqrt((1 − v)/(1 + v)) (paper eq. 15) and the bar
/// is at rest; the front runs back at dX/dt = −e^φ/s_ahead = −1/s_c, reaches the free
/// rear at t1 = l0 s_c and returns as a release front at +1/s_c, behind which the bar
/// is unstrained at −v (footnote 2 of the paper). Valid for t < 2 t1.
inline ExactProfile wall_impact_profile(double v, double l0, double t) {
  const double s_c = std::sqrt((1.0 - v) / (1.0 + v));
  const double t1 = l0 * s_c;
  const double front = t < t1 ? l0 - t / s_c : (t - t1) / s_c;
  return {{0.0, front, 1.0}, {front, l0, s_c}};
}

// =====================================================================================
// (b) a rigid flyer on a Hooke target

/// The star state of a rigid state (rest density ρa, rapidity φ0, unstrained) meeting a
/// hooke state (rest density ρb, wave speed b) at rest and unstrained, by plain
/// bisection on the pressure (as tests/solvers/two_material_exact.hpp):
///   rigid:  φ = φ0 − ½ ln(1 + 2p/ρa)   (J+ carried, Ψ = −ln s, s⁻² = 1 + 2p/ρa);
///   hooke:  φ = asinh(b/a) − asinh(b s(p)/a), a = sqrt(1 − b²), s(p) from e/R − ρb = p
///           with R = sqrt(b² + a²/s²), e = ρb (R − b²)/a² (SPEC §2).
struct RigidOnHookeStar {
  double pressure;
  double rapidity;
  double stretch_rigid;
  double stretch_hooke;
};

inline double hooke_stretch_at_pressure(double rho_b, double b, double p) {
  const double a = std::sqrt(1.0 - b * b);
  double lo = -30.0, hi = 0.0;  // ln s
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi), s = std::exp(mid);
    const double R = std::sqrt(b * b + a * a / (s * s));
    const double e = rho_b * (R - b * b) / (a * a);
    (e / R - rho_b > p ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

inline RigidOnHookeStar rigid_on_hooke_star(double rho_a, double phi0, double rho_b, double b) {
  const double a = std::sqrt(1.0 - b * b);
  auto mismatch = [&](double p) {
    const double left = phi0 - 0.5 * std::log1p(2.0 * p / rho_a);
    const double right = std::asinh(b / a) - std::asinh(b * hooke_stretch_at_pressure(rho_b, b, p) / a);
    return left - right;
  };
  double lo = 0.0, hi = rho_b * b * b / (a * a) * (1.0 - 1e-12);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mismatch(mid) > 0.0 ? lo : hi) = mid;
  }
  const double p = 0.5 * (lo + hi);
  return {p, phi0 - 0.5 * std::log1p(2.0 * p / rho_a), 1.0 / std::sqrt(1.0 + 2.0 * p / rho_a),
          hooke_stretch_at_pressure(rho_b, b, p)};
}

/// The flyer (labels [0, l_a], moving at v0) touches the target (labels [0, l_b], at
/// rest) at t = 0. Before either front reaches a far end: in the flyer a C− front at
/// dX/dt = −e^φ0 (rigid, unstrained ahead), in the target a C+ front at dX/dt = b
/// (hooke: c_s = b in the natural state at rest). Both are linearly degenerate jumps.
struct CollisionProfiles {
  ExactProfile flyer, target;
};

inline CollisionProfiles rigid_on_hooke_profiles(double rho_a, double v0, double l_a, double rho_b, double b,
                                                 double l_b, double t) {
  const double phi0 = std::atanh(v0);
  const RigidOnHookeStar star = rigid_on_hooke_star(rho_a, phi0, rho_b, b);
  const double flyer_front = l_a - t * std::exp(phi0);
  const double target_front = b * t;
  return {{{0.0, flyer_front, 1.0}, {flyer_front, l_a, star.stretch_rigid}},
          {{0.0, target_front, star.stretch_hooke}, {target_front, l_b, 1.0}}};
}

// =====================================================================================
// (c) the constant_sound_speed shock tube

/// p(s) = ρ V²/(1+V²) (s^−(1+V²) − 1); with it (e + p) s = ρ s^−V² (SPEC §2).
inline double css_pressure(double rho, double V, double s) {
  return rho * V * V / (1.0 + V * V) * (std::pow(s, -(1.0 + V * V)) - 1.0);
}

/// The rapidity behind a right-moving shock into the natural state at rest, with star
/// stretch s < 1: the label and momentum jump conditions m[s/γ] = −[v] and
/// m[(e+p) s γ v] = [p] (SPEC §1) eliminate m to A c² − p c + (p s − A) = 0 for
/// c = cosh φ, A = ρ s^−V²; the root with c ≥ 1.
inline double css_shock_rapidity(double rho, double V, double s) {
  const double p = css_pressure(rho, V, s);
  const double A = rho * std::pow(s, -V * V);
  const double c = (p + std::sqrt(p * p - 4.0 * A * (p * s - A))) / (2.0 * A);
  return std::acosh(std::max(1.0, c));
}

struct ShockTubeExact {
  ConstantSoundSpeedFan fan;
  double stretch_left, stretch_right, stretch_star;
  double shock_speed;  ///< Lagrangian dX/dt
  ExactProfile profile;
};

/// Left (X < Xc) at rest with stretch sL < 1, right natural state at rest; a C− fan
/// runs left, a C+ shock right. The star stretch solves φ_fan(s) = φ_shock(s) by
/// bisection on s in [sL, 1]. Valid until a wave reaches an end of [0, l0].
inline ShockTubeExact shock_tube_exact(double rho, double V, double sL, double Xc, double l0, double t) {
  ShockTubeExact r;
  r.stretch_left = sL;
  r.stretch_right = 1.0;
  double lo = sL, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double fan = V * std::log(mid / sL);  // φ on the fan, φL = 0
    (fan - css_shock_rapidity(rho, V, mid) < 0.0 ? lo : hi) = mid;
  }
  r.stretch_star = 0.5 * (lo + hi);
  const double phi = css_shock_rapidity(rho, V, r.stretch_star);
  r.shock_speed = std::tanh(phi) / (1.0 - r.stretch_star / std::cosh(phi));  // m = v*/(1 − s*/γ*)
  r.fan = ConstantSoundSpeedFan{V, 0.0, sL, 0.0, Xc, t};
  r.fan.rapidity_tail = r.fan.rapidity(r.stretch_star);  // = φ behind the shock
  const double head = r.fan.head(), tail = r.fan.tail(), shock = Xc + t * r.shock_speed;
  r.profile = {{0.0, head, sL}, {head, tail, 0.0, r.fan}, {tail, shock, r.stretch_star}, {shock, l0, 1.0}};
  return r;
}

// =====================================================================================
// the L1 distance

namespace detail {

/// ∫ |c − s(X)| dX over [a, b] where s − c keeps its sign: composite 8-point
/// Gauss–Legendre on panels no wider than 1e-3 (s is analytic inside the fan).
inline double fan_integral(const ConstantSoundSpeedFan& fan, double c, double a, double b) {
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
  return std::abs(sum);
}

/// ∫ |c − s(X)| dX over [a, b] inside the fan: split where s crosses c (s increases with X).
inline double fan_l1(const ConstantSoundSpeedFan& fan, double c, double a, double b) {
  const double phi = fan.rapidity(c);
  if (phi > fan.rapidity_left && phi < fan.rapidity_tail) {
    const double crossing = fan.label(phi);
    if (crossing > a && crossing < b) return fan_integral(fan, c, a, crossing) + fan_integral(fan, c, crossing, b);
  }
  return fan_integral(fan, c, a, b);
}

}  // namespace detail

/// ∫ |s_h − s| dX of a piecewise-constant numerical profile s_h (pieces sorted, covering
/// the body) against an exact one, integrated exactly piece by piece: constants in
/// closed form, the fan by Gauss–Legendre on either side of the crossing.
inline double l1_distance(const std::vector<Piece>& numerical, const ExactProfile& exact) {
  double sum = 0.0;
  std::size_t j = 0;
  for (const Piece& p : numerical) {
    while (j < exact.size() && exact[j].X1 <= p.X0) ++j;
    for (std::size_t k = j; k < exact.size() && exact[k].X0 < p.X1; ++k) {
      const double a = std::max(p.X0, exact[k].X0), b = std::min(p.X1, exact[k].X1);
      if (!(b > a)) continue;
      sum += exact[k].fan ? detail::fan_l1(*exact[k].fan, p.value, a, b) : std::abs(p.value - exact[k].value) * (b - a);
    }
  }
  return sum;
}

}  // namespace rigidity::work_precision
