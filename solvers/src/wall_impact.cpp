#include "rigidity/solvers/wall_impact.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include "rigidity/solvers/riemann.hpp"

namespace rigidity {

/// An unstrained bar at speed v strikes a fixed (push-only) wall on its right: the state
/// behind the reflected front from the exact Riemann solver, and the front's speed.
///
/// The front speed relative to the unstrained bar: shock_speeds gives the front's
/// Lagrangian speed m = dX/dt (< 0, labels per unit lab time). In the bar's rest frame the
/// unstrained labels are proper lengths (x' = X, as x_X = s/γ with s = 1) and its clock
/// reads t' = γ (t − v x). Along the front dx = λ dt with lab speed λ = v + (s/γ) m = v + m/γ
/// (dx = (s/γ) dX + v dt), so dt' = γ (1 − v λ) dt = (1/γ − v m) dt and
///
///     u = |dX/dt'| = −m γ / (1 − m γ v),        γ = cosh φ, γ v = sinh φ, φ = artanh v:
///
/// free of cancellation (m < 0). For a linearly degenerate material m = −c_s(1)/(γ (1 − v c_s(1)))
/// and u = c_s(1); label conservation across the front gives the check u = γ v/(γ − s).
ImpactOutcome wall_impact(const Material& material, double v) {
  const double rapidity = std::atanh(v);
  const State bar{rapidity, Stretch::natural()};
  const RiemannSolution solution = solve_wall(material, bar, Side::left, 0.0, 0.0);
  if (solution.status != Status::ok) return {Impact{v}, solution.status};
  const State& star = solution.left;
  const double m = shock_speeds(material, bar, star, -1).lagrangian;
  double u = -m * std::cosh(rapidity) / (1.0 - m * std::sinh(rapidity));
  // No front outruns light: a light-speed front (c_s = 1) may round to an ulp above c.
  if (u > 1.0 && u <= 1.0 + 4.0 * std::numeric_limits<double>::epsilon()) u = 1.0;
  const Impact impact{v, star.stretch.value(), solution.pressure, u};
  if (!std::isfinite(impact.s) || !std::isfinite(impact.p) || !std::isfinite(impact.front_speed) || !(m < 0.0))
    return {impact, Status::not_converged};
  return {impact, Status::ok};
}

/// The impact speed from which on the bar is crushed (the state behind the front leaves the
/// admissible range: zero length for `hooke`), if any. Linearly degenerate: J+ = φ + Ψ(1) = φ
/// is carried to the wall at rest, so Ψ* = φ and the limit is v = tanh Ψ_max. Otherwise (a
/// shock) the speed is bisected in rapidity between impacts with and without a solution.
std::optional<double> crush_speed(const Material& material) {
  const double psi_max = material.psi_max();
  if (!std::isfinite(psi_max)) return std::nullopt;
  if (material.linearly_degenerate()) return std::tanh(psi_max);
  const auto crushed = [&](double rapidity) { return wall_impact(material, std::tanh(rapidity)).status != Status::ok; };
  double lo = 0.0, hi = 20.0;  // tanh 20 = 1 − 8e-18: as close to c as a double gets
  if (!crushed(hi)) return std::nullopt;
  for (int i = 0; i < 200 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (crushed(mid) ? hi : lo) = mid;
  }
  return std::tanh(hi);
}

std::optional<double> hugoniot_speed(const Material& material, Stretch s) {
  const Solved<double> rapidity = hugoniot_rapidity(material, State{0.0, Stretch::natural()}, s, +1);
  if (!rapidity.ok() || !std::isfinite(rapidity.value)) return std::nullopt;
  return std::abs(std::tanh(rapidity.value));
}

double isentrope_speed(const Material& material, Stretch s) {
  return std::tanh(std::abs(material.riemann_psi(s) - material.riemann_psi(Stretch::natural())));
}

}  // namespace rigidity
