#include "rigidity/numeric_material.hpp"

#include <gsl/gsl_deriv.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigidity/errors.hpp"

namespace rigidity {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

/// Relative accuracy asked of the quadrature of the work ∫ p ds in W = ρ00 − ∫ p ds (GSL's
/// error estimate is pessimistic: the result is good to ~1e-15).
constexpr double kWorkRelTol = 1e-12;
/// Initial step in ln s of the central differences (GSL then picks the optimal step).
constexpr double kDerivativeStep = 1e-2;
/// Step in ln s of the second differences: balances rounding ε|W|/h² against truncation h⁴.
constexpr double kSecondDerivativeStep = 4e-3;
/// Relative accuracy of c_s each kind of numeric material reaches (see the header).
constexpr double kPressureLawSoundSpeedAccuracy = 1e-10;
constexpr double kStrainEnergySoundSpeedAccuracy = 1e-6;
/// Subintervals a quadrature may use.
constexpr std::size_t kQuadratureLimit = 200;
/// Brent iterations before a root find is reported as not converged.
constexpr int kMaxRootIterations = 200;
/// First step, in ln s, of the bracket grown from s = 1; it grows fourfold each time.
constexpr double kFirstBracketStep = 0.125;

/// GSL's default error handler aborts; numeric materials report every failure as a Status.
void disable_gsl_abort_handler() {
  static const bool disabled = [] {
    gsl_set_error_handler_off();
    return true;
  }();
  static_cast<void>(disabled);
}

/// A gsl_function calling f (which must outlive it).
template <class F>
gsl_function gsl_function_of(F& f) {
  gsl_function g;
  g.function = [](double x, void* params) -> double { return (*static_cast<F*>(params))(x); };
  g.params = &f;
  return g;
}

/// Quadrature workspaces per thread, one per nesting level (Ψ integrates c_s, and c_s of a
/// PressureLawMaterial integrates p), allocated once.
class ScopedWorkspace {
 public:
  ScopedWorkspace() : pool_(thread_pool()) {
    if (pool_.depth == pool_.levels.size()) {
      gsl_integration_workspace* w = gsl_integration_workspace_alloc(kQuadratureLimit);
      if (w == nullptr) throw std::bad_alloc();
      pool_.levels.push_back(w);
    }
    workspace_ = pool_.levels[pool_.depth++];
  }
  ~ScopedWorkspace() { --pool_.depth; }
  ScopedWorkspace(const ScopedWorkspace&) = delete;
  ScopedWorkspace& operator=(const ScopedWorkspace&) = delete;

  [[nodiscard]] gsl_integration_workspace* get() const { return workspace_; }

 private:
  struct Pool {
    std::vector<gsl_integration_workspace*> levels;
    std::size_t depth = 0;
    Pool() = default;
    Pool(const Pool&) = delete;
    Pool& operator=(const Pool&) = delete;
    ~Pool() {
      for (gsl_integration_workspace* w : levels) gsl_integration_workspace_free(w);
    }
  };
  static Pool& thread_pool() {
    thread_local Pool pool;
    return pool;
  }

  Pool& pool_;
  gsl_integration_workspace* workspace_ = nullptr;
};

/// ∫_a^b f by GSL QAG (21-point Gauss–Kronrod, adaptive); not_converged if GSL cannot meet
/// max(epsabs, epsrel |∫f|).
template <class F>
Solved<Estimate> integrate(F& f, double a, double b, double epsabs, double epsrel) {
  if (a == b) return {Estimate{0.0, 0.0}};
  ScopedWorkspace workspace;
  const gsl_function g = gsl_function_of(f);
  double result = 0.0;
  double abserr = 0.0;
  const int status = gsl_integration_qag(&g, a, b, epsabs, epsrel, kQuadratureLimit, GSL_INTEG_GAUSS21, workspace.get(),
                                         &result, &abserr);
  if (status != GSL_SUCCESS || !std::isfinite(result)) return Solved<Estimate>::failure(Status::not_converged);
  return {Estimate{result, abserr}};
}

/// df/dx at x by GSL's central difference with step control.
template <class F>
Solved<Estimate> differentiate(F& f, double x) {
  const gsl_function g = gsl_function_of(f);
  double result = 0.0;
  double abserr = 0.0;
  const int status = gsl_deriv_central(&g, x, kDerivativeStep, &result, &abserr);
  if (status != GSL_SUCCESS || !std::isfinite(result) || !std::isfinite(abserr))
    return Solved<Estimate>::failure(Status::not_converged);
  return {Estimate{result, abserr}};
}

/// d²f/dx² at x by the fourth-order central difference
///   D(h) = [−f(x+2h) + 16 f(x+h) − 30 f(x) + 16 f(x−h) − f(x−2h)] / (12 h²),
/// with its error estimated from D(2h) (truncation, ∝ h⁴) and from ε|f| (rounding, ∝ 1/h²).
template <class F>
Solved<Estimate> second_derivative(F& f, double x) {
  const double h = kSecondDerivativeStep;
  double values[9];  // f(x + k h), k = −4..4
  double largest = 0.0;
  for (int k = -4; k <= 4; ++k) {
    values[k + 4] = f(x + k * h);
    if (!std::isfinite(values[k + 4])) return Solved<Estimate>::failure(Status::not_converged);
    largest = std::max(largest, std::abs(values[k + 4]));
  }
  auto at = [&](int k) { return values[k + 4]; };
  auto stencil = [&](int m) {  // D(m h)
    const double step = m * h;
    return (-at(2 * m) + 16.0 * at(m) - 30.0 * at(0) + 16.0 * at(-m) - at(-2 * m)) / (12.0 * step * step);
  };
  const double fine = stencil(1);
  const double coarse = stencil(2);
  const double truncation = std::abs(fine - coarse) / 15.0;
  const double rounding = (64.0 / 12.0) * kEpsilon * largest / (h * h);
  return {Estimate{fine, truncation + rounding}};
}

/// A function of ln s that may fail: it records the first failure (or non-finite value) and
/// returns 0 from then on, so that GSL can be driven by it and the caller can report it after.
template <class G>
class Guarded {
 public:
  explicit Guarded(G g) : g_(std::move(g)) {}
  double operator()(double log_s) {
    if (status_ != Status::ok) return 0.0;
    const Solved<Estimate> r = g_(Stretch::from_log(log_s));
    if (!r.ok() || !std::isfinite(r.value.value)) {
      status_ = r.ok() ? Status::not_converged : r.status;
      return 0.0;
    }
    return r.value.value;
  }
  [[nodiscard]] Status status() const { return status_; }

 private:
  G g_;
  Status status_ = Status::ok;
};

/// The ln s in [log_min, log_max] at which the decreasing function g equals target, for
/// g(log_max) <= target <= g(log_min): a bracket grown from ln s = 0, then Brent's method.
template <class G>
Solved<Stretch> solve_decreasing(G g, double target, double log_min, double log_max) {
  Guarded<G> guarded(std::move(g));
  auto f = [&](double log_s) { return guarded(log_s) - target; };

  // Grow a bracket [near, far] from s = 1 towards the root, fourfold each step.
  double near = std::clamp(0.0, log_min, log_max);
  double f_near = f(near);
  if (guarded.status() != Status::ok) return Solved<Stretch>::failure(guarded.status());
  if (f_near == 0.0) return {Stretch::from_log(near)};
  const double direction = f_near > 0.0 ? 1.0 : -1.0;  // g decreases: above the target, go to larger s
  const double edge = direction > 0.0 ? log_max : log_min;
  double step = kFirstBracketStep;
  double far = near;
  double f_far = f_near;
  while (true) {
    far = direction > 0.0 ? std::min(near + step, edge) : std::max(near - step, edge);
    f_far = f(far);
    if (guarded.status() != Status::ok) return Solved<Stretch>::failure(guarded.status());
    if (f_far == 0.0) return {Stretch::from_log(far)};
    if ((f_far > 0.0) != (f_near > 0.0)) break;
    if (far == edge) return Solved<Stretch>::failure(Status::no_bracket);
    near = far;
    f_near = f_far;
    step *= 4.0;
  }

  std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), &gsl_root_fsolver_free);
  if (!solver) throw std::bad_alloc();
  gsl_function function = gsl_function_of(f);
  if (gsl_root_fsolver_set(solver.get(), &function, std::min(near, far), std::max(near, far)) != GSL_SUCCESS)
    return Solved<Stretch>::failure(Status::no_bracket);
  for (int iteration = 0; iteration < kMaxRootIterations; ++iteration) {
    const int status = gsl_root_fsolver_iterate(solver.get());
    if (guarded.status() != Status::ok) return Solved<Stretch>::failure(guarded.status());
    if (status != GSL_SUCCESS) return Solved<Stretch>::failure(Status::not_converged);
    const double lo = gsl_root_fsolver_x_lower(solver.get());
    const double hi = gsl_root_fsolver_x_upper(solver.get());
    // ln s to a few ulps: the law takes s as a double, so nothing finer is resolved.
    if (gsl_root_test_interval(lo, hi, kEpsilon, 4.0 * kEpsilon) == GSL_SUCCESS)
      return {Stretch::from_log(gsl_root_fsolver_root(solver.get()))};
  }
  return Solved<Stretch>::failure(Status::not_converged);
}

/// The value of r, or NumericalError naming what failed.
double value_or_throw(const Solved<Estimate>& r, std::string_view what, std::string_view model, Stretch s) {
  if (r.ok()) return r.value.value;
  throw NumericalError("material '" + std::string(model) + "': " + std::string(what) + " at stretch " +
                       std::to_string(s.value()) + ": " + std::string(to_string(r.status)));
}

}  // namespace

std::optional<Solved<Stretch>> NumericMaterial::outside_or_at_window_end(double target, const Estimate& highest,
                                                                         const Estimate& lowest) const {
  if (target > highest.value + highest.error || target < lowest.value - lowest.error)
    return Solved<Stretch>::failure(Status::out_of_range);
  // At or beyond the value at an end, but within its error: that end, to the accuracy there is.
  if (target >= highest.value) return Solved<Stretch>{Stretch::from_log(window_.log_min)};
  if (target <= lowest.value) return Solved<Stretch>{Stretch::from_log(window_.log_max)};
  return std::nullopt;
}

// ---- NumericMaterial -------------------------------------------------------------

NumericMaterial::NumericMaterial(double rest_density, StretchRange window, double sound_speed_accuracy)
    : Material(rest_density), window_(window), sound_speed_accuracy_(sound_speed_accuracy) {
  if (!std::isfinite(window.log_min) || !std::isfinite(window.log_max))
    throw std::invalid_argument("a numeric material needs a finite window of stretches");
  if (!(window.log_min <= 0.0 && window.log_max >= 0.0 && window.log_min < window.log_max))
    throw std::invalid_argument("the window of stretches of a numeric material must contain s = 1");
  disable_gsl_abort_handler();
}

StretchRange NumericMaterial::default_window() { return {std::log(1e-6), std::log(1e6)}; }

double NumericMaterial::strain_energy(Stretch s) const {
  return value_or_throw(strain_energy_estimate(s), "strain energy quadrature", model(), s);
}

double NumericMaterial::energy_density(Stretch s) const { return strain_energy(s) / s.value(); }

double NumericMaterial::stiffness(Stretch s) const {
  return value_or_throw(stiffness_estimate(s), "stiffness derivative", model(), s);
}

double NumericMaterial::sound_speed(Stretch s) const {
  return value_or_throw(sound_speed_estimate(s), "sound speed", model(), s);
}

double NumericMaterial::riemann_psi(Stretch s) const {
  return value_or_throw(riemann_psi_estimate(s), "Riemann invariant quadrature", model(), s);
}

Solved<Estimate> NumericMaterial::enthalpy_estimate(Stretch s) const {
  const Solved<Estimate> w = strain_energy_estimate(s);
  if (!w.ok()) return w;
  const Solved<Estimate> p = pressure_estimate(s);
  if (!p.ok()) return p;
  const double stretch = s.value();
  // s (e + p) = W + s p
  const double reduced = w.value.value + stretch * p.value.value;
  const double error = w.value.error + stretch * p.value.error +
                       kEpsilon * (std::abs(w.value.value) + std::abs(stretch * p.value.value));
  return {Estimate{reduced / stretch, error / stretch}};
}

Solved<Estimate> NumericMaterial::sound_speed_estimate(Stretch s) const {
  const Solved<Estimate> stiff = stiffness_estimate(s);
  if (!stiff.ok()) return stiff;
  const Solved<Estimate> enthalpy = enthalpy_estimate(s);
  if (!enthalpy.ok()) return enthalpy;
  const double curvature = stiff.value.value;    // W''
  const double e_plus_p = enthalpy.value.value;  // e + p
  if (!std::isfinite(curvature) || !std::isfinite(e_plus_p)) return Solved<Estimate>::failure(Status::not_converged);
  // e + p lost in its own error: c_s is undetermined, not a number to report.
  if (std::abs(e_plus_p) <= enthalpy.value.error) return Solved<Estimate>::failure(Status::not_converged);
  double square = s.value() * curvature / e_plus_p;  // c_s² = s W''/(e + p)  (SPEC §1)
  if (!(square > 0.0)) return {Estimate{0.0, 0.0}};  // not hyperbolic
  const double relative_error =
      stiff.value.error / std::abs(curvature) + enthalpy.value.error / std::abs(e_plus_p) + 4.0 * kEpsilon;
  if (square > 1.0 && square - 1.0 <= square * relative_error) square = 1.0;  // c, within the error
  const double speed = std::sqrt(square);
  return {Estimate{speed, 0.5 * speed * relative_error}};
}

Solved<Estimate> NumericMaterial::riemann_psi_estimate(Stretch s) const {
  if (s.log() == 0.0) return {Estimate{0.0, 0.0}};
  Guarded sound_speed_of([this](Stretch sigma) { return sound_speed_estimate(sigma); });
  // Ψ = ∫_s^1 c_s dσ/σ = ∫_{ln s}^0 c_s dτ  (SPEC §1)
  const Solved<Estimate> psi = integrate(sound_speed_of, s.log(), 0.0, 0.0, sound_speed_accuracy_);
  if (sound_speed_of.status() != Status::ok) return Solved<Estimate>::failure(sound_speed_of.status());
  return psi;
}

double NumericMaterial::max_pressure() const {
  const Stretch end = Stretch::from_log(window_.log_min);
  return value_or_throw(pressure_estimate(end), "pressure", model(), end);
}

double NumericMaterial::max_tension() const {
  const Stretch end = Stretch::from_log(window_.log_max);
  return value_or_throw(pressure_estimate(end), "pressure", model(), end);
}

double NumericMaterial::psi_max() const { return riemann_psi(Stretch::from_log(window_.log_min)); }

double NumericMaterial::psi_min() const { return riemann_psi(Stretch::from_log(window_.log_max)); }

Solved<Stretch> NumericMaterial::stretch_at_pressure(double p) const {
  if (!std::isfinite(p)) return Solved<Stretch>::failure(Status::out_of_range);
  const Solved<Estimate> highest = pressure_estimate(Stretch::from_log(window_.log_min));
  const Solved<Estimate> lowest = pressure_estimate(Stretch::from_log(window_.log_max));
  if (!highest.ok()) return Solved<Stretch>::failure(highest.status);
  if (!lowest.ok()) return Solved<Stretch>::failure(lowest.status);
  if (const auto settled = outside_or_at_window_end(p, highest.value, lowest.value)) return *settled;
  return solve_decreasing([this](Stretch s) { return pressure_estimate(s); }, p, window_.log_min, window_.log_max);
}

Solved<Stretch> NumericMaterial::stretch_at_psi(double psi) const {
  if (!std::isfinite(psi)) return Solved<Stretch>::failure(Status::out_of_range);
  const Solved<Estimate> highest = riemann_psi_estimate(Stretch::from_log(window_.log_min));
  const Solved<Estimate> lowest = riemann_psi_estimate(Stretch::from_log(window_.log_max));
  if (!highest.ok()) return Solved<Stretch>::failure(highest.status);
  if (!lowest.ok()) return Solved<Stretch>::failure(lowest.status);
  if (const auto settled = outside_or_at_window_end(psi, highest.value, lowest.value)) return *settled;
  return solve_decreasing([this](Stretch s) { return riemann_psi_estimate(s); }, psi, window_.log_min, window_.log_max);
}

// ---- PressureLawMaterial -------------------------------------------------------------

PressureLawMaterial::PressureLawMaterial(double rest_density, StretchRange window)
    : NumericMaterial(rest_density, window, kPressureLawSoundSpeedAccuracy) {}

Solved<Estimate> PressureLawMaterial::pressure_estimate(Stretch s) const {
  const double p = pressure(s);
  if (!std::isfinite(p)) return Solved<Estimate>::failure(Status::not_converged);  // the law gave no number
  return {Estimate{p, 0.0}};
}

Solved<Estimate> PressureLawMaterial::strain_energy_estimate(Stretch s) const {
  // W(s) = W(1) − ∫_1^s p dσ = ρ00 − ∫_0^{ln s} p(e^τ) e^τ dτ  (p = −W', SPEC §1)
  auto force_density = [this](double tau) {
    const double sigma = std::exp(tau);
    return pressure_law(sigma) * sigma;
  };
  const Solved<Estimate> work = integrate(force_density, 0.0, s.log(), kEpsilon * rest_density(), kWorkRelTol);
  if (!work.ok()) return work;
  const double w = rest_density() - work.value.value;
  return {Estimate{w, work.value.error + kEpsilon * std::abs(w)}};
}

Solved<Estimate> PressureLawMaterial::stiffness_estimate(Stretch s) const {
  // GSL sizes its step by the rounding error it expects, ε |f|. Near s = 1 a law rounds at
  // the scale of the terms that cancel in it, ~ε ρ00 (e.g. 1/s² − 1), not at ε |p| → 0:
  // differentiating ρ00 + p makes GSL expect that.
  auto offset_pressure_of_log = [this](double tau) { return rest_density() + pressure_law(std::exp(tau)); };
  const Solved<Estimate> slope = differentiate(offset_pressure_of_log, s.log());  // dp/d ln s = −s W''
  if (!slope.ok()) return slope;
  const double stretch = s.value();
  return {Estimate{-slope.value.value / stretch, slope.value.error / stretch}};
}

// ---- StrainEnergyMaterial ---------------------------------------------------------------

StrainEnergyMaterial::StrainEnergyMaterial(double rest_density, StretchRange window)
    : NumericMaterial(rest_density, window, kStrainEnergySoundSpeedAccuracy) {}

double StrainEnergyMaterial::pressure(Stretch s) const {
  return value_or_throw(pressure_estimate(s), "pressure derivative", model(), s);
}

Solved<Estimate> StrainEnergyMaterial::strain_energy_estimate(Stretch s) const {
  const double w = strain_energy_law(s.value());
  if (!std::isfinite(w)) return Solved<Estimate>::failure(Status::not_converged);  // the law gave no number
  return {Estimate{w, kEpsilon * std::abs(w)}};
}

Solved<Estimate> StrainEnergyMaterial::pressure_estimate(Stretch s) const {
  auto energy_of_log = [this](double tau) { return strain_energy_law(std::exp(tau)); };
  const Solved<Estimate> slope = differentiate(energy_of_log, s.log());  // dW/d ln s = s W' = −s p
  if (!slope.ok()) return slope;
  const double stretch = s.value();
  return {Estimate{-slope.value.value / stretch, slope.value.error / stretch}};
}

Solved<Estimate> StrainEnergyMaterial::stiffness_estimate(Stretch s) const {
  // s² W'' = d²W/dτ² − dW/dτ with τ = ln s. Differentiating the numerical p again would
  // amplify its error; the second derivative comes straight from W instead.
  auto energy_of_log = [this](double tau) { return strain_energy_law(std::exp(tau)); };
  const Solved<Estimate> curvature = second_derivative(energy_of_log, s.log());
  if (!curvature.ok()) return curvature;
  const Solved<Estimate> slope = differentiate(energy_of_log, s.log());
  if (!slope.ok()) return slope;
  const double square = s.value() * s.value();
  return {Estimate{(curvature.value.value - slope.value.value) / square,
                   (curvature.value.error + slope.value.error) / square}};
}

}  // namespace rigidity
