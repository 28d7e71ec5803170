#pragma once
/// The Riemann problem of Newtonian elastodynamics for any stress–strain law, by Wendroff's hull
/// construction: the Newtonian limit (v ≪ c, |σ| ≪ ρ00 c²) that Berjamin, Lombard, Chiavassa &
/// Favrie (arXiv 1608.02721) solve for laws with an inflection (hyperbola, tanh, polynomial). An
/// independent reference for the tests: it shares no code with solvers/ or materials/, nor with
/// exact/nonconvex_riemann.hpp (Liu's construction for the relativistic system).
///
/// In labels X, strain ε = s − 1 and velocity v, the system is ε_t = v_X, ρ v_t = σ(ε)_X with
/// σ' > 0. Characteristics run at ∓√(σ'/ρ); a shock between ε_a and ε_b at ∓√([σ]/[ε]/ρ). Along
/// a C− wave dv = √(σ'/ρ) dε, along a C+ wave dv = −√(σ'/ρ) dε, and across a shock the same with
/// the chord's slope. A wave's pieces run ever slower from its outer state inward (Liu's
/// condition), so the slope of the path it follows in the (ε, σ) plane never grows from the
/// outer strain to the star strain: the least concave majorant of σ over the interval where the
/// star strain is larger (the wave stretches), the greatest convex minorant where it is smaller.
/// Where that envelope is σ itself the wave is a fan; where it is a chord, a shock, attached
/// to the fan next to it at the point where the chord is tangent (a sonic point).
///
/// The envelope is the hull of σ sampled at kHullPoints strains across the wave (Andrew's
/// monotone chain), so a fan is a chain of chords kHullPoints⁻¹ of the wave wide: the star
/// velocity and the states inside a fan are exact to second order in that width, a sonic point
/// to first order.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace rigidity::exact::newtonian {

inline constexpr int kHullPoints = 20001;

/// σ(ε) with σ' > 0 on [min_strain, max_strain], and the mass density per label ρ.
struct Law {
  std::function<double(double)> sigma;
  double rho = 1.0;
  double min_strain = -0.5, max_strain = 0.5;
};

struct State {
  double strain = 0.0, velocity = 0.0;
};

/// One wave: the envelope's vertices from the outer strain to the star strain.
struct Wave {
  int family = -1;  ///< −1: into the left state (C−); +1: into the right state (C+)
  State outer;
  std::vector<double> strain, stress;  ///< the envelope's vertices, outer first
  double rho = 1.0;

  /// √(slope / ρ) of the envelope's edge k (between vertices k and k + 1).
  [[nodiscard]] double speed(std::size_t k) const {
    return std::sqrt((stress[k + 1] - stress[k]) / (strain[k + 1] - strain[k]) / rho);
  }
  /// The velocity behind the wave: dv = −family √(slope/ρ) dε along the envelope.
  [[nodiscard]] double star_velocity() const {
    double v = outer.velocity;
    for (std::size_t k = 0; k + 1 < strain.size(); ++k) v -= family * speed(k) * (strain[k + 1] - strain[k]);
    return v;
  }
  [[nodiscard]] State star() const { return State{strain.back(), star_velocity()}; }
  /// The edges wider than `chord` (in strain) are shocks; the rest is fan. "S", "R", "RS", ...
  [[nodiscard]] std::string pattern(double chord) const {
    std::string out;
    for (std::size_t k = 0; k + 1 < strain.size(); ++k) {
      const char piece = std::abs(strain[k + 1] - strain[k]) > chord ? 'S' : 'R';
      if (out.empty() || out.back() != piece || piece == 'S') out += piece;
    }
    return out;
  }
  /// The state at ξ = X/t (on the wave's side of the centre): the outer state ahead of the
  /// fastest edge, then the vertex where the edges' speeds fall below |ξ|; inside a fan (two
  /// short edges either side of that vertex) between the edges' midpoints, where the chords'
  /// slopes are σ' to second order in their width, in proportion to the speed.
  [[nodiscard]] State at(double xi) const {
    double v = outer.velocity;
    const double fan_edge = 1e-3 * std::abs(strain.back() - strain.front());
    for (std::size_t k = 0; k + 1 < strain.size(); ++k) {
      const double dv = -family * speed(k) * (strain[k + 1] - strain[k]);
      if (speed(k) < std::abs(xi)) {
        if (k == 0 || std::abs(strain[k + 1] - strain[k]) > fan_edge || std::abs(strain[k] - strain[k - 1]) > fan_edge)
          return State{strain[k], v};
        // Between the midpoints of edges k − 1 and k: w = 0 at the first, 1 at the second.
        const double w = (speed(k - 1) - std::abs(xi)) / (speed(k - 1) - speed(k));
        const double e = 0.5 * (strain[k - 1] + strain[k]) + w * 0.5 * (strain[k + 1] - strain[k - 1]);
        return State{e, v - family * (w < 0.5 ? speed(k - 1) : speed(k)) * (e - strain[k])};
      }
      v += dv;
    }
    return State{strain.back(), v};
  }
};

/// The wave of `family` from `outer` to the star strain.
inline Wave build_wave(const Law& law, const State& outer, int family, double star_strain) {
  Wave w;
  w.family = family;
  w.outer = outer;
  w.rho = law.rho;
  const bool stretching = star_strain > outer.strain;
  const double lo = std::min(outer.strain, star_strain), hi = std::max(outer.strain, star_strain);
  std::vector<double> e, s;
  for (int i = 0; i < kHullPoints; ++i) {
    const double x = i == kHullPoints - 1 ? hi : lo + (hi - lo) * i / (kHullPoints - 1);
    const double y = law.sigma(x);
    // Upper hull (least concave majorant) when stretching, lower hull otherwise: drop the last
    // vertex while it lies on the wrong side of (or on) the line from the one before to x.
    while (e.size() >= 2) {
      const std::size_t n = e.size();
      const double cross = (e[n - 1] - e[n - 2]) * (y - s[n - 2]) - (s[n - 1] - s[n - 2]) * (x - e[n - 2]);
      if (stretching ? cross >= 0.0 : cross <= 0.0) {
        e.pop_back();
        s.pop_back();
      } else {
        break;
      }
    }
    e.push_back(x);
    s.push_back(y);
  }
  if (!stretching) {  // outer first: the outer strain is the larger
    std::reverse(e.begin(), e.end());
    std::reverse(s.begin(), s.end());
  }
  w.strain = std::move(e);
  w.stress = std::move(s);
  return w;
}

struct Solution {
  Wave left, right;
  /// The state at ξ = X/t.
  [[nodiscard]] State at(double xi) const { return xi < 0.0 ? left.at(xi) : right.at(xi); }
};

/// The star strain where the velocities behind the two waves agree (the left's rises with it, the
/// right's falls), by bisection over the law's range.
inline Solution riemann_problem(const Law& law, const State& left, const State& right) {
  const auto mismatch = [&](double strain) {
    return build_wave(law, left, -1, strain).star_velocity() - build_wave(law, right, +1, strain).star_velocity();
  };
  double lo = law.min_strain, hi = law.max_strain;
  for (int i = 0; i < 100 && hi - lo > 1e-15 * (1.0 + std::abs(lo)); ++i) {
    const double middle = 0.5 * (lo + hi);
    (mismatch(middle) < 0.0 ? lo : hi) = middle;
  }
  const double star = 0.5 * (lo + hi);
  return Solution{build_wave(law, left, -1, star), build_wave(law, right, +1, star)};
}

}  // namespace rigidity::exact::newtonian
