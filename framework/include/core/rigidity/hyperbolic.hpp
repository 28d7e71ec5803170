#pragma once
/// sinh φ, cosh φ, e^±φ and tanh φ of a rapidity from one exponential.
///
/// Below |φ| = 1 from expm1, so that sinh φ keeps full relative precision near 0; above,
/// from exp; beyond |φ| = 700, where e^φ overflows, from the library's sinh and cosh
/// (infinite there as well, with e^±φ at their limits).

#include <cmath>

namespace rigidity {

struct Hyperbolic {
  double sinh = 0.0, cosh = 1.0;
  double ep = 1.0, em = 1.0;  ///< e^φ, e^−φ
};

[[nodiscard]] inline Hyperbolic hyperbolic(double phi) {
  Hyperbolic h;
  const double a = std::abs(phi);
  if (a < 1.0) {
    const double u = std::expm1(phi);
    h.ep = 1.0 + u;
    h.em = 1.0 / h.ep;
    h.sinh = 0.5 * u * (u + 2.0) / (1.0 + u);
    h.cosh = 1.0 + 0.5 * u * u / (1.0 + u);
  } else if (a < 700.0) {
    h.ep = std::exp(phi);
    h.em = 1.0 / h.ep;
    h.sinh = 0.5 * (h.ep - h.em);
    h.cosh = 0.5 * (h.ep + h.em);
  } else {
    h.ep = std::exp(phi);
    h.em = std::exp(-phi);
    h.sinh = std::sinh(phi);
    h.cosh = std::cosh(phi);
  }
  return h;
}

/// tanh φ (the velocity of rapidity φ) from h = hyperbolic(φ); the library's beyond
/// |φ| = 300, where sinh φ / cosh φ would be inf / inf.
[[nodiscard]] inline double velocity_of(double phi, const Hyperbolic& h) {
  return std::abs(phi) < 300.0 ? h.sinh / h.cosh : std::tanh(phi);
}

}  // namespace rigidity
