#pragma once
// Values that may fail and Brent's method on them: shared by the exact Riemann solver and the
// composite waves of laws that are not convex.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <limits>
#include <string_view>

#include "rigidity/material.hpp"
#include "rigidity/status.hpp"

namespace rigidity::solving {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr std::string_view kBrent = "Brent's method did not converge";

/// A value, or why it could not be computed.
template <class T>
struct Outcome {
  T value{};
  Status status = Status::ok;
  std::string_view what;               ///< with a failed status: the computation that failed
  const Material* material = nullptr;  ///< and the material it concerned
  [[nodiscard]] bool ok() const { return status == Status::ok; }
  /// The same failure, for a result of another type.
  template <class U>
  [[nodiscard]] Outcome<U> as() const {
    return Outcome<U>{U{}, status, what, material};
  }
};

/// A computed value.
template <class T>
Outcome<T> succeeded(T value) {
  return Outcome<T>{value, Status::ok, {}, nullptr};
}

/// A function of the material failed. out_of_range is the solver's own verdict on a physical
/// limit, reached through the limits the material declares; a function failing inside them is
/// a numerical failure, whatever status it gave.
template <class T>
Outcome<T> numerical_failure(Status status, std::string_view what, const Material& m) {
  return Outcome<T>{T{}, status == Status::out_of_range ? Status::not_converged : status, what, &m};
}

/// A function for Brent's method whose evaluation can fail (f returns Outcome<double>). The
/// first failure is kept, and that evaluation, like every later one, gives NaN, on which GSL
/// stops (GSL_EBADFUNC); the caller then reports failure(), never an iterate.
template <class F>
class Recording {
 public:
  explicit Recording(const F& f) : f_(&f) {}
  double operator()(double z) const {
    if (!failure_.ok()) return kNaN;
    const Outcome<double> r = (*f_)(z);
    if (!r.ok()) {
      failure_ = r;
      return kNaN;
    }
    return r.value;
  }
  [[nodiscard]] const Outcome<double>& failure() const { return failure_; }

 private:
  const F* f_;
  mutable Outcome<double> failure_;
};

/// Brent's method (GSL) on a bracket where f changes sign; converged to round-off in z, or to
/// `absolute` if that is larger. A failed evaluation of f ends it with that failure.
template <class F>
Outcome<double> find_root(const F& f, double lo, double hi, const Material& m, double absolute = 1.0e-300) {
  gsl_set_error_handler_off();
  const Recording<F> recording(f);
  gsl_function fn{[](double z, void* params) { return (*static_cast<const Recording<F>*>(params))(z); },
                  const_cast<Recording<F>*>(&recording)};
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (solver == nullptr) return numerical_failure<double>(Status::not_converged, kBrent, m);
  Outcome<double> result = numerical_failure<double>(Status::not_converged, kBrent, m);
  if (gsl_root_fsolver_set(solver, &fn, lo, hi) == GSL_SUCCESS) {
    for (int iter = 0; iter < 300; ++iter) {
      if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS) break;
      const double a = gsl_root_fsolver_x_lower(solver), b = gsl_root_fsolver_x_upper(solver);
      const double root = gsl_root_fsolver_root(solver);
      if (gsl_root_test_interval(a, b, absolute, 2.0 * std::numeric_limits<double>::epsilon()) == GSL_SUCCESS ||
          recording(root) == 0.0) {
        result = succeeded<double>(root);
        break;
      }
    }
  }
  gsl_root_fsolver_free(solver);
  if (!recording.failure().ok()) return recording.failure();
  return result;
}

}  // namespace rigidity::solving
