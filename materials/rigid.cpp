/// `rigid`: the most rigid material relativity allows, shocks and sound both at c
/// (McCrea 1952, Brotas 1968; Brotas & Fernandes, physics/0307019, §3.2).
///
/// With t = ln s every formula is written so that a strain of 1e-12 keeps full
/// relative precision (1/s² − 1 = expm1(−2t)) and nothing overflows whose true value
/// is below 1e308.

#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/parameters.hpp"
#include "rigidity/registry.hpp"

namespace rigidity {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

class Rigid final : public Material {
 public:
  static constexpr std::string_view kName = "rigid";

  static std::string doc() {
    return "Relativistic rigid material (McCrea 1952, Brotas 1968): shock and sound waves run at c. "
           "p = (rho00/2)(1/s^2 - 1), e = (rho00/2)(1/s^2 + 1); c_s = c everywhere; "
           "unbounded pressure as s -> 0, maximum tension -rho00/2 as s -> infinity.";
  }
  static std::vector<ParameterSpec> parameters() { return {rest_density_parameter()}; }

  explicit Rigid(const ParameterValues& values) : Material(values.number("rest_density")) {}

  [[nodiscard]] std::string_view model() const override { return kName; }

  /// W = (ρ00/2)(1/s + s) = ρ00 cosh(ln s): rest energy plus the paper's eq. (16).
  [[nodiscard]] double strain_energy(Stretch s) const override { return rest_density() * std::cosh(s.log()); }

  /// p = (ρ00/2)(1/s² − 1): paper eq. (19), docs/materials.md.
  [[nodiscard]] double pressure(Stretch s) const override { return 0.5 * rest_density() * std::expm1(-2.0 * s.log()); }

  /// e = (ρ00/2)(1/s² + 1) = ρ00 (1 + (1/s² − 1)/2): paper eq. (24), docs/materials.md.
  /// e + p = ρ00/s²: exact where e and p nearly cancel (far tension).
  [[nodiscard]] double enthalpy_density(Stretch s) const override { return rest_density() * std::exp(-2.0 * s.log()); }

  /// p and e + p from one exponential: e + p = ρ00 (1 + (1/s² − 1)) where 1/s² − 1 > −1/4;
  /// far in tension, where that sum cancels, e + p from its own exponential.
  [[nodiscard]] LawValues laws_at(Stretch s) const override {
    const double q = std::expm1(-2.0 * s.log());
    const double enthalpy = q > -0.25 ? rest_density() * (1.0 + q) : enthalpy_density(s);
    return {0.5 * rest_density() * q, enthalpy, 1.0};
  }

  [[nodiscard]] double energy_density(Stretch s) const override {
    return rest_density() * (1.0 + 0.5 * std::expm1(-2.0 * s.log()));
  }

  /// c_s = 1: the defining property (paper §3.2, V_b = V_p = c).
  [[nodiscard]] double sound_speed(Stretch) const override { return 1.0; }

  /// W'' = ρ00/s³ (derivative of eq. (16)).
  [[nodiscard]] double stiffness(Stretch s) const override { return rest_density() * std::exp(-3.0 * s.log()); }

  /// Ψ = ∫_s^1 dσ/σ = −ln s (docs/physics.md with c_s = 1).
  [[nodiscard]] double riemann_psi(Stretch s) const override { return -s.log(); }

  /// ln s = −½ ln(1 + 2p/ρ00), the inverse of eq. (19); reachable for −ρ00/2 < p < ∞.
  [[nodiscard]] Solved<Stretch> stretch_at_pressure(double p) const override {
    if (!(p > max_tension() && p < max_pressure())) return Solved<Stretch>::failure(Status::out_of_range);
    const double log_s = -0.5 * std::log1p(2.0 * p / rest_density());
    if (!std::isfinite(log_s)) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(log_s)};
  }

  /// ln s = −Ψ; every finite Ψ is reachable.
  [[nodiscard]] Solved<Stretch> stretch_at_psi(double psi) const override {
    if (!std::isfinite(psi)) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(-psi)};
  }

  [[nodiscard]] double max_pressure() const override { return kInfinity; }
  /// lim_{s→∞} p = −ρ00/2 (paper, fig. 3).
  [[nodiscard]] double max_tension() const override { return -0.5 * rest_density(); }
  [[nodiscard]] double psi_max() const override { return kInfinity; }
  [[nodiscard]] double psi_min() const override { return -kInfinity; }
  /// Both families move at ±c: every front is a contact-like jump.
  [[nodiscard]] bool linearly_degenerate() const override { return true; }
  [[nodiscard]] bool sound_at_light_speed() const override { return true; }
};

RIGIDITY_REGISTER_MATERIAL(Rigid);

}  // namespace
}  // namespace rigidity
