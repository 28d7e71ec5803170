#include "rigidity/solvers/riemann.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "rigidity/errors.hpp"

namespace rigidity {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Stand-in for an infinite rapidity mismatch inside a bracketing root find:
/// far beyond any physical rapidity difference, small enough for Brent's arithmetic.
constexpr double kHuge = 1.0e8;

/// Brent's method (GSL) on a bracket with f(lo) < 0 < f(hi); converged to round-off in z.
template <class F>
Solved<double> find_root(const F& f, double lo, double hi) {
  gsl_set_error_handler_off();
  gsl_function fn{[](double z, void* params) { return (*static_cast<const F*>(params))(z); },
                  const_cast<F*>(&f)};
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (solver == nullptr) return Solved<double>::failure(Status::not_converged);
  Solved<double> result = Solved<double>::failure(Status::not_converged);
  if (gsl_root_fsolver_set(solver, &fn, lo, hi) == GSL_SUCCESS) {
    for (int iter = 0; iter < 300; ++iter) {
      if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS) break;
      const double a = gsl_root_fsolver_x_lower(solver), b = gsl_root_fsolver_x_upper(solver);
      const double root = gsl_root_fsolver_root(solver);
      if (gsl_root_test_interval(a, b, 1.0e-300, 2.0 * std::numeric_limits<double>::epsilon()) == GSL_SUCCESS ||
          f(root) == 0.0) {
        result = Solved<double>{root, Status::ok};
        break;
      }
    }
  }
  gsl_root_fsolver_free(solver);
  return result;
}

/// Expands from `start` in direction `dir` (±1) until f takes the wanted sign
/// (f < 0 for dir = -1, f > 0 for dir = +1), staying inside [limit_lo, limit_hi].
template <class F>
Solved<double> expand_bracket(const F& f, double start, int dir, double limit_lo, double limit_hi,
                              double first_step = 0.5) {
  double step = first_step;
  double z = start;
  for (int i = 0; i < 200; ++i) {
    z = std::clamp(z + dir * step, limit_lo, limit_hi);
    const double value = f(z);
    if ((dir < 0 && value < 0.0) || (dir > 0 && value > 0.0)) return {z, Status::ok};
    if (z == limit_lo || z == limit_hi) break;
    step *= 2.0;
  }
  return Solved<double>::failure(Status::no_bracket);
}

/// The rapidity behind a shock of family `family` (−1: C−, +1: C+) that takes the
/// outer state to the star stretch. The label and momentum jump conditions in the
/// lab frame, m [s/γ] = −[v] and m [(e+p) s γ v] = [p], give after eliminating the
/// Lagrangian speed m
///     H(φ*) = [v] [(e+p) s γ v] + [p] [s/γ] = 0,
/// with one root on each side of the outer rapidity; the family picks the side.
/// H < 0 at φ* = φ_outer for a compression and grows without bound away from it.
Solved<double> shock_star_rapidity(const Material& m, const State& outer, Stretch star, int family) {
  const double p_outer = m.pressure(outer.stretch), p_star = m.pressure(star);
  const double v_outer = std::tanh(outer.rapidity);
  const double labels_outer = label_density(outer), momentum_outer = momentum_density(m, outer);
  const auto hugoniot = [&](double rapidity) {
    const State st{rapidity, star};
    return (std::tanh(rapidity) - v_outer) * (momentum_density(m, st) - momentum_outer) +
           (p_star - p_outer) * (label_density(st) - labels_outer);
  };
  // Increasing away from the outer rapidity on the family's side: g(d) = H(φ_outer + family d).
  // The rarefaction curve's rapidity change |ΔΨ| agrees with the shock's to second order in
  // the strength: bracket the root tightly around it, so that Brent needs few steps.
  // The star moves against the family's direction in a compression (a C− shock slows the
  // left state) and with it in an expansion; the rarefaction curve gives the side.
  const double psi_change = m.riemann_psi(star) - m.riemann_psi(outer.stretch);
  const double direction = psi_change > 0.0 ? family : -family;
  const auto g = [&](double d) { return hugoniot(outer.rapidity + direction * d); };
  const double guess = std::abs(psi_change);
  const double step = 0.02 * guess + 1e-300;
  double lo = 0.0, hi = guess;
  if (g(guess) > 0.0) {
    const Solved<double> below = expand_bracket(g, guess, -1, 0.0, guess, step);
    if (below.ok()) lo = below.value;
  } else {
    lo = guess;
    const Solved<double> above = expand_bracket(g, guess, +1, guess, 1.0e3, step);
    if (!above.ok()) return above;
    hi = above.value;
  }
  const Solved<double> d = g(lo) == 0.0 ? Solved<double>{lo, Status::ok} : find_root(g, lo, hi);
  if (!d.ok()) return d;
  return Solved<double>{outer.rapidity + direction * d.value, Status::ok};
}

/// The star state on a wave curve given the star stretch (rather than pressure).
WaveCurvePoint point_at_stretch(const WaveCurve& curve, Stretch star) {
  const Material& m = curve.material();
  const State& st = curve.state();
  const double sign = curve.side() == Side::left ? -1.0 : 1.0;
  double jump;  // |rapidity change| with sign: positive when the star is compressed relative to the side
  const int family = curve.side() == Side::left ? -1 : +1;
  if (wave_is_shock(m, st, star, family)) {
    const Solved<double> rapidity = shock_star_rapidity(m, st, star, family);
    if (!rapidity.ok()) return WaveCurvePoint{0.0, star, rapidity.status};
    return WaveCurvePoint{rapidity.value, star, Status::ok};
  } else {
    // Invariant of the other family is carried across: Ψ* − Ψ_side.
    jump = m.riemann_psi(star) - (curve.side() == Side::left ? curve.invariant() - st.rapidity
                                                              : st.rapidity - curve.invariant());
  }
  return WaveCurvePoint{st.rapidity + sign * jump, star, Status::ok};
}

/// f(z) = φ*_L − φ*_R for a left star stretch z (ln s); increasing in z.
struct Mismatch {
  const WaveCurve* left;
  const WaveCurve* right;
  double operator()(double z) const {
    const Stretch star_left = Stretch::from_log(z);
    const double p = left->material().pressure(star_left);
    const WaveCurvePoint a = point_at_stretch(*left, star_left);
    const WaveCurvePoint b = right->at_pressure(p);
    if (!b.ok()) return p > right->pressure() ? -kHuge : kHuge;
    return std::clamp(a.rapidity - b.rapidity, -kHuge, kHuge);
  }
};

RiemannSolution collapse(double demanded_psi, double limit_psi, double impact_rapidity) {
  RiemannSolution s;
  s.status = Status::out_of_range;
  s.demanded_psi = demanded_psi;
  s.limit_psi = limit_psi;
  s.impact_rapidity = impact_rapidity;
  return s;
}

/// Star pressure on a wave curve whose star stretch is fixed by Ψ (LD waves, rarefactions).
RiemannSolution parted_pair(const WaveCurve& left, const WaveCurve& right, double min_pressure) {
  RiemannSolution out;
  out.parted = true;
  out.pressure = min_pressure;
  const WaveCurvePoint a = left.at_pressure(min_pressure);
  const WaveCurvePoint b = right.at_pressure(min_pressure);
  out.status = a.ok() && b.ok() ? Status::ok : Status::not_converged;
  out.left = State{a.rapidity, a.stretch};
  out.right = State{b.rapidity, b.stretch};
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
  if (p == pressure_) return WaveCurvePoint{state_.rapidity, state_.stretch, Status::ok};
  const Solved<Stretch> star = material_->stretch_at_pressure(p);
  if (!star.ok()) return WaveCurvePoint{0.0, Stretch{}, star.status};
  return point_at_stretch(*this, star.value);
}

RiemannSolution solve_riemann(const Material& left_material, const State& left, const Material& right_material,
                              const State& right, double min_pressure) {
  // One linearly degenerate material on both sides: the star state is closed form,
  // J+ from the left, J− from the right.
  if (&left_material == &right_material && left_material.linearly_degenerate()) {
    const Material& m = left_material;
    const double j_plus = left.rapidity + m.riemann_psi(left.stretch);
    const double j_minus = right.rapidity - m.riemann_psi(right.stretch);
    const double psi_star = 0.5 * (j_plus - j_minus);
    const double rapidity_star = 0.5 * (j_plus + j_minus);
    if (psi_star >= m.psi_max()) return collapse(psi_star, m.psi_max(), left.rapidity - right.rapidity);
    if (min_pressure > -kInf) {
      const Solved<Stretch> parting = m.stretch_at_pressure(min_pressure);
      if (parting.ok() && psi_star < m.riemann_psi(parting.value)) {
        return parted_pair(WaveCurve(m, left, Side::left), WaveCurve(m, right, Side::right), min_pressure);
      }
    }
    const Solved<Stretch> star = m.stretch_at_psi(psi_star);
    if (!star.ok()) return RiemannSolution{star.status, false, 0.0, {}, {}, psi_star, m.psi_max()};
    RiemannSolution out;
    out.pressure = m.pressure(star.value);
    out.left = out.right = State{rapidity_star, star.value};
    return out;
  }

  const WaveCurve lc(left_material, left, Side::left);
  const WaveCurve rc(right_material, right, Side::right);
  // General: Brent on the left star stretch z = ln s*_L, f(z) = φ*_L − φ*_R increasing.
  const Mismatch f{&lc, &rc};
  const StretchRange range = left_material.admissible();
  double z_hi = range.log_max;
  if (min_pressure > -kInf) {
    const Solved<Stretch> parting = left_material.stretch_at_pressure(min_pressure);
    if (parting.ok()) {
      z_hi = parting.value.log();
      if (f(z_hi) < 0.0) return parted_pair(lc, rc, min_pressure);
      if (f(z_hi) == 0.0) return parted_pair(lc, rc, min_pressure);
    }
  }
  // Start from the left state, or for one material on both sides from the star state
  // the rarefaction curves would give (exact for weak waves), with a step to match.
  double start = std::min(left.stretch.log(), z_hi);
  double first_step = 0.5;
  if (&left_material == &right_material) {
    const double psi_guess = 0.5 * (lc.invariant() - rc.invariant());
    const Solved<Stretch> guess = left_material.stretch_at_psi(std::min(psi_guess, left_material.psi_max()));
    if (guess.ok()) {
      first_step = 1e-3 + 0.05 * std::abs(guess.value.log() - start);
      start = std::min(guess.value.log(), z_hi);
    }
  }
  double lo = start, hi = start;
  const double f_start = f(start);
  if (f_start == 0.0) {
    lo = hi = start;
  } else if (f_start > 0.0) {
    hi = start;
    const Solved<double> b = expand_bracket(f, start, -1, range.log_min, z_hi, first_step);
    if (!b.ok()) {
      // Even at the largest reachable compression the left state outruns the right.
      const Material& weaker = left_material.psi_max() <= right_material.psi_max() ? left_material : right_material;
      return collapse(std::numeric_limits<double>::quiet_NaN(), weaker.psi_max(), left.rapidity - right.rapidity);
    }
    lo = b.value;
  } else {
    lo = start;
    const Solved<double> b = expand_bracket(f, start, +1, range.log_min, z_hi, first_step);
    if (!b.ok()) return RiemannSolution{Status::no_bracket, false, 0.0, {}, {}, 0.0, 0.0};
    hi = b.value;
  }
  double z = lo;
  if (lo != hi) {
    const Solved<double> root = find_root(f, lo, hi);
    if (!root.ok()) return RiemannSolution{root.status, false, 0.0, {}, {}, 0.0, 0.0};
    z = root.value;
  }
  const Stretch star_left = Stretch::from_log(z);
  RiemannSolution out;
  out.pressure = left_material.pressure(star_left);
  const WaveCurvePoint a = point_at_stretch(lc, star_left);
  const WaveCurvePoint b = rc.at_pressure(out.pressure);
  if (!b.ok()) return RiemannSolution{b.status, false, 0.0, {}, {}, 0.0, 0.0};
  const double rapidity = 0.5 * (a.rapidity + b.rapidity);
  out.left = State{rapidity, star_left};
  out.right = State{rapidity, b.stretch};
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
  const Solved<Stretch> on_curve =
      psi_star < m.psi_max() ? m.stretch_at_psi(psi_star) : Solved<Stretch>::failure(Status::out_of_range);
  const bool jump_or_fan =
      m.linearly_degenerate() || (on_curve.ok() && !wave_is_shock(m, state, on_curve.value, family));
  Stretch star;
  if (jump_or_fan) {
    if (psi_star >= m.psi_max()) return collapse(psi_star, m.psi_max(), impact);
    // A wall that cannot pull lets go before the material would reach that tension (the
    // rigid fluid cannot even be put in tension: its curve ends at p = 0).
    if (min_pressure > -kInf) {
      const Solved<Stretch> parting = m.stretch_at_pressure(min_pressure);
      if (parting.ok() && psi_star < m.riemann_psi(parting.value)) return solve_free_end(m, state, side);
    }
    if (!on_curve.ok()) return RiemannSolution{Status::not_converged, false, 0.0, {}, {}, psi_star, m.psi_max()};
    star = on_curve.value;
  } else {
    // A shock: solve φ*(z) = φ_wall on the wave curve for the star stretch z = ln s*; the
    // mismatch g grows with z (the less compressed the star, the more of the side's motion
    // towards the wall it keeps), so its sign at the side's own stretch says which way to go.
    const auto g = [&curve, wall_rapidity, side](double z) {
      const WaveCurvePoint pt = point_at_stretch(curve, Stretch::from_log(z));
      return side == Side::left ? pt.rapidity - wall_rapidity : wall_rapidity - pt.rapidity;
    };
    const double z_side = state.stretch.log();
    const StretchRange range = m.admissible();
    const int direction = g(z_side) > 0.0 ? -1 : +1;
    const Solved<double> far = expand_bracket(g, z_side, direction, range.log_min, range.log_max);
    if (!far.ok()) {
      if (direction < 0) return collapse(std::numeric_limits<double>::quiet_NaN(), m.psi_max(), impact);
      return RiemannSolution{far.status, false, 0.0, {}, {}, 0.0, 0.0};
    }
    const Solved<double> root =
        direction < 0 ? find_root(g, far.value, z_side) : find_root(g, z_side, far.value);
    if (!root.ok()) return RiemannSolution{root.status, false, 0.0, {}, {}, 0.0, 0.0};
    star = Stretch::from_log(root.value);
  }
  RiemannSolution out;
  out.pressure = m.pressure(star);
  // A wall that cannot pull lets go: the end is free.
  if (out.pressure < min_pressure) return solve_free_end(m, state, side);
  out.left = out.right = State{wall_rapidity, star};
  return out;
}

RiemannSolution solve_free_end(const Material& m, const State& state, Side side) {
  const double p_free = std::max(0.0, m.cavitation_pressure());
  const WaveCurve curve(m, state, side);
  RiemannSolution out;
  out.parted = true;
  out.pressure = p_free;
  const WaveCurvePoint pt = curve.at_pressure(p_free);
  out.status = pt.status;
  out.left = out.right = State{pt.rapidity, pt.stretch};
  return out;
}

double label_density(const State& st) { return st.stretch.value() / std::cosh(st.rapidity); }

double momentum_density(const Material& m, const State& st) {
  return m.enthalpy_density(st.stretch) * st.stretch.value() * std::sinh(st.rapidity);
}

double energy_density(const Material& m, const State& st) {
  // ((e+p)γ² − p) s/γ = (e+p) s cosh φ − p s / cosh φ
  const double s = st.stretch.value();
  const double ch = std::cosh(st.rapidity);
  return m.enthalpy_density(st.stretch) * s * ch - m.pressure(st.stretch) * s / ch;
}

void require_solved(const RiemannSolution& sol, const Material& m, double t, double x) {
  if (sol.status == Status::ok) return;
  std::ostringstream os;
  os.precision(12);
  if (sol.status != Status::out_of_range) {
    os << "the Riemann problem at t = " << t << ", x = " << x << " could not be solved (" << to_string(sol.status)
       << ")";
    throw NumericalError(os.str());
  }
  os << "no classical solution at t = " << t << ", x = " << x << ": an impact at relative speed "
     << std::tanh(sol.impact_rapidity) << " c would crush the material '" << m.model() << "' to zero length";
  if (std::isfinite(sol.demanded_psi)) {
    // Linearly degenerate: the compressed state would need Ψ = demanded ≥ Ψ_max; tanh Ψ is
    // the impact speed relative to the compressed material (the wall's frame for a wall).
    os << ": it demands an impact speed v = tanh(Psi) = " << std::tanh(sol.demanded_psi)
       << " c relative to the compressed material, at or above the material's limit " << std::tanh(sol.limit_psi)
       << " c";
  } else {
    os << " (its limit: impact speed " << std::tanh(sol.limit_psi) << " c relative to the compressed material)";
  }
  if (m.model() == "hooke") os << "; for hooke the limit is the wave speed V = " << std::tanh(sol.limit_psi) << " c";
  throw InadmissibleError(os.str());
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

FrontSpeeds characteristic_speeds(const Material& m, const State& state, int family) {
  const double c = m.sound_speed(state.stretch);
  if (c == 1.0) {
    // Signals at light speed: dX/dt = ± e^∓φ / s, dx/dt = ±1 exactly.
    return FrontSpeeds{family * std::exp(-family * state.rapidity - state.stretch.log()), static_cast<double>(family)};
  }
  // cosh φ ± c sinh φ = ((1 ± c) e^φ + (1 ∓ c) e^−φ)/2 and sinh φ ± c cosh φ likewise:
  // free of cancellation for c → 1 and large |φ| (for c = 1 exactly e^±φ).
  const double ep = std::exp(state.rapidity), em = 1.0 / ep;
  const double a = family > 0 ? 1.0 + c : 1.0 - c;
  const double b = family > 0 ? 1.0 - c : 1.0 + c;
  const double denominator = 0.5 * (a * ep + b * em);
  const double numerator = 0.5 * (a * ep - b * em);
  return FrontSpeeds{family * c / (state.stretch.value() * denominator), numerator / denominator};
}

double characteristic_speed(const Material& m, const State& state, int family) {
  return characteristic_speeds(m, state, family).lagrangian;
}

double characteristic_lab_speed(const Material& m, const State& state, int family) {
  return characteristic_speeds(m, state, family).lab;
}

Solved<double> shock_dissipation_rate(const Material& m, const State& left, const State& right) {
  const double phi_l = left.rapidity, phi_r = right.rapidity;
  const double s_l = left.stretch.value();
  const double ch_l = std::cosh(phi_l), ch_r = std::cosh(phi_r);
  const double v_l = std::tanh(phi_l), v_r = std::tanh(phi_r);
  const double p_l = m.pressure(left.stretch), p_r = m.pressure(right.stretch);
  const double dp = p_r - p_l;
  // [v] and [τ] to full relative precision however weak the jump:
  //   [v] = sinh(φr − φl)/(cosh φl cosh φr),
  //   [τ] = τl (exp(ln(sr/sl) + ln(cosh φl / cosh φr)) − 1),
  //   cosh φl / cosh φr − 1 = 2 sinh((φl + φr)/2) sinh((φl − φr)/2) / cosh φr.
  const double dv = std::sinh(phi_r - phi_l) / (ch_l * ch_r);
  const double cosh_ratio =
      std::log1p(2.0 * std::sinh(0.5 * (phi_l + phi_r)) * std::sinh(0.5 * (phi_l - phi_r)) / ch_r);
  const double dtau = s_l / ch_l * std::expm1(right.stretch.log() - left.stretch.log() + cosh_ratio);
  if (dtau == 0.0) return {0.0, Status::ok};
  const double speed = -dv / dtau;  // label jump condition m [τ] = −[v]
  // A strong shock: the energy jump and the flux jump directly, their difference is not small.
  if (std::abs(right.stretch.log() - left.stretch.log()) > 0.3) {
    const double jump_E = energy_density(m, right) - energy_density(m, left);
    return {speed * jump_E - (p_r * v_r - p_l * v_l), Status::ok};
  }
  // δτ and δM by 8-point Gauss–Legendre on the halves of θ ∈ [0, 1]: f' is analytic along the
  // path and the path is short, so the rule is exact to round-off.
  static constexpr double kNode[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static constexpr double kWeight[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  double delta_tau = 0.0, delta_momentum = 0.0;
  for (int i = 0; i < 8; ++i) {
    for (double sign : {-1.0, 1.0}) {
      const double theta = 0.25 + 0.5 * (i / 4) + 0.25 * sign * kNode[i % 4];
      const double p = p_l + theta * dp, v = v_l + theta * (v_r - v_l);
      const Solved<Stretch> st = m.stretch_at_pressure(p);
      if (!st.ok()) return Solved<double>::failure(st.status);
      const double s = st.value.value();
      const double gamma = 1.0 / std::sqrt((1.0 - v) * (1.0 + v));
      const double h = m.enthalpy_density(st.value) * s;
      // τ' = s'(p)[p]/γ + s (dγ⁻¹/dv)[v], s'(p) = −1/W''; M' = s [p] γ v + h γ³ [v].
      const double tau_rate = -dp / (m.stiffness(st.value) * gamma) - s * v * gamma * dv;
      const double momentum_rate = s * dp * gamma * v + h * gamma * gamma * gamma * dv;
      const double weight = 0.25 * kWeight[i % 4] * (0.5 - theta);
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
  const double speed = -(std::tanh(star.rapidity) - std::tanh(outer.rapidity)) /
                       (label_density(star) - label_density(outer));
  return FrontSpeeds{speed, std::tanh(outer.rapidity) + speed * label_density(outer)};
}

}  // namespace rigidity
