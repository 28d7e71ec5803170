#pragma once
/// Plain bisection for the independent references: nothing clever, so that nothing in
/// it can share a mistake with the solvers' bracketing and Brent iterations.

#include <cmath>
#include <limits>

namespace rigidity::exact {

/// A root of f in [lo, hi], where f(lo) and f(hi) have opposite signs (or one is zero),
/// halved until the bracket is as narrow as the arithmetic allows: adjacent numbers, a
/// relative width of 2 ε, or an absolute width of `floor`. NaN if the signs do not bracket.
template <class Real, class F>
Real bisect(const F& f, Real lo, Real hi, Real floor = Real(0)) {
  const Real eps = std::numeric_limits<Real>::epsilon();
  Real f_lo = f(lo);
  const Real f_hi = f(hi);
  if (f_lo == Real(0)) return lo;
  if (f_hi == Real(0)) return hi;
  if ((f_lo < Real(0)) == (f_hi < Real(0))) return std::numeric_limits<Real>::quiet_NaN();
  for (int i = 0; i < 4000; ++i) {
    const Real mid = lo + (hi - lo) / Real(2);
    if (mid <= std::fmin(lo, hi) || mid >= std::fmax(lo, hi)) break;
    const Real width = std::fabs(hi - lo);
    if (width <= Real(2) * eps * std::fmax(std::fabs(lo), std::fabs(hi)) || width <= floor) break;
    const Real f_mid = f(mid);
    if (f_mid == Real(0)) return mid;
    if ((f_mid < Real(0)) == (f_lo < Real(0))) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  return lo + (hi - lo) / Real(2);
}

}  // namespace rigidity::exact
