#include "rigidity/solvers/riemann.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

#include "outcome.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/hyperbolic.hpp"
#include "rigidity/number_text.hpp"

namespace rigidity {

namespace {

using solving::find_root;
using solving::numerical_failure;
using solving::Outcome;
using solving::succeeded;

constexpr double kInf = std::numeric_limits<double>::infinity();
using solving::kNaN;
/// |ln s| beyond which no stretch is a state double arithmetic evaluates (s < 1e-304 or
/// s > 1e304): the furthest a bracket search goes toward a range that has no end.
constexpr double kLogStretchHorizon = 700.0;
/// A material's inverse may round out of its range this close (relative) to one of its limits.
constexpr double kLimitRoundOff = 1e-12;
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Secant steps a Riemann problem of one material takes from its two-rarefaction guess
/// before it brackets the root instead.
constexpr int kSecantSteps = 8;

/// What failed, for the messages of numerical failures.
constexpr std::string_view kPressureInverse = "the material's inverse stretch_at_pressure failed";
constexpr std::string_view kPsiInverse = "the material's inverse stretch_at_psi failed";
constexpr std::string_view kJumpConditions = "the shock jump conditions could not be solved";
constexpr std::string_view kCompositeWave = "a composite wave (a law with an inflection) could not be built";
constexpr std::string_view kBeyondDoubles = "the star state lies beyond the range of double precision";

/// Which end of a material's range: compression (s smallest, p → max_pressure, Ψ → Ψ_max) or
/// tension (s largest, p → max_tension, Ψ → Ψ_min).
enum class End { compression, tension };

/// Ψ lies beyond the end of the material's range (an end at a finite stretch is in the range).
bool beyond_psi(const Material& m, double psi, End end) {
  const StretchRange range = m.admissible();
  if (end == End::compression) return psi > m.psi_max() || (psi == m.psi_max() && !std::isfinite(range.log_min));
  return psi < m.psi_min() || (psi == m.psi_min() && !std::isfinite(range.log_max));
}

/// p within round-off of a limit of the material's pressure.
bool at_pressure_limit(const Material& m, double p) {
  const auto near = [p](double limit) {
    return std::isfinite(limit) && std::abs(p - limit) <= kLimitRoundOff * std::abs(limit);
  };
  return p >= m.max_pressure() || p <= m.max_tension() || near(m.max_pressure()) || near(m.max_tension());
}

/// Where a search for a sign change ended.
struct Reach {
  bool found = false;     ///< f(z) has the sign sought; false: f keeps its sign to the end of its domain
  double z = 0.0;         ///< where it was found (or the end of the domain)
  double value = 0.0;     ///< f(z): if not found, the limit of f at the end of the domain
  double previous = 0.0;  ///< the last point before z, where f has the other sign: the bracket's other end
};

/// From `start`, where f has the sign −dir, toward `end` (the end of f's domain in direction
/// dir; ±inf allowed), a point where f has the sign of dir. Steps grow geometrically, step·2^k,
/// so a finite end is reached in a bounded number of steps; there the end decides, with f's own
/// value (its limit) at the end: of the wrong sign, the domain holds no root (not found: a
/// physical limit, for the caller to report); finite, it closes the bracket; infinite (or not
/// known), it is approached by halving the distance. An infinite end is searched to
/// |ln s| = kLogStretchHorizon: a root beyond is a star state no double represents.
template <class F>
Outcome<Reach> reach_sign(const F& f, double start, double dir, double step, double end, const Material& m) {
  const double last = std::isfinite(end) ? end : dir * std::max(kLogStretchHorizon, std::abs(start) + 1.0);
  double z = start;
  for (int k = 0; k < 1100; ++k) {
    const double next = start + dir * std::ldexp(step, k);
    if (!(dir * (next - last) < 0.0)) break;
    const Outcome<double> v = f(next);
    if (!v.ok()) return v.template as<Reach>();
    if (dir * v.value > 0.0) return succeeded<Reach>(Reach{true, next, v.value, z});
    z = next;
  }
  const Outcome<double> at_end = f(end);
  if (!at_end.ok()) return at_end.template as<Reach>();
  if (!std::isnan(at_end.value) && !(dir * at_end.value > 0.0))
    return succeeded<Reach>(Reach{false, end, at_end.value, z});
  if (std::isfinite(end)) {
    if (std::isfinite(at_end.value)) return succeeded<Reach>(Reach{true, end, at_end.value, z});
    for (;;) {
      const double next = z + 0.5 * (end - z);
      if (next == z || next == end) break;
      const Outcome<double> v = f(next);
      if (!v.ok()) return v.template as<Reach>();
      if (dir * v.value > 0.0) return succeeded<Reach>(Reach{true, next, v.value, z});
      z = next;
    }
  } else if (dir * (last - z) > 0.0) {
    const Outcome<double> v = f(last);
    if (!v.ok()) return v.template as<Reach>();
    if (dir * v.value > 0.0) return succeeded<Reach>(Reach{true, last, v.value, z});
  }
  return numerical_failure<Reach>(Status::not_converged, kBeyondDoubles, m);
}

/// The rapidity behind a shock of family `family` (−1: C−, +1: C+) that takes the
/// outer state to the star stretch. The label and momentum jump conditions in the
/// lab frame, m [s/γ] = −[v] and m [(e+p) s γ v] = [p], give after eliminating the
/// Lagrangian speed m
///     H(φ*) = [v] [(e+p) s γ v] + [p] [s/γ] = 0,
/// with one root on each side of the outer rapidity; the family picks the side.
/// H = [p] [s/γ] < 0 at φ* = φ_outer (p falls as s grows) and grows without bound away from it.
Outcome<double> shock_star_rapidity(const Material& m, const State& outer, Stretch star, int family) {
  const double p_outer = m.pressure(outer.stretch), p_star = m.pressure(star);
  const double cosh_outer = std::cosh(outer.rapidity);
  const double labels_outer = label_density(outer), momentum_outer = momentum_density(m, outer);
  // [v] = tanh φ* − tanh φ_outer = sinh(φ* − φ_outer)/(cosh φ* cosh φ_outer): exact where both
  // tanh round to ±1 (|φ| > 19).
  // H and the size of its round-off there (its two products of jumps, each taken as a
  // difference of O(1) values).
  struct Residual {
    double value, round_off;
  };
  const auto hugoniot_residual = [&](double rapidity) {
    const State st{rapidity, star};
    const double cosh_star = std::cosh(rapidity);
    const double dv = std::sinh(rapidity - outer.rapidity) / cosh_star / cosh_outer;
    const double momentum_star = momentum_density(m, st);
    const double scale = std::abs(dv) * (std::abs(momentum_star) + std::abs(momentum_outer)) +
                         std::abs(p_star - p_outer) * (star.value() / cosh_star + labels_outer);
    return Residual{
        dv * (momentum_star - momentum_outer) + (p_star - p_outer) * (star.value() / cosh_star - labels_outer),
        64.0 * std::numeric_limits<double>::epsilon() * (1.0 + std::abs(rapidity)) * scale};
  };
  const auto hugoniot = [&](double rapidity) { return hugoniot_residual(rapidity).value; };
  // The star moves against the family's direction in a compression (a C− shock slows the left
  // state) and with it in an expansion: g(d) = H(φ_outer + direction d) grows with d ≥ 0.
  const double direction = star.log() < outer.stretch.log() ? family : -family;
  const auto g = [&](double d) { return hugoniot(outer.rapidity + direction * d); };
  const auto failure = [&m] { return numerical_failure<double>(Status::not_converged, kJumpConditions, m); };
  const auto at = [&](double d) { return succeeded<double>(outer.rapidity + direction * d); };
  // H(φ_outer) = [p] [s/γ] (the [v] term vanishes exactly) has the sign of [p] [s]. A jump for
  // which that rounds to ≥ 0 is too weak for the arithmetic to tell from none: its rapidity
  // change is below round-off.
  const double at_outer = (p_star - p_outer) * (star.value() - outer.stretch.value());
  if (std::isnan(at_outer)) return failure();
  if (at_outer >= 0.0) return at(0.0);
  // The rest-frame closed form and Newton steps on the lab-frame condition in its
  // cancellation-free form (hugoniot_rapidity) settle almost every shock in one or two
  // evaluations; the root is taken if H, the same condition written directly, vanishes there
  // to its round-off. Where it does not, or the root lies on the other family's side, the
  // root of H is bracketed below.
  const JumpLaws laws_outer{outer.stretch.value(), p_outer, m.enthalpy_density(outer.stretch)};
  const JumpLaws laws_star{star.value(), p_star, m.enthalpy_density(star)};
  const Solved<double> closed = hugoniot_rapidity(outer, laws_outer, star, laws_star, family);
  if (closed.ok() && direction * (closed.value - outer.rapidity) >= 0.0) {
    const Residual check = hugoniot_residual(closed.value);
    if (std::abs(check.value) <= check.round_off) return succeeded<double>(closed.value);
  }
  // The rarefaction curve's |ΔΨ| agrees with the shock's rapidity change to second order in the
  // strength: bracket tightly around it, so that Brent needs few steps. Where ΔΨ rounds away
  // (a star an ulp from the outer stretch), c_s |Δ ln s| gives the same scale.
  const double guess = std::max(std::abs(m.riemann_psi(star) - m.riemann_psi(outer.stretch)),
                                m.sound_speed(outer.stretch) * std::abs(star.log() - outer.stretch.log()));
  const double step = 0.02 * guess + std::numeric_limits<double>::denorm_min();
  // Beyond |φ*| ≈ 700, cosh φ* overflows; H has long turned positive there.
  const double d_max = std::max(guess, 700.0 - direction * outer.rapidity);
  double lo = 0.0, hi = guess;
  const double at_guess = g(guess);
  if (std::isnan(at_guess)) return failure();
  if (at_guess == 0.0) return at(guess);
  if (at_guess > 0.0) {
    for (int k = 0; k < 1100; ++k) {  // tighten from below; g(0) < 0 closes the bracket anyway
      const double d = guess - std::ldexp(step, k);
      if (!(d > 0.0)) break;
      const double value = g(d);
      if (std::isnan(value)) return failure();
      if (value == 0.0) return at(d);
      if (value < 0.0) {
        lo = d;
        break;
      }
      hi = d;
    }
  } else {
    bool found = false;
    for (int k = 0; k < 1100 && !found; ++k) {
      const double d = std::min(guess + std::ldexp(step, k), d_max);
      const double value = g(d);
      if (std::isnan(value)) return failure();
      if (value == 0.0) return at(d);
      if (value > 0.0) {
        hi = d;
        found = true;
      } else {
        lo = d;
        if (d == d_max) break;
      }
    }
    if (!found) return failure();
  }
  const auto checked = [&](double d) {
    const double value = g(d);
    return std::isfinite(value) ? succeeded<double>(value) : failure();
  };
  // The answer φ_outer ± d is a double: d finer than its ulp, ε |φ_outer|, does not change it
  // (and in a weak shock H's round-off would leave Brent bisecting to get there).
  const Outcome<double> d =
      find_root(checked, lo, hi, m, std::numeric_limits<double>::epsilon() * std::abs(outer.rapidity));
  if (!d.ok()) return d;
  return at(d.value);
}

/// How far Ψ* may lie from the parting pressure's Ψ and still count as at it: Ψ* is made of the
/// `terms` (the sides' rapidities and Ψs, the parting Ψ), each to a few dozen ulps (a numeric
/// material's Ψ is a table).
double parting_round_off(std::initializer_list<double> terms) {
  double sum = 0.0;
  for (const double term : terms) sum += std::abs(term);
  return 64.0 * kEps * sum;
}

/// The star rapidity on a wave curve at a star stretch: across a shock from the jump
/// conditions; across a fan or a linearly degenerate jump from the invariant carried across
/// it, J+ = φ + Ψ across a C− wave (left side), J− = φ − Ψ across a C+ wave (right side).
Outcome<double> star_rapidity(const WaveCurve& curve, Stretch star) {
  const Material& m = curve.material();
  const int family = curve.side() == Side::left ? -1 : +1;
  if (crosses_inflection(m, curve.state().stretch, star)) {
    const Solved<CompositeWave> wave = composite_wave(m, curve.state(), star, family);
    if (!wave.ok()) return numerical_failure<double>(wave.status, kCompositeWave, m);
    return succeeded<double>(wave.value.pieces.back().end.rapidity);
  }
  if (wave_is_shock(m, curve.state(), star, family)) return shock_star_rapidity(m, curve.state(), star, family);
  const double psi = m.riemann_psi(star);
  return succeeded<double>(curve.side() == Side::left ? curve.invariant() - psi : curve.invariant() + psi);
}

/// The limit of the star rapidity on a wave curve as the star state reaches an end of its
/// material's range: its value at a finite end; for a linearly degenerate material, from the
/// invariant, J+ − Ψ_end (left) or J− + Ψ_end (right), ±inf if Ψ is unbounded; NaN (not known)
/// for a genuinely nonlinear material whose range has no end there.
Outcome<double> curve_limit(const WaveCurve& curve, End end) {
  const Material& m = curve.material();
  const StretchRange range = m.admissible();
  const double log_end = end == End::compression ? range.log_min : range.log_max;
  if (std::isfinite(log_end)) return star_rapidity(curve, Stretch::from_log(log_end));
  if (!m.linearly_degenerate()) return succeeded<double>(kNaN);
  const double psi_end = end == End::compression ? m.psi_max() : m.psi_min();
  return succeeded<double>(curve.side() == Side::left ? curve.invariant() - psi_end : curve.invariant() + psi_end);
}

/// The star rapidity on a wave curve at pressure p, the ends of the curve included: at (or by
/// round-off beyond) max_pressure its limit in compression, at max_tension in tension.
Outcome<double> rapidity_at_pressure(const WaveCurve& curve, double p) {
  const Material& m = curve.material();
  if (p == curve.pressure()) return succeeded<double>(curve.state().rapidity);
  if (p >= m.max_pressure()) return curve_limit(curve, End::compression);
  if (p <= m.max_tension()) return curve_limit(curve, End::tension);
  const Solved<Stretch> star = m.stretch_at_pressure(p);
  if (!star.ok()) {
    if (star.status == Status::out_of_range && at_pressure_limit(m, p))
      return curve_limit(curve, p > curve.pressure() ? End::compression : End::tension);
    return numerical_failure<double>(star.status, kPressureInverse, m);
  }
  return star_rapidity(curve, star.value);
}

/// The star state on a wave curve at pressure p: out_of_range at or beyond the material's
/// limits (or within round-off of one), any other failure a numerical one.
Outcome<State> state_at_pressure(const WaveCurve& curve, double p) {
  const Material& m = curve.material();
  if (p == curve.pressure()) return succeeded<State>(curve.state());
  const Solved<Stretch> star = m.stretch_at_pressure(p);
  if (!star.ok()) {
    if (star.status == Status::out_of_range && at_pressure_limit(m, p))
      return Outcome<State>{State{}, Status::out_of_range, kPressureInverse, &m};
    return numerical_failure<State>(star.status, kPressureInverse, m);
  }
  const Outcome<double> rapidity = star_rapidity(curve, star.value);
  if (!rapidity.ok()) return rapidity.as<State>();
  return succeeded<State>(State{rapidity.value, star.value});
}

/// ln s at which the material's pressure is p, the ends of its range included.
Outcome<double> log_stretch_at_pressure(const Material& m, double p) {
  if (p >= m.max_pressure()) return succeeded<double>(m.admissible().log_min);
  if (p <= m.max_tension()) return succeeded<double>(m.admissible().log_max);
  const Solved<Stretch> s = m.stretch_at_pressure(p);
  if (!s.ok()) return numerical_failure<double>(s.status, kPressureInverse, m);
  return succeeded<double>(s.value.log());
}

/// Ψ at which the material's pressure is p, the ends of its range included.
Outcome<double> psi_at_pressure(const Material& m, double p) {
  if (p >= m.max_pressure()) return succeeded<double>(m.psi_max());
  if (p <= m.max_tension()) return succeeded<double>(m.psi_min());
  const Outcome<double> log_s = log_stretch_at_pressure(m, p);
  if (!log_s.ok()) return log_s;
  return succeeded<double>(m.riemann_psi(Stretch::from_log(log_s.value)));
}

/// The left star stretch z = ln s*_L of a Riemann problem ranges over [lo, hi]: from where the
/// first side is crushed (reaches its largest pressure) to where the first reaches its largest
/// tension, or where the pressure falls to the minimum the meeting point carries (they part).
struct Domain {
  double lo = -kInf, hi = kInf;
  Side lo_limit = Side::left;  ///< whose range ends at lo
  Side hi_limit = Side::left;  ///< whose range ends at hi, unless parting
  bool parting = false;        ///< at hi the pressure is parting_pressure
  double parting_pressure = -kInf;
};

Outcome<Domain> riemann_domain(const Material& left, const Material& right, double min_pressure) {
  Domain d;
  if (right.max_pressure() < left.max_pressure()) {
    const Outcome<double> lo = log_stretch_at_pressure(left, right.max_pressure());
    if (!lo.ok()) return lo.as<Domain>();
    d.lo = lo.value;
    d.lo_limit = Side::right;
  } else {
    d.lo = left.admissible().log_min;
  }
  Outcome<double> hi = succeeded<double>(left.admissible().log_max);
  if (min_pressure >= std::max(left.max_tension(), right.max_tension())) {
    hi = log_stretch_at_pressure(left, min_pressure);
    d.parting = true;
    d.parting_pressure = min_pressure;
  } else if (right.max_tension() > left.max_tension()) {
    hi = log_stretch_at_pressure(left, right.max_tension());
    d.hi_limit = Side::right;
  }
  if (!hi.ok()) return hi.as<Domain>();
  d.hi = hi.value;
  return succeeded<Domain>(d);
}

/// f(z) = φ*_L − φ*_R for the left star stretch z = ln s*_L in the domain; increasing in z. At an
/// end of the domain (±inf included) it is the limit of f there, possibly ±inf, or NaN where no
/// closed form is known; inside, a value that is not finite is a failure.
class Mismatch {
 public:
  Mismatch(const WaveCurve& left, const WaveCurve& right, const Domain& domain)
      : left_(&left), right_(&right), domain_(domain) {}

  [[nodiscard]] Outcome<double> operator()(double z) const {
    const Material& ml = left_->material();
    const Material& mr = right_->material();
    const bool at_lo = z == domain_.lo, at_hi = z == domain_.hi;
    double p;
    Outcome<double> left;
    if (std::isinf(z)) {
      const End end = z < 0.0 ? End::compression : End::tension;
      p = end == End::compression ? ml.max_pressure() : ml.max_tension();
      left = curve_limit(*left_, end);
    } else {
      const Stretch star = Stretch::from_log(z);
      if (at_lo && domain_.lo_limit == Side::right) {
        p = mr.max_pressure();
      } else if (at_hi && domain_.parting) {
        p = domain_.parting_pressure;
      } else if (at_hi && domain_.hi_limit == Side::right) {
        p = mr.max_tension();
      } else {
        p = ml.pressure(star);
      }
      left = star_rapidity(*left_, star);
    }
    if (!left.ok()) return left;
    if (std::isnan(p)) return numerical_failure<double>(Status::not_converged, kBeyondDoubles, ml);
    const Outcome<double> right = rapidity_at_pressure(*right_, p);
    if (!right.ok()) return right;
    const double value = left.value - right.value;
    if (!at_lo && !at_hi && !std::isfinite(value))
      return numerical_failure<double>(Status::not_converged, kBeyondDoubles, ml);
    return succeeded<double>(value);
  }

 private:
  const WaveCurve* left_;
  const WaveCurve* right_;
  Domain domain_;
};

/// A numerical failure as a solution (out_of_range never: only the limit analysis reports that).
template <class T>
RiemannSolution failed(const Outcome<T>& outcome) {
  RiemannSolution s;
  s.status = outcome.status == Status::out_of_range ? Status::not_converged : outcome.status;
  s.failure = outcome.what;
  s.material = outcome.material;
  return s;
}

/// No classical solution: material m would leave its admissible range at `end` (crushed, or
/// pulled beyond its largest tension), where Ψ would have to be demanded_psi (NaN if not known).
RiemannSolution beyond_range(const Material& m, End end, double demanded_psi, double impact_rapidity) {
  RiemannSolution s;
  s.status = Status::out_of_range;
  s.material = &m;
  s.in_tension = end == End::tension;
  s.limit_psi = end == End::compression ? m.psi_max() : m.psi_min();
  s.demanded_psi = demanded_psi;
  s.impact_rapidity = impact_rapidity;
  return s;
}

/// The sides part at min_pressure: each relaxes to it through its own wave.
RiemannSolution parted_pair(const WaveCurve& left, const WaveCurve& right, double min_pressure) {
  const Outcome<State> a = state_at_pressure(left, min_pressure);
  if (!a.ok()) return failed(a);
  const Outcome<State> b = state_at_pressure(right, min_pressure);
  if (!b.ok()) return failed(b);
  RiemannSolution out;
  out.parted = true;
  out.pressure = min_pressure;
  out.left = a.value;
  out.right = b.value;
  return out;
}

}  // namespace

WaveCurve::WaveCurve(const Material& material, const State& state, Side side)
    : material_(&material),
      state_(state),
      side_(side),
      pressure_(material.pressure(state.stretch)),
      psi_(material.riemann_psi(state.stretch)),
      invariant_(side == Side::left ? state.rapidity + psi_ : state.rapidity - psi_) {}

WaveCurvePoint WaveCurve::at_pressure(double p) const {
  const Outcome<State> star = state_at_pressure(*this, p);
  if (!star.ok()) return WaveCurvePoint{0.0, Stretch{}, star.status};
  return WaveCurvePoint{star.value.rapidity, star.value.stretch, Status::ok};
}

RiemannSolution solve_riemann(const Material& left_material, const State& left, const Material& right_material,
                              const State& right, double min_pressure) {
  const double impact = left.rapidity - right.rapidity;
  // One linearly degenerate material on both sides: the star state is closed form,
  // J+ from the left, J− from the right.
  if (&left_material == &right_material && left_material.linearly_degenerate()) {
    const Material& m = left_material;
    const double j_plus = left.rapidity + m.riemann_psi(left.stretch);
    const double j_minus = right.rapidity - m.riemann_psi(right.stretch);
    double psi_star = 0.5 * (j_plus - j_minus);
    const double rapidity_star = 0.5 * (j_plus + j_minus);
    if (beyond_psi(m, psi_star, End::compression)) return beyond_range(m, End::compression, psi_star, impact);
    if (min_pressure >= m.max_tension()) {
      // At the parting pressure to within the precision of Ψ* the contact carries no force and
      // the sides move together: it holds, at exactly that pressure (see solve_wall).
      const Outcome<double> parting = psi_at_pressure(m, min_pressure);
      if (!parting.ok()) return failed(parting);
      const double round_off = parting_round_off(
          {left.rapidity, m.riemann_psi(left.stretch), right.rapidity, m.riemann_psi(right.stretch), parting.value});
      if (psi_star < parting.value - round_off) {
        return parted_pair(WaveCurve(m, left, Side::left), WaveCurve(m, right, Side::right), min_pressure);
      }
      psi_star = std::max(psi_star, parting.value);
    }
    if (beyond_psi(m, psi_star, End::tension)) return beyond_range(m, End::tension, psi_star, impact);
    const Solved<Stretch> star = m.stretch_at_psi(psi_star);
    if (!star.ok()) return failed(numerical_failure<Stretch>(star.status, kPsiInverse, m));
    RiemannSolution out;
    out.pressure = m.pressure(star.value);
    out.left = out.right = State{rapidity_star, star.value};
    return out;
  }

  // General: Brent on the left star stretch z = ln s*_L, f(z) = φ*_L − φ*_R increasing, over the
  // stretches at which both sides can take the star pressure.
  const WaveCurve lc(left_material, left, Side::left);
  const WaveCurve rc(right_material, right, Side::right);
  const Outcome<Domain> domain = riemann_domain(left_material, right_material, min_pressure);
  if (!domain.ok()) return failed(domain);
  const Domain& d = domain.value;
  const Mismatch f(lc, rc, d);
  // Whether the sides move together exactly at the parting pressure (touching at rest,
  // unstrained): the contact holds there, at the end of the domain, and nothing parts.
  bool level_at_parting = false;
  if (d.parting) {
    // If even at the parting pressure the left side does not catch up with the right, they part.
    const Outcome<double> at_parting = f(d.hi);
    if (!at_parting.ok()) return failed(at_parting);
    // Sides that catch up at the parting pressure to within the precision of their rapidities
    // there hold, at exactly that pressure (see solve_wall).
    const double round_off = 64.0 * kEps * (std::abs(left.rapidity) + std::abs(right.rapidity) + 1.0);
    if (at_parting.value < -round_off) return parted_pair(lc, rc, min_pressure);
    level_at_parting = std::abs(at_parting.value) <= round_off;
  }
  // Start from the left state, or for one material on both sides from the star state the
  // rarefaction curves would give (exact for weak waves), with a step to match; the guess is
  // only a guess, so a failed one is not used. A root at the parting pressure is the start.
  const auto inside = [&d](double z) { return std::max(d.lo, std::min(z, d.hi)); };
  double start = level_at_parting ? d.hi : inside(left.stretch.log());
  double first_step = 0.5;
  if (!level_at_parting && &left_material == &right_material) {
    const double psi_guess = 0.5 * (lc.invariant() - rc.invariant());
    const Solved<Stretch> guess = left_material.stretch_at_psi(std::min(psi_guess, left_material.psi_max()));
    if (guess.ok()) {
      first_step = 1e-3 + 0.05 * std::abs(guess.value.log() - start);
      start = inside(guess.value.log());
    }
  }
  const Outcome<double> at_start = f(start);
  if (!at_start.ok()) return failed(at_start);
  if (std::isnan(at_start.value))
    return failed(numerical_failure<double>(Status::not_converged, kBeyondDoubles, left_material));
  double z = start;
  bool settled = at_start.value == 0.0 || level_at_parting;
  if (!settled && &left_material == &right_material) {
    // One material: secant steps from the two-rarefaction guess (off by a third-order term
    // for weak waves; f' = 2 c_s there) reach the root to round-off in a few evaluations.
    // Any step that leaves the domain, fails or does not settle in kSecantSteps hands over to
    // the bracketing search below.
    const double scale = 1.0 + std::abs(left.rapidity) + std::abs(right.rapidity);
    double z0 = start, g0 = at_start.value;
    double z1 = z0 - g0 / (2.0 * left_material.sound_speed(Stretch::from_log(z0)));
    for (int step = 0; step < kSecantSteps && !settled; ++step) {
      if (!(z1 > d.lo && z1 < d.hi)) break;
      const Outcome<double> g1 = f(z1);
      if (!g1.ok() || !std::isfinite(g1.value)) break;
      const bool still = std::abs(z1 - z0) <= 2.0 * kEps * std::abs(z1) + 1e-300;
      if (g1.value == 0.0 || still || std::abs(g1.value) <= 4.0 * kEps * scale) {
        z = z1;
        settled = true;
        break;
      }
      if (g1.value == g0) break;
      const double next = z1 - g1.value * (z1 - z0) / (g1.value - g0);
      z0 = z1;
      g0 = g1.value;
      z1 = next;
    }
  }
  if (!settled) {
    // Compress the left star (go down in z) while the left outruns the right, else relax it.
    const double dir = at_start.value > 0.0 ? -1.0 : 1.0;
    const Outcome<Reach> reach = reach_sign(f, start, dir, first_step, dir < 0.0 ? d.lo : d.hi, left_material);
    if (!reach.ok()) return failed(reach);
    if (!reach.value.found) {
      // f keeps its sign to the end of the domain: the side whose range ends there would have to
      // leave it. On the invariant's curve it would need Ψ = Ψ_end + f(end) (J+ − φ*_R for the
      // left, φ*_L − J− for the right); behind a shock that Ψ is not defined.
      const End end = dir < 0.0 ? End::compression : End::tension;
      const WaveCurve& limiting = (dir < 0.0 ? d.lo_limit : d.hi_limit) == Side::left ? lc : rc;
      const Material& m = limiting.material();
      const double psi_end = end == End::compression ? m.psi_max() : m.psi_min();
      const double demanded = m.linearly_degenerate() && std::isfinite(psi_end) ? psi_end + reach.value.value : kNaN;
      // Unless f vanishes at a range end that is itself a state (a finite stretch): the root.
      const StretchRange range = m.admissible();
      const bool end_is_state = std::isfinite(end == End::compression ? range.log_min : range.log_max);
      if (!(reach.value.value == 0.0 && std::isfinite(reach.value.z) && end_is_state))
        return beyond_range(m, end, demanded, impact);
      z = reach.value.z;
    } else {
      const double a = reach.value.previous, b = reach.value.z;
      const Outcome<double> root = find_root(f, std::min(a, b), std::max(a, b), left_material);
      if (!root.ok()) return failed(root);
      z = root.value;
    }
  }
  const Stretch star_left = Stretch::from_log(z);
  RiemannSolution out;
  out.pressure = left_material.pressure(star_left);
  const Outcome<double> a = star_rapidity(lc, star_left);
  if (!a.ok()) return failed(a);
  const Outcome<State> b = state_at_pressure(rc, out.pressure);
  if (!b.ok()) {
    if (b.status != Status::out_of_range) return failed(b);
    // The root lies within round-off of the right side's limit: it is crushed (or pulled) to it.
    const End end = out.pressure > rc.pressure() ? End::compression : End::tension;
    const double demanded = right_material.linearly_degenerate() ? a.value - rc.invariant() : kNaN;
    return beyond_range(right_material, end, demanded, impact);
  }
  const double rapidity = 0.5 * (a.value + b.value.rapidity);
  out.left = State{rapidity, star_left};
  out.right = State{rapidity, b.value.stretch};
  return out;
}

RiemannSolution solve_wall(const Material& m, const State& state, Side side, double wall_rapidity,
                           double min_pressure) {
  const WaveCurve curve(m, state, side);
  const int family = side == Side::left ? -1 : +1;
  const double impact = side == Side::left ? state.rapidity - wall_rapidity : wall_rapidity - state.rapidity;
  // The star on the rarefaction curve: Ψ* from the invariant carried across the wave. It is
  // the answer for a linearly degenerate material and for a fan.
  const double psi_star = side == Side::left ? curve.invariant() - wall_rapidity : wall_rapidity - curve.invariant();
  const bool in_range = !beyond_psi(m, psi_star, End::compression) && !beyond_psi(m, psi_star, End::tension);
  const Solved<Stretch> on_curve =
      in_range ? m.stretch_at_psi(psi_star) : Solved<Stretch>::failure(Status::out_of_range);
  if (in_range && !on_curve.ok()) return failed(numerical_failure<Stretch>(on_curve.status, kPsiInverse, m));
  const bool jump_or_fan =
      m.linearly_degenerate() || (on_curve.ok() && !wave_is_shock(m, state, on_curve.value, family));
  Stretch star;
  if (jump_or_fan) {
    if (beyond_psi(m, psi_star, End::compression)) return beyond_range(m, End::compression, psi_star, impact);
    // A wall that cannot pull lets go before the material would reach that tension (the
    // rigid fluid cannot even be put in tension: its curve ends at p = 0). A star at the parting
    // pressure to within the precision of Ψ* (the invariant less the wall's rapidity, each term
    // to a few dozen ulps: a numeric material's Ψ is a table) carries no force and moves with the
    // wall: the contact holds, at exactly that pressure, until a wave brings tension. Whether Ψ*
    // rounds above or below must not decide when the body leaves.
    if (min_pressure >= m.max_tension()) {
      const Outcome<double> parting = psi_at_pressure(m, min_pressure);
      if (!parting.ok()) return failed(parting);
      const double round_off =
          parting_round_off({state.rapidity, m.riemann_psi(state.stretch), wall_rapidity, parting.value});
      if (psi_star < parting.value - round_off) return solve_free_end(m, state, side);
      if (psi_star <= parting.value + round_off) {
        const Outcome<double> log_s = log_stretch_at_pressure(m, min_pressure);
        if (!log_s.ok()) return failed(log_s);
        RiemannSolution out;
        out.pressure = min_pressure;
        out.left = out.right = State{wall_rapidity, Stretch::from_log(log_s.value)};
        return out;
      }
    }
    if (beyond_psi(m, psi_star, End::tension)) return beyond_range(m, End::tension, psi_star, impact);
    star = on_curve.value;
  } else {
    // A shock: solve φ*(z) = φ_wall on the wave curve for the star stretch z = ln s*; the
    // mismatch g grows with z (the less compressed the star, the more of the side's motion
    // towards the wall it keeps), so its sign at the side's own stretch says which way to go.
    const StretchRange range = m.admissible();
    const auto g = [&](double z) -> Outcome<double> {
      const bool end = z == range.log_min || z == range.log_max;
      const Outcome<double> rapidity = std::isinf(z) ? curve_limit(curve, z < 0.0 ? End::compression : End::tension)
                                                     : star_rapidity(curve, Stretch::from_log(z));
      if (!rapidity.ok()) return rapidity;
      const double value = side == Side::left ? rapidity.value - wall_rapidity : wall_rapidity - rapidity.value;
      if (!end && !std::isfinite(value)) return numerical_failure<double>(Status::not_converged, kBeyondDoubles, m);
      return succeeded<double>(value);
    };
    const double z_side = state.stretch.log();
    if (impact == 0.0) {
      star = state.stretch;
    } else {
      const double dir = impact > 0.0 ? -1.0 : 1.0;
      const Outcome<Reach> reach = reach_sign(g, z_side, dir, 0.5, dir < 0.0 ? range.log_min : range.log_max, m);
      if (!reach.ok()) return failed(reach);
      if (!reach.value.found) {
        // g vanishing at a range end that is a finite stretch is a root; otherwise no state of
        // the material meets the wall.
        if (reach.value.value == 0.0 && std::isfinite(reach.value.z)) {
          star = Stretch::from_log(reach.value.z);
        } else if (dir < 0.0) {
          return beyond_range(m, End::compression, kNaN, impact);
        } else if (min_pressure >= m.max_tension()) {
          return solve_free_end(m, state, side);
        } else {
          return beyond_range(m, End::tension, kNaN, impact);
        }
      } else {
        const double a = reach.value.previous, b = reach.value.z;
        const Outcome<double> root = find_root(g, std::min(a, b), std::max(a, b), m);
        if (!root.ok()) return failed(root);
        star = Stretch::from_log(root.value);
      }
    }
  }
  RiemannSolution out;
  out.pressure = m.pressure(star);
  // A wall that cannot pull lets go: the end is free.
  if (out.pressure < min_pressure) return solve_free_end(m, state, side);
  out.left = out.right = State{wall_rapidity, star};
  return out;
}

RiemannSolution solve_free_end(const Material& m, const State& state, Side side) {
  // The traction p = 0 (the cavitation pressure where that is higher), and the end is free.
  RiemannSolution out = solve_traction_end(m, state, side, 0.0);
  out.parted = out.status == Status::ok;
  return out;
}

RiemannSolution solve_traction_end(const Material& m, const State& state, Side side, double pressure) {
  const double held = std::max(pressure, m.cavitation_pressure());
  const WaveCurve curve(m, state, side);
  const Outcome<State> pt = state_at_pressure(curve, held);
  if (!pt.ok()) return failed(pt);
  RiemannSolution out;
  out.pressure = held;
  out.left = out.right = pt.value;
  return out;
}

double label_density(const State& st) { return st.stretch.value() / std::cosh(st.rapidity); }

double momentum_density(const Material& m, const State& st) {
  return momentum_density(st.stretch.value(), std::sinh(st.rapidity), m.enthalpy_density(st.stretch));
}

EnergyParts energy_parts(const Material& m, const State& st) {
  const double s = st.stretch.value();
  const double half = std::sinh(0.5 * st.rapidity);
  EnergyParts parts;
  parts.kinetic = s * (m.energy_density(st.stretch) * 2.0 * half * half +
                       m.pressure(st.stretch) * std::sinh(st.rapidity) * std::tanh(st.rapidity));
  parts.internal = m.strain_energy(st.stretch) - m.rest_density();
  parts.rest = m.rest_density();
  return parts;
}

double energy_density(const Material& m, const State& st) {
  return energy_density(st.stretch.value(), std::cosh(st.rapidity), m.pressure(st.stretch),
                        m.enthalpy_density(st.stretch));
}

bool representable(Stretch s) { return std::abs(s.log()) < kRepresentableLogStretch; }

void require_solved(const RiemannSolution& sol, const Material& material, double t, double x, UnitSystem units) {
  // Every number in the scene's units, with its unit; speeds of an SI scene also as fractions of c.
  const auto in_units = [units](double value, Dimension d) { return rigidity::in_units(value, d, units); };
  if (sol.status == Status::ok) {
    // A solution whose stretch or pressure double precision cannot carry (an impact at a
    // Lorentz factor of 1e40 compresses a soft gas to s = 1e-400) is a limit of the
    // representation, reported as such, not a number that turns the books into noise.
    if (representable(sol.left.stretch) && representable(sol.right.stretch) && std::isfinite(sol.pressure) &&
        std::abs(sol.pressure) < 1e300)
      return;
    const Material& m = sol.material != nullptr ? *sol.material : material;
    const Stretch extreme =
        std::abs(sol.left.stretch.log()) > std::abs(sol.right.stretch.log()) ? sol.left.stretch : sol.right.stretch;
    Inadmissibility unrepresentable = Inadmissibility::at(t, x);
    unrepresentable.material = std::string(m.model());
    throw InadmissibleError("no state double precision can carry at t = " + in_units(t, Dimension::time) +
                                ", x = " + in_units(x, Dimension::length) + ": material '" + std::string(m.model()) +
                                "' would reach s = exp(" + shortest(extreme.log()) +
                                ") and p = " + in_units(sol.pressure, Dimension::pressure) +
                                " (double precision carries s in [1e-300, 1e300] and |p| below 1e300); the bodies "
                                "meet too fast for this material: lower their Lorentz factors",
                            unrepresentable);
  }
  const Material& m = sol.material != nullptr ? *sol.material : material;
  const std::string model(m.model());
  const std::string where = "at t = " + in_units(t, Dimension::time) + ", x = " + in_units(x, Dimension::length);
  if (sol.status != Status::out_of_range) {
    std::string what =
        "the Riemann problem " + where + " could not be solved (" + std::string(to_string(sol.status)) + ")";
    if (!sol.failure.empty()) what += ": " + std::string(sol.failure) + " (material '" + model + "')";
    throw NumericalError(what);
  }
  // Ψ(s) = ∫_s^1 c_s dσ/σ: an unstrained bar meeting a wall at speed v comes to rest with
  // Ψ = artanh v on the invariant's curve, so tanh Ψ_max is the largest impact speed it takes.
  const StretchRange range = m.admissible();
  const bool demanded_known = std::isfinite(sol.demanded_psi);
  std::string what = "no classical solution " + where + ": ";
  // A material declared on a finite range (a fit valid between two stretches) is not crushed
  // when a state would leave it: the state leaves the range the law was given on.
  const std::string declared = "s in [" + shortest(std::exp(range.log_min)) + ", " +
                               (std::isfinite(range.log_max) ? shortest(std::exp(range.log_max)) : "inf") + "]";
  if (!sol.in_tension) {
    what += "an impact at relative speed " + in_units(std::tanh(sol.impact_rapidity), Dimension::velocity) + " would " +
            (std::isfinite(range.log_min)
                 ? "take the material '" + model + "' out of the range its law is declared on, " + declared +
                       ": below its smallest admissible stretch s = " + shortest(std::exp(range.log_min))
                 : "crush the material '" + model + "' to zero length");
    if (demanded_known) {
      what += ": it would need Psi = " + shortest(sol.demanded_psi) +
              " (tanh Psi = " + in_units(std::tanh(sol.demanded_psi), Dimension::velocity) + "), at or beyond";
    } else {
      what += ": beyond";
    }
    what += " its limit Psi_max = " + shortest(sol.limit_psi) +
            " (tanh Psi_max = " + in_units(std::tanh(sol.limit_psi), Dimension::velocity) +
            ", the largest impact speed an unstrained bar of it takes against a wall)";
  } else {
    what += "sides separating at relative speed " +
            in_units(std::abs(std::tanh(sol.impact_rapidity)), Dimension::velocity) + " would " +
            (std::isfinite(range.log_max)
                 ? "take the material '" + model + "' out of the range its law is declared on, " + declared +
                       ": beyond its largest admissible stretch s = " + shortest(std::exp(range.log_max))
                 : "pull the material '" + model + "' to infinite length");
    if (demanded_known)
      what += ": it would need Psi = " + shortest(sol.demanded_psi) + ", at or beyond";
    else
      what += ": beyond";
    what += " its limit Psi_min = " + shortest(sol.limit_psi) +
            " (its largest tension, p = " + in_units(m.max_tension(), Dimension::pressure) + ")";
  }
  Inadmissibility stop = Inadmissibility::at(t, x);
  stop.relative_speed = std::abs(std::tanh(sol.impact_rapidity));
  stop.psi_needed = demanded_known ? sol.demanded_psi : Inadmissibility::kUnknown;
  stop.psi_limit = sol.limit_psi;
  stop.in_tension = sol.in_tension;
  stop.material = model;
  throw InadmissibleError(what, std::move(stop));
}

bool wave_is_shock(const Material& m, const State& outer, Stretch star, int family) {
  if (m.linearly_degenerate() || star == outer.stretch) return false;
  // The star on the rarefaction curve: J+ = φ + Ψ carried across a C− wave, J− = φ − Ψ across a C+.
  const double psi_change = m.riemann_psi(star) - m.riemann_psi(outer.stretch);
  const State on_curve{outer.rapidity + family * psi_change, star};
  const double outer_speed = characteristic_speed(m, outer, family);
  const double star_speed = characteristic_speed(m, on_curve, family);
  // A C− fan has the outer state on its left, a C+ fan on its right.
  return family < 0 ? !(outer_speed < star_speed) : !(star_speed < outer_speed);
}

Solved<State> centred_fan_state(const Material& m, int family, double j_other, double psi_a, double psi_b,
                                double speed) {
  const auto state_at = [&](double psi) -> Outcome<State> {
    const Solved<Stretch> s = m.stretch_at_psi(psi);
    if (!s.ok()) return numerical_failure<State>(s.status, "the stretch of a state in a fan", m);
    return succeeded(State{family > 0 ? j_other + psi : j_other - psi, s.value});
  };
  const auto mismatch = [&](double psi) -> Outcome<double> {
    const Outcome<State> st = state_at(psi);
    if (!st.ok()) return st.as<double>();
    return succeeded(characteristic_speeds(m, st.value, family).lagrangian - speed);
  };
  const double lo = std::min(psi_a, psi_b), hi = std::max(psi_a, psi_b);
  Outcome<double> psi = succeeded(lo);
  if (lo < hi) {
    const Outcome<double> at_lo = mismatch(lo), at_hi = mismatch(hi);
    if (!at_lo.ok() || !at_hi.ok()) return Solved<State>::failure(Status::not_converged);
    if (at_lo.value == 0.0 || at_hi.value == 0.0) {
      psi = succeeded(at_lo.value == 0.0 ? lo : hi);
    } else if ((at_lo.value < 0.0) == (at_hi.value < 0.0)) {
      return Solved<State>::failure(Status::out_of_range);  // the speed is not the fan's
    } else {
      psi = find_root(mismatch, lo, hi, m);
    }
  }
  if (!psi.ok()) return Solved<State>::failure(psi.status);
  const Outcome<State> st = state_at(psi.value);
  if (!st.ok()) return Solved<State>::failure(st.status);
  return Solved<State>{st.value, Status::ok};
}

Solved<double> shock_rapidity(const Material& m, const State& outer, Stretch star, int family) {
  const Outcome<double> r = shock_star_rapidity(m, outer, star, family);
  return r.ok() ? Solved<double>{r.value, Status::ok} : Solved<double>::failure(r.status);
}

Solved<double> hugoniot_rapidity(const Material& m, const State& outer, Stretch star, int family) {
  JumpLaws at_outer, at_star;
  return hugoniot_rapidity(outer, at_outer.at(m, outer.stretch), star, at_star.at(m, star), family);
}

Solved<double> hugoniot_rapidity(const State& outer, const JumpLaws& at_outer, Stretch star, const JumpLaws& at_star,
                                 int family) {
  const double s0 = at_outer.stretch, s = at_star.stretch;
  const double dp = at_star.pressure - at_outer.pressure;
  const double w = at_star.enthalpy;
  const double qa = s * s * w * w;
  const double qb = 2.0 * s * s * w - dp * s0 * s0;
  // s/s0 − 1, from which both the quadratic's constant term and [τ] below are written.
  const double log_ratio = star.log() - outer.stretch.log();
  const double ratio_m1 = std::expm1(log_ratio);
  const double qc = s0 * s0 * ratio_m1 * (ratio_m1 + 2.0);
  const double disc = qb * qb - 4.0 * qa * qc;
  if (!(disc >= 0.0) || dp == 0.0) return Solved<double>::failure(Status::out_of_range);
  const double root = std::sqrt(disc);
  const double y = qb >= 0.0 ? 2.0 * qc / (-qb - root) : (-qb + root) / (2.0 * qa);
  const double u2 = dp * y;
  if (!(u2 >= 0.0) || !(dp + w * u2 != 0.0) || ((dp + w * u2) > 0.0) != (dp > 0.0))
    return Solved<double>::failure(Status::out_of_range);
  const double sinh_relative = std::sqrt(u2);
  const double relative = std::asinh(sinh_relative);
  // A compression (Ψ grows as s falls, c_s > 0) slows the state behind a C− shock (it moves
  // against the family's direction).
  const double direction = star.log() < outer.stretch.log() ? family : -family;
  double phi = outer.rapidity + direction * relative;

  // The lab frame: g(φ) = [p][τ] + [v][M] = 0 with τ = s/cosh φ, v = tanh φ, M = w s sinh φ.
  const double phi0 = outer.rapidity;
  const Hyperbolic outer_hyperbolic = hyperbolic(phi0);
  const double ch0 = outer_hyperbolic.cosh, sh0 = outer_hyperbolic.sinh;
  const double tau0 = s0 / ch0, momentum0 = at_outer.enthalpy * s0 * sh0;
  // Newton in ρ = φ − φ0, with sinh and cosh of ρ and of d = −ρ/2 at hand. Those of the
  // closed-form start come from sinh ρ = √u² by the half-angle formulas; a step δ of Newton
  // (third order in a weak shock's strength, then its square) moves them by the addition
  // theorems with sinh δ and cosh δ from their series, exact to round-off for |δ| < 1e-4,
  // so that a weak shock is settled without another exponential. sinh φ and cosh φ follow
  // from those of φ0 and ρ, without cancellation while |ρ| < 1/2 (cosh φ ≥ cosh φ0 e^−|ρ|);
  // a stronger shock, or a larger step, takes them from exponentials.
  Hyperbolic rho{direction * sinh_relative, std::sqrt(1.0 + u2)};
  Hyperbolic d{0.0, std::sqrt(0.5 * (1.0 + rho.cosh))};
  d.sinh = -0.5 * rho.sinh / d.cosh;
  const auto shift = [](Hyperbolic& a, double e) {  // the angle a − e, for |e| < 1e-4
    const double se = e * (1.0 + e * e / 6.0), ce = 1.0 + 0.5 * e * e;
    const double sinh = a.sinh * ce - a.cosh * se, cosh = a.cosh * ce - a.sinh * se;
    a.sinh = sinh;
    a.cosh = cosh;
  };
  bool by_addition = relative < 0.5;
  bool settled = false;
  for (int step = 0; step < 8 && !settled; ++step) {
    double ch = 0.0, sh = 0.0;
    if (by_addition) {
      ch = ch0 * rho.cosh + sh0 * rho.sinh;
      sh = sh0 * rho.cosh + ch0 * rho.sinh;
    } else {
      const Hyperbolic at_phi = hyperbolic(phi);
      ch = at_phi.cosh;
      sh = at_phi.sinh;
      d = hyperbolic(0.5 * (phi0 - phi));
    }
    const double sd = d.sinh, cd = d.cosh;
    // With d = (φ0 − φ)/2: cosh φ0 / cosh φ − 1 = 2 sinh(φ + d) sinh d / cosh φ =: x,
    // sinh(φ − φ0) = −2 sinh d cosh d, and [τ] = τ0 ((s/s0)(1 + x) − 1) = τ0 (r + (1 + r) x)
    // with r = s/s0 − 1, each without cancellation.
    const double cosh_excess = 2.0 * (sh * cd + ch * sd) * sd / ch;
    const double dtau = tau0 * (ratio_m1 + (1.0 + ratio_m1) * cosh_excess);
    const double dv = -2.0 * sd * cd / (ch0 * ch);
    const double dm = w * s * sh - momentum0;
    const double g = dp * dtau + dv * dm;
    const double slope = -dp * s * sh / (ch * ch) + dm / (ch * ch) + dv * w * s * ch;
    if (!(slope != 0.0) || !std::isfinite(g)) break;
    const double delta = g / slope;
    phi -= delta;
    // Newton's next error is about δ² g''/(2 g'), with g''/g' of the order of 1/(the jump in
    // rapidity): below round-off, no further step is needed (one, for a weak shock, whose
    // closed-form start is off by a third-order term only).
    settled = delta * delta <=
              4.0 * std::numeric_limits<double>::epsilon() * (1.0 + std::abs(phi)) * std::max(relative, 1e-300);
    if (by_addition && !settled) {
      by_addition = std::abs(delta) < 1e-4;
      if (by_addition) {
        shift(rho, delta);
        shift(d, -0.5 * delta);
      }
    }
  }
  if (!settled || !std::isfinite(phi)) return Solved<double>::failure(Status::not_converged);
  return Solved<double>{phi, Status::ok};
}

FrontSpeeds characteristic_speeds(const Material& m, const State& state, int family) {
  return characteristic_speeds(m.sound_speed(state.stretch), state, family);
}

FrontSpeeds characteristic_speeds(double c, const State& state, int family) {
  if (c == 1.0) {
    // Signals at light speed: dX/dt = ± e^∓φ / s, dx/dt = ±1 exactly (from ln s: no overflow).
    return FrontSpeeds{family * std::exp(-family * state.rapidity - state.stretch.log()), static_cast<double>(family)};
  }
  return characteristic_speeds(c, state.rapidity, state.stretch.value(), family);
}

namespace {
/// The speeds of family `family` at sound speed c < 1 from e^φ, e^−φ and s:
/// cosh φ ± c sinh φ = ((1 ± c) e^φ + (1 ∓ c) e^−φ)/2 and sinh φ ± c cosh φ likewise,
/// free of cancellation for c → 1 and large |φ|.
FrontSpeeds speeds_from_exponentials(double c, double ep, double em, double s, int family) {
  const double a = family > 0 ? 1.0 + c : 1.0 - c;
  const double b = family > 0 ? 1.0 - c : 1.0 + c;
  const double denominator = 0.5 * (a * ep + b * em);
  const double numerator = 0.5 * (a * ep - b * em);
  return FrontSpeeds{family * c / (s * denominator), numerator / denominator};
}
}  // namespace

FrontSpeeds characteristic_speeds(double c, double rapidity, double s, int family) {
  // For c = 1 exactly e^±φ.
  if (c == 1.0) return FrontSpeeds{family * std::exp(-family * rapidity - std::log(s)), static_cast<double>(family)};
  const double ep = std::exp(rapidity);
  return speeds_from_exponentials(c, ep, 1.0 / ep, s, family);
}

void characteristic_speeds_both(const Material& m, const State& state, FrontSpeeds (&speeds)[2]) {
  const double c = m.sound_speed(state.stretch);
  if (c == 1.0) {
    speeds[0] = characteristic_speeds(c, state, -1);
    speeds[1] = characteristic_speeds(c, state, +1);
    return;
  }
  // e^±φ and s computed once for both.
  const double s = state.stretch.value();
  const double ep = std::exp(state.rapidity), em = 1.0 / ep;
  speeds[0] = speeds_from_exponentials(c, ep, em, s, -1);
  speeds[1] = speeds_from_exponentials(c, ep, em, s, +1);
}

double characteristic_speed(const Material& m, const State& state, int family) {
  return characteristic_speeds(m, state, family).lagrangian;
}

double characteristic_lab_speed(const Material& m, const State& state, int family) {
  return characteristic_speeds(m, state, family).lab;
}

LabelJump label_jump(const State& a, const State& b) { return label_jump(a, hyperbolic(a.rapidity), b); }

LabelJump label_jump(const State& a, const Hyperbolic& at_a, const State& b) {
  // cosh and sinh of φa from one exponential, those of h from another, and
  // sinh((φa + φb)/2) = sinh(φa + h) from both: three evaluations of the exponential
  // where seven hyperbolic functions would be.
  LabelJump jump;
  jump.left = at_a;
  const Hyperbolic half = hyperbolic(0.5 * (b.rapidity - a.rapidity));
  jump.scaled_v = 2.0 * half.sinh * half.cosh;
  const double r = std::expm1(b.stretch.log() - a.stretch.log());
  jump.stretch_ratio_m1 = r;
  jump.left_stretch = a.stretch.value();
  // A difference whose terms are more than 1/kCancels times its size has lost that many bits.
  constexpr double kCancels = 0.0625;
  const auto cancels = [](double x, double y) {
    return std::abs(x + y) < kCancels * std::max(std::abs(x), std::abs(y));
  };
  // sinh(φa + h) from the two products where they add; where they cancel (a strong jump
  // across rest: φa and h of opposite signs), from its own exponential.
  const double sinh_a_ch = jump.left.sinh * half.cosh, cosh_a_sh = jump.left.cosh * half.sinh;
  const double sinh_mid =
      cancels(sinh_a_ch, cosh_a_sh) ? std::sinh(0.5 * (a.rapidity + b.rapidity)) : sinh_a_ch + cosh_a_sh;
  const double ratio_term = r * jump.left.cosh, rapidity_term = -2.0 * sinh_mid * half.sinh;
  jump.scaled_tau = jump.left_stretch * (ratio_term + rapidity_term);
  if (cancels(ratio_term, rapidity_term)) {
    // A strong jump between sides of very different γ (a bar struck near light speed): the
    // two terms above are each about γ times [τ] cosh φa cosh φb. Directly, sb cosh φa −
    // sa cosh φb: its terms are the sides' lab lengths per label, scaled, the larger of them
    // about the difference itself there. The weak jumps the form above is for keep it.
    jump.right = hyperbolic(b.rapidity);
    jump.right_known = true;
    const double b_term = b.stretch.value() * jump.left.cosh, a_term = jump.left_stretch * jump.right.cosh;
    if (std::max(b_term, a_term) < jump.left_stretch * std::max(std::abs(ratio_term), std::abs(rapidity_term)))
      jump.scaled_tau = b_term - a_term;
  }
  return jump;
}

Solved<double> shock_dissipation_rate(const Material& m, const State& left, const State& right,
                                      double relative_precision) {
  return shock_dissipation_rate(m, left, JumpLaws{}, right, JumpLaws{}, label_jump(left, right), relative_precision);
}

Solved<double> shock_dissipation_rate(const Material& m, const State& left, JumpLaws at_left, const State& right,
                                      JumpLaws at_right, const LabelJump& jump, double relative_precision) {
  const double phi_l = left.rapidity, phi_r = right.rapidity;
  const double s_l = jump.left_stretch;
  const Hyperbolic& at_l = jump.left;
  const Hyperbolic at_r = jump.right_known ? jump.right : hyperbolic(phi_r);
  const double ch_l = at_l.cosh, ch_r = at_r.cosh;
  const double v_l = velocity_of(phi_l, at_l), v_r = velocity_of(phi_r, at_r);
  at_left.at(m, left.stretch);
  at_right.at(m, right.stretch);
  const double p_l = at_left.pressure, p_r = at_right.pressure;
  const double dp = p_r - p_l;
  // [v] and [τ] to full relative precision however weak the jump (see LabelJump).
  const double dv = jump.scaled_v / (ch_l * ch_r);
  const double dtau = jump.scaled_tau / (ch_l * ch_r);
  if (dtau == 0.0) return {0.0, Status::ok};
  const double speed = -dv / dtau;  // label jump condition m [τ] = −[v]
  // A strong shock: the energy jump and the flux jump directly, their difference is not
  // small; a weaker one the same way when the digits that difference keeps are enough.
  const bool strong = std::abs(right.stretch.log() - left.stretch.log()) > 0.3;
  if (strong || relative_precision > 0.0) {
    // energy_density of both states, from the pressures and cosh φ already at hand.
    const double s_r = s_l * (1.0 + jump.stretch_ratio_m1);
    const double E_l = at_left.enthalpy * s_l * ch_l - p_l * s_l / ch_l;
    const double E_r = at_right.enthalpy * s_r * ch_r - p_r * s_r / ch_r;
    const double direct = speed * (E_r - E_l) - (p_r * v_r - p_l * v_l);
    const double round_off =
        8.0 * std::numeric_limits<double>::epsilon() *
        (std::abs(speed) * (std::abs(E_l) + std::abs(E_r)) + std::abs(p_l * v_l) + std::abs(p_r * v_r));
    if (strong || round_off <= relative_precision * std::abs(direct)) return {direct, Status::ok};
  }
  // δτ and δM by Gauss–Legendre on each half of θ ∈ [0, 1]: f' is analytic along the path
  // and each θ-derivative brings a factor of the jump, so 8 points per half are exact to
  // round-off up to |[ln s]| = 0.3 (measured: 4 points leave 1e-9 at 0.15), and 4 points
  // are below 0.03, where the weak shocks of crossings and fan steps live.
  static constexpr double kNode8[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static constexpr double kWeight8[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                         0.1012285362903763};
  static constexpr double kNode4[2] = {0.3399810435848563, 0.8611363115940526};
  static constexpr double kWeight4[2] = {0.6521451548625461, 0.3478548451374538};
  const bool weak = std::abs(right.stretch.log() - left.stretch.log()) < 0.03;
  const int pairs = weak ? 2 : 4;  // node pairs ± per half
  const double* node = weak ? kNode4 : kNode8;
  const double* node_weight = weak ? kWeight4 : kWeight8;
  double delta_tau = 0.0, delta_momentum = 0.0;
  for (int i = 0; i < 2 * pairs; ++i) {
    for (double sign : {-1.0, 1.0}) {
      const double theta = 0.25 + 0.5 * (i / pairs) + 0.25 * sign * node[i % pairs];
      const double p = p_l + theta * dp, v = v_l + theta * (v_r - v_l);
      const Solved<Stretch> st = m.stretch_at_pressure(p);
      if (!st.ok()) return Solved<double>::failure(st.status);
      const double s = st.value.value();
      const double gamma = 1.0 / std::sqrt((1.0 - v) * (1.0 + v));
      const double h = m.enthalpy_density(st.value) * s;
      // τ' = s'(p)[p]/γ + s (dγ⁻¹/dv)[v], s'(p) = −1/W''; M' = s [p] γ v + h γ³ [v].
      const double tau_rate = -dp / (m.stiffness(st.value) * gamma) - s * v * gamma * dv;
      const double momentum_rate = s * dp * gamma * v + h * gamma * gamma * gamma * dv;
      const double weight = 0.25 * node_weight[i % pairs] * (0.5 - theta);
      delta_tau += weight * tau_rate;
      delta_momentum += weight * momentum_rate;
    }
  }
  return {speed * (dp * delta_tau - dv * delta_momentum), Status::ok};
}

FrontSpeeds shock_speeds(const Material& m, const State& outer, const State& star, int family) {
  if (m.linearly_degenerate()) {
    return characteristic_speeds(m, star, family);
  }
  // Label jump condition m [s/γ] = −[v]; the lab speed follows from dx = (s/γ) dX + v dt.
  const double speed =
      -(std::tanh(star.rapidity) - std::tanh(outer.rapidity)) / (label_density(star) - label_density(outer));
  return FrontSpeeds{speed, std::tanh(outer.rapidity) + speed * label_density(outer)};
}

}  // namespace rigidity
