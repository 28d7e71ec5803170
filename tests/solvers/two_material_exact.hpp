#pragma once
// An independent exact solution for tests: a rigid state (rest density ρa, rapidity
// φ0, unstrained) meeting a hooke state (rest density ρb, wave speed b) at rest and
// unstrained. The star pressure solves φ_L(p) = φ_R(p) by plain bisection on p:
//   rigid:  φ = φ0 − ½ ln(1 + 2p/ρa)        (J+ carried, Ψ = −ln s, s⁻² = 1 + 2p/ρa)
//   hooke:  φ = asinh(b/a) − asinh(b s(p)/a), s(p) from e(s)/R(s) − ρb = p.
#include <cmath>

namespace rigidity {

struct ExactStar {
  double pressure;
  double velocity;
};

inline ExactStar rigid_on_hooke_star(double rho_a, double phi0, double rho_b, double b) {
  const double a = std::sqrt(1.0 - b * b);
  auto hooke_stretch = [&](double p) {
    double lo = -30.0, hi = 0.0;  // ln s
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi), s = std::exp(mid);
      const double R = std::sqrt(b * b + a * a / (s * s));
      const double e = rho_b * (R - b * b) / (a * a);
      (e / R - rho_b > p ? lo : hi) = mid;
    }
    return std::exp(0.5 * (lo + hi));
  };
  auto mismatch = [&](double p) {
    const double left = phi0 - 0.5 * std::log1p(2.0 * p / rho_a);
    const double right = std::asinh(b / a) - std::asinh(b * hooke_stretch(p) / a);
    return left - right;
  };
  double lo = 0.0, hi = rho_b * b * b / (a * a) * (1.0 - 1e-12);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mismatch(mid) > 0.0 ? lo : hi) = mid;
  }
  const double p = 0.5 * (lo + hi);
  return ExactStar{p, std::tanh(phi0 - 0.5 * std::log1p(2.0 * p / rho_a))};
}

}  // namespace rigidity
