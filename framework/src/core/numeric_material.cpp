#include "rigidity/numeric_material.hpp"

#include <gsl/gsl_deriv.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigidity/chebyshev.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/number_text.hpp"

namespace rigidity {
namespace {

/// ∫_0^τ of panel k of `f` by the 8-point Gauss–Legendre rule (exact for degree 15; the panel's
/// polynomial is smooth on the short stretch from s = 1).
double gauss_legendre_of_panel(const PiecewiseChebyshev& f, std::size_t k, double tau) {
  constexpr std::size_t kPoints = 8;
  static const std::unique_ptr<gsl_integration_glfixed_table, decltype(&gsl_integration_glfixed_table_free)> rule(
      gsl_integration_glfixed_table_alloc(kPoints), &gsl_integration_glfixed_table_free);
  double sum = 0.0;
  for (std::size_t i = 0; i < kPoints; ++i) {
    double x = 0.0;
    double weight = 0.0;
    gsl_integration_glfixed_point(0.0, tau, i, &x, &weight, rule.get());
    sum += weight * f.on_panel(k, x);
  }
  return sum;
}

}  // namespace

namespace detail {

/// The tables of a numeric material (see the header), all in τ = ln s over its window, all on
/// the same panels (but psi_inverse's, in Ψ).
struct NumericTables {
  PiecewiseChebyshev w;                    ///< W(τ)
  PiecewiseChebyshev w_t;                  ///< dW/dτ = −s p
  PiecewiseChebyshev w_tt;                 ///< d²W/dτ²
  PiecewiseChebyshev curvature;            ///< s² W'' = W_ττ − W_τ
  PiecewiseChebyshev inertia;              ///< s (e + p) = W − W_τ
  PiecewiseChebyshev cs;                   ///< c_s(τ)
  PiecewiseChebyshev psi;                  ///< Ψ(τ) = −∫_0^τ c_s
  std::vector<double> pressure_at_breaks;  ///< p at the panel ends (as pressure() gives it)
  std::vector<double> psi_at_breaks;       ///< Ψ at the panel ends (as riemann_psi() gives it)
  double pressure_accuracy = 0.0;          ///< error of p, in units of e (0: p is the law itself)
  /// Ψ(τ)/τ on the panel that ends at s = 1 and on the one that starts there (empty if none).
  PiecewiseChebyshev psi_over_tau_below;
  PiecewiseChebyshev psi_over_tau_above;
  /// τ(Ψ), ascending in Ψ: the first guess of stretch_at_psi; empty if Ψ does not decrease
  /// strictly (a window reaching where the law is not hyperbolic), and then the secant through
  /// the bracket is. (p's inverse is not tabulated: over p's range, which may span 20 decades
  /// and end flat, it costs more to build than it saves.)
  PiecewiseChebyshev psi_inverse;

  /// An estimate of p at panel end `i`, with its error: to tell a target just beyond a window end
  /// by rounding from one that is out of range.
  [[nodiscard]] Estimate pressure_at_end(std::size_t i) const {
    const double tau = w.breaks()[i];
    const double p = pressure_at_breaks[i];
    return {p,
            4.0 * std::numeric_limits<double>::epsilon() * std::abs(p) + pressure_accuracy * w(tau) * std::exp(-tau)};
  }

  /// s² W'' = d²W/dτ² − dW/dτ on panel k.
  [[nodiscard]] double stiffness_times_square(std::size_t k, double tau) const { return curvature.on_panel(k, tau); }
  /// c_s² = s W''/(e + p) = (W_ττ − W_τ)/(W − W_τ) on panel k.
  [[nodiscard]] double sound_speed_squared(std::size_t k, double tau) const {
    return curvature.on_panel(k, tau) / inertia.on_panel(k, tau);
  }
  /// Ψ(τ). On the two panels beside s = 1, where Ψ → 0 and the antiderivative would keep only
  /// its absolute precision, as τ (Ψ/τ), which keeps the relative precision.
  [[nodiscard]] double riemann_psi(double tau) const {
    if (tau == 0.0) return 0.0;
    const std::size_t k = psi.panel_of(tau);
    if (!psi_over_tau_above.empty() && psi.breaks()[k] == 0.0) return tau * psi_over_tau_above(tau);
    if (!psi_over_tau_below.empty() && psi.breaks()[k + 1] == 0.0) return tau * psi_over_tau_below(tau);
    return psi.on_panel(k, tau);
  }

  /// p = −W_τ/s from the table (StrainEnergyMaterial).
  [[nodiscard]] double pressure(double tau) const { return -w_t(tau) * std::exp(-tau); }

  /// c_s and Ψ from w, w_t, w_tt, and Ψ at the panel ends; false if c_s is not a number somewhere.
  [[nodiscard]] bool complete() {
    curvature = PiecewiseChebyshev::combination(1.0, w_tt, -1.0, w_t);
    inertia = PiecewiseChebyshev::combination(1.0, w, -1.0, w_t);
    const auto speed = [this](double tau) {
      const double square = sound_speed_squared(w.panel_of(tau), tau);
      return square > 0.0 ? std::sqrt(square) : 0.0;  // 0 where not hyperbolic
    };
    Solved<PiecewiseChebyshev> speeds = PiecewiseChebyshev::sample(w.breaks(), speed);
    if (!speeds.ok()) return false;
    cs = std::move(speeds.value);
    psi = cs.integral(0.0).affine(-1.0, 0.0);  // Ψ = ∫_τ^0 c_s  (docs/physics.md)
    // Beside s = 1: Ψ/τ = −(1/τ) ∫_0^τ c_s by Gauss–Legendre quadrature of the c_s table on
    // the panel, −c_s(0) at τ = 0.
    const std::vector<double>& b = psi.breaks();
    for (std::size_t k = 0; k < psi.panels(); ++k) {
      if (b[k] != 0.0 && b[k + 1] != 0.0) continue;
      const auto ratio = [this, k](double tau) {
        if (tau == 0.0) return -cs.on_panel(k, 0.0);
        return -gauss_legendre_of_panel(cs, k, tau) / tau;
      };
      Solved<PiecewiseChebyshev> near = PiecewiseChebyshev::sample({b[k], b[k + 1]}, ratio);
      if (!near.ok()) return false;
      (b[k] == 0.0 ? psi_over_tau_above : psi_over_tau_below) = std::move(near.value);
    }
    for (const double end : b) psi_at_breaks.push_back(riemann_psi(end));
    build_inverse();
    return true;
  }

  /// The τ at which Ψ = psi, on panel k, whose ends bracket it: Newton from psi_inverse's guess.
  [[nodiscard]] Solved<double> log_stretch_at_psi(std::size_t k, double target) const;
  /// Builds psi_inverse.
  void build_inverse();
};

}  // namespace detail

namespace {

using detail::NumericTables;

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
/// The relative tolerances the tables try in turn: a law that rounds more coarsely than the
/// first (an iteration inside it, say) needs too many panels for it, and gets the next.
constexpr double kTableTolerances[] = {1e-14, 1e-12, 1e-10};
/// Error of p = −W' from the derivative of a StrainEnergyMaterial's table, in units of e
/// (measured ~1e-13 for smooth laws; tests/core/numeric_material_test.cpp).
constexpr double kStrainEnergyTablePressureAccuracy = 1e-11;
/// Newton iterations of the inverses on the tables before they report not_converged.
constexpr int kMaxNewtonIterations = 100;

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

/// The panel ends of a window's tables: its ends, s = 1, and the law's own breaks inside it.
std::vector<double> table_breaks(StretchRange window, std::vector<double> law_breaks) {
  std::vector<double> breaks{window.log_min, window.log_max};
  if (window.log_min < 0.0 && window.log_max > 0.0) breaks.push_back(0.0);
  for (const double b : law_breaks)
    if (b > window.log_min && b < window.log_max) breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  return breaks;
}

/// f tabulated on `breaks` to the first tolerance it meets; failure if it gives no number. A
/// law with many breaks (a table of many rows: each row is one) may use a few panels per break.
Solved<PiecewiseChebyshev> tabulate_law(const std::vector<double>& breaks, const std::function<double(double)>& f) {
  for (const double tolerance : kTableTolerances) {
    PiecewiseChebyshev::Refinement refinement;
    refinement.rel_tol = tolerance;
    refinement.max_panels = std::max(refinement.max_panels, 4 * breaks.size());
    Solved<PiecewiseChebyshev> table = PiecewiseChebyshev::adapt(breaks, f, refinement);
    if (table.ok()) return table;
  }
  return Solved<PiecewiseChebyshev>::failure(Status::not_converged);
}

/// The τ in [lo, hi] at which the decreasing g equals target, for g(lo) = g_lo >= target >=
/// g(hi) = g_hi: Newton steps with the slope dg from `guess` (the secant through the bracket if
/// it is not inside it), kept inside the bracket (bisection where a step would leave it), to
/// ln s within a few ulps, as the direct root find.
template <class G, class D>
Solved<double> solve_decreasing_newton(G g, D dg, double target, double lo, double hi, double g_lo, double g_hi,
                                       double guess) {
  auto resolved = [](double a, double b) { return std::abs(a - b) <= kEpsilon + 4.0 * kEpsilon * std::abs(a); };
  if (g_lo == target) return {lo};
  if (g_hi == target) return {hi};
  if (!(g_lo > target && g_hi < target)) return Solved<double>::failure(Status::no_bracket);
  double x = guess > lo && guess < hi ? guess : lo + (hi - lo) * (g_lo - target) / (g_lo - g_hi);
  for (int iteration = 0; iteration < kMaxNewtonIterations; ++iteration) {
    const double f = g(x) - target;
    if (!std::isfinite(f)) return Solved<double>::failure(Status::not_converged);
    if (f == 0.0) return {x};
    (f > 0.0 ? lo : hi) = x;
    double next = x - f / dg(x);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (resolved(next, x) || resolved(lo, hi)) return {next};
    x = next;
  }
  return Solved<double>::failure(Status::not_converged);
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The value of r, or NumericalError naming what failed.
double value_or_throw(const Solved<Estimate>& r, std::string_view what, std::string_view model, Stretch s) {
  if (r.ok()) return r.value.value;
  throw NumericalError("material '" + std::string(model) + "': " + std::string(what) + " at stretch " +
                       shortest(s.value()) + ": " + std::string(to_string(r.status)));
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

// ---- the tables' inverse of Ψ ----------------------------------------------------------

Solved<double> NumericTables::log_stretch_at_psi(std::size_t k, double target) const {
  const std::vector<double>& b = psi.breaks();
  const double guess = psi_inverse.empty() ? kNaN : psi_inverse(target);
  return solve_decreasing_newton([this](double tau) { return riemann_psi(tau); },
                                 [this, k](double tau) { return -cs.on_panel(k, tau); }, target, b[k], b[k + 1],
                                 psi_at_breaks[k], psi_at_breaks[k + 1], guess);
}

namespace {

/// τ(y) for a function y(τ) of the tables that decreases strictly across the panels, from its
/// values at the panel ends: each node a Newton solve from the secant on its panel. Empty if y
/// does not decrease strictly (a window reaching where the law is not hyperbolic).
template <class Value, class Slope>
PiecewiseChebyshev inverse_of(const std::vector<double>& breaks, const std::vector<double>& at_breaks, Value value,
                              Slope slope) {
  const std::vector<double> ends(at_breaks.rbegin(), at_breaks.rend());  // ascending y
  for (std::size_t i = 1; i < ends.size(); ++i)
    if (!(ends[i] > ends[i - 1])) return {};
  const auto tau_of = [&](double target) {
    const auto above = std::upper_bound(at_breaks.begin(), at_breaks.end(), target, std::greater<>());
    const std::size_t k =
        std::clamp<std::size_t>(static_cast<std::size_t>(above - at_breaks.begin()), 1, breaks.size() - 1) - 1;
    const Solved<double> tau = solve_decreasing_newton(
        value, [&](double t) { return slope(k, t); }, target, breaks[k], breaks[k + 1], at_breaks[k], at_breaks[k + 1],
        kNaN);
    return tau.ok() ? tau.value : kNaN;
  };
  PiecewiseChebyshev::Refinement refinement;
  refinement.rel_tol = 1e-13;
  refinement.max_width = std::numeric_limits<double>::infinity();  // y's units are not ln s's
  refinement.max_panels = 1024;                                    // a guess: not worth more
  Solved<PiecewiseChebyshev> inverse = PiecewiseChebyshev::adapt(ends, tau_of, refinement);
  return inverse.ok() ? std::move(inverse.value) : PiecewiseChebyshev();
}

}  // namespace

void NumericTables::build_inverse() {
  const std::vector<double>& b = psi.breaks();
  psi_inverse = inverse_of(
      b, psi_at_breaks, [this](double tau) { return riemann_psi(tau); },
      [this](std::size_t k, double tau) { return -cs.on_panel(k, tau); });
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

NumericMaterial::~NumericMaterial() = default;

const NumericTables* NumericMaterial::tables_at(Stretch s) const {
  const double tau = s.log();
  if (!(tau >= window_.log_min && tau <= window_.log_max)) return nullptr;
  std::call_once(tables_built_, [this] { tables_ = build_tables(); });
  return tables_.get();
}

double NumericMaterial::energy_density(Stretch s) const { return strain_energy(s) / s.value(); }

double NumericMaterial::stiffness(Stretch s) const {
  if (const NumericTables* t = tables_at(s)) {
    const double tau = s.log();
    return t->stiffness_times_square(t->w.panel_of(tau), tau) * std::exp(-2.0 * tau);  // W'' = (W_ττ − W_τ)/s²
  }
  return value_or_throw(stiffness_estimate(s), "stiffness derivative", model(), s);
}

double NumericMaterial::sound_speed(Stretch s) const {
  if (const NumericTables* t = tables_at(s)) {
    const double tau = s.log();
    double square = t->sound_speed_squared(t->w.panel_of(tau), tau);  // c_s² = s W''/(e + p)  (docs/physics.md)
    if (!(square > 0.0)) return 0.0;                                  // not hyperbolic
    if (square > 1.0 && square - 1.0 <= square * sound_speed_accuracy_) square = 1.0;  // c, within the accuracy
    return std::sqrt(square);
  }
  return value_or_throw(sound_speed_estimate(s), "sound speed", model(), s);
}

double NumericMaterial::riemann_psi(Stretch s) const {
  if (s.log() == 0.0) return 0.0;
  if (const NumericTables* t = tables_at(s)) return t->riemann_psi(s.log());
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
  double square = s.value() * curvature / e_plus_p;  // c_s² = s W''/(e + p)  (docs/physics.md)
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
  // Ψ = ∫_s^1 c_s dσ/σ = ∫_{ln s}^0 c_s dτ  (docs/physics.md)
  const Solved<Estimate> psi = integrate(sound_speed_of, s.log(), 0.0, 0.0, sound_speed_accuracy_);
  if (sound_speed_of.status() != Status::ok) return Solved<Estimate>::failure(sound_speed_of.status());
  return psi;
}

double NumericMaterial::max_pressure() const {
  const Stretch end = Stretch::from_log(window_.log_min);
  if (const NumericTables* t = tables_at(end)) return t->pressure_at_breaks.front();
  return value_or_throw(pressure_estimate(end), "pressure", model(), end);
}

double NumericMaterial::max_tension() const {
  const Stretch end = Stretch::from_log(window_.log_max);
  if (const NumericTables* t = tables_at(end)) return t->pressure_at_breaks.back();
  return value_or_throw(pressure_estimate(end), "pressure", model(), end);
}

double NumericMaterial::psi_max() const { return riemann_psi(Stretch::from_log(window_.log_min)); }

double NumericMaterial::psi_min() const { return riemann_psi(Stretch::from_log(window_.log_max)); }

Solved<Stretch> NumericMaterial::stretch_at_pressure(double p) const {
  if (!std::isfinite(p)) return Solved<Stretch>::failure(Status::out_of_range);
  if (const NumericTables* t = tables_at(Stretch::natural())) {
    // The panel whose ends bracket p (p decreases), then Newton on pressure() itself, with
    // dp/dτ = −s W'' from the tables, from the secant through the bracket.
    const std::vector<double>& at = t->pressure_at_breaks;
    if (const auto settled = outside_or_at_window_end(p, t->pressure_at_end(0), t->pressure_at_end(at.size() - 1)))
      return *settled;
    const auto above = std::upper_bound(at.begin(), at.end(), p, std::greater<>());  // first end with p(end) < p
    const std::size_t k = static_cast<std::size_t>(above - at.begin()) - 1;
    const std::vector<double>& breaks = t->w.breaks();
    const auto pressure_of = [this](double tau) { return pressure(Stretch::from_log(tau)); };
    const auto slope_of = [t, k](double tau) { return -t->stiffness_times_square(k, tau) * std::exp(-tau); };
    const Solved<double> tau =
        solve_decreasing_newton(pressure_of, slope_of, p, breaks[k], breaks[k + 1], at[k], at[k + 1], kNaN);
    if (!tau.ok()) return Solved<Stretch>::failure(tau.status);
    return {Stretch::from_log(tau.value)};
  }
  const Solved<Estimate> highest = pressure_estimate(Stretch::from_log(window_.log_min));
  const Solved<Estimate> lowest = pressure_estimate(Stretch::from_log(window_.log_max));
  if (!highest.ok()) return Solved<Stretch>::failure(highest.status);
  if (!lowest.ok()) return Solved<Stretch>::failure(lowest.status);
  if (const auto settled = outside_or_at_window_end(p, highest.value, lowest.value)) return *settled;
  return solve_decreasing([this](Stretch s) { return pressure_estimate(s); }, p, window_.log_min, window_.log_max);
}

Solved<Stretch> NumericMaterial::stretch_at_psi(double psi) const {
  if (!std::isfinite(psi)) return Solved<Stretch>::failure(Status::out_of_range);
  if (const NumericTables* t = tables_at(Stretch::natural())) {
    // The panel whose ends bracket Ψ (Ψ decreases), then Newton on the table, dΨ/dτ = −c_s,
    // from the inverse table's guess.
    const std::vector<double>& at = t->psi_at_breaks;
    const double margin = 4.0 * kEpsilon + sound_speed_accuracy_;  // relative, as c_s's
    const Estimate highest{at.front(), margin * std::abs(at.front())};
    const Estimate lowest{at.back(), margin * std::abs(at.back())};
    if (const auto settled = outside_or_at_window_end(psi, highest, lowest)) return *settled;
    const auto above = std::upper_bound(at.begin(), at.end(), psi, std::greater<>());
    const std::size_t k = static_cast<std::size_t>(above - at.begin()) - 1;
    const Solved<double> tau = t->log_stretch_at_psi(k, psi);
    if (!tau.ok()) return Solved<Stretch>::failure(tau.status);
    return {Stretch::from_log(tau.value)};
  }
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

double PressureLawMaterial::strain_energy(Stretch s) const {
  if (s.log() == 0.0) return rest_density();  // W(1) = ρ00, exactly
  if (const NumericTables* t = tables_at(s)) return t->w(s.log());
  return value_or_throw(strain_energy_estimate(s), "strain energy quadrature", model(), s);
}

std::unique_ptr<NumericTables> PressureLawMaterial::build_tables() const {
  // s p(s) in τ = ln s is −dW/dτ: its antiderivative gives W = ρ00 − ∫_0^τ s p dτ, its
  // derivative W_ττ.
  const std::vector<double> breaks = table_breaks(admissible(), law_breaks());
  Solved<PiecewiseChebyshev> force =
      tabulate_law(breaks, [this](double tau) { return pressure_law_at_log(tau) * std::exp(tau); });
  if (!force.ok()) return nullptr;
  auto t = std::make_unique<NumericTables>();
  t->w_t = force.value.affine(-1.0, 0.0);
  t->w_tt = t->w_t.derivative();
  t->w = force.value.integral(0.0).affine(-1.0, rest_density());
  for (const double b : t->w.breaks()) t->pressure_at_breaks.push_back(pressure_law_at_log(b));  // as pressure()
  if (!t->complete()) return nullptr;
  return t;
}

Solved<Estimate> PressureLawMaterial::pressure_estimate(Stretch s) const {
  const double p = pressure(s);
  if (!std::isfinite(p)) return Solved<Estimate>::failure(Status::not_converged);  // the law gave no number
  return {Estimate{p, 0.0}};
}

Solved<Estimate> PressureLawMaterial::strain_energy_estimate(Stretch s) const {
  // W(s) = W(1) − ∫_1^s p dσ = ρ00 − ∫_0^{ln s} p(e^τ) e^τ dτ  (p = −W', docs/physics.md)
  auto force_density = [this](double tau) { return pressure_law_at_log(tau) * std::exp(tau); };
  const Solved<Estimate> work = integrate(force_density, 0.0, s.log(), kEpsilon * rest_density(), kWorkRelTol);
  if (!work.ok()) return work;
  const double w = rest_density() - work.value.value;
  return {Estimate{w, work.value.error + kEpsilon * std::abs(w)}};
}

Solved<Estimate> PressureLawMaterial::stiffness_estimate(Stretch s) const {
  // GSL sizes its step by the rounding error it expects, ε |f|. Near s = 1 a law rounds at
  // the scale of the terms that cancel in it, ~ε ρ00 (e.g. 1/s² − 1), not at ε |p| → 0:
  // differentiating ρ00 + p makes GSL expect that.
  auto offset_pressure_of_log = [this](double tau) { return rest_density() + pressure_law_at_log(tau); };
  const Solved<Estimate> slope = differentiate(offset_pressure_of_log, s.log());  // dp/d ln s = −s W''
  if (!slope.ok()) return slope;
  const double stretch = s.value();
  return {Estimate{-slope.value.value / stretch, slope.value.error / stretch}};
}

// ---- StrainEnergyMaterial ---------------------------------------------------------------

StrainEnergyMaterial::StrainEnergyMaterial(double rest_density, StretchRange window)
    : NumericMaterial(rest_density, window, kStrainEnergySoundSpeedAccuracy) {}

double StrainEnergyMaterial::strain_energy(Stretch s) const {
  return value_or_throw(strain_energy_estimate(s), "strain energy law", model(), s);
}

double StrainEnergyMaterial::pressure(Stretch s) const {
  if (const NumericTables* t = tables_at(s)) return t->pressure(s.log());
  return value_or_throw(pressure_estimate(s), "pressure derivative", model(), s);
}

std::unique_ptr<NumericTables> StrainEnergyMaterial::build_tables() const {
  const std::vector<double> breaks = table_breaks(admissible(), law_breaks());
  Solved<PiecewiseChebyshev> energy =
      tabulate_law(breaks, [this](double tau) { return strain_energy_law(std::exp(tau)); });
  if (!energy.ok()) return nullptr;
  auto t = std::make_unique<NumericTables>();
  t->w = std::move(energy.value);
  t->w_t = t->w.derivative();
  t->w_tt = t->w_t.derivative();
  t->pressure_accuracy = kStrainEnergyTablePressureAccuracy;
  for (const double b : t->w.breaks()) t->pressure_at_breaks.push_back(t->pressure(b));  // as pressure()
  if (!t->complete()) return nullptr;
  return t;
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
