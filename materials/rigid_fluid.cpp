/// `rigid_fluid`: the "rigid" fluid e = ρ00 c² + p, the stiffest fluid relativity allows
/// (physics/0307019, footnote 4: eliminating s between eqs. (19) and (24)). In
/// compression it is the `rigid` law; it carries no tension: at p = 0 it cavitates
/// (the column parts and free ends appear), so its admissible stretches are s ≤ 1.

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

class RigidFluid final : public Material {
 public:
  static constexpr std::string_view kName = "rigid_fluid";

  static std::string doc() {
    return "Relativistic rigid fluid, e = rho00 c^2 + p (c_s = c): the rigid law (McCrea 1952, Brotas 1968) "
           "p = (rho00/2)(1/s^2 - 1) in compression, s <= 1. Carries no tension: where it would, it "
           "cavitates (p = 0, the column parts, free ends appear).";
  }
  static std::vector<ParameterSpec> parameters() { return {rest_density_parameter()}; }

  explicit RigidFluid(const ParameterValues& values) : Material(values.number("rest_density")) {}

  [[nodiscard]] std::string_view model() const override { return kName; }

  /// W = ρ00 cosh(ln s), as for `rigid` (paper eq. (16) plus rest energy).
  [[nodiscard]] double strain_energy(Stretch s) const override { return rest_density() * std::cosh(s.log()); }

  /// p = (ρ00/2)(1/s² − 1): paper eq. (19).
  [[nodiscard]] double pressure(Stretch s) const override { return 0.5 * rest_density() * std::expm1(-2.0 * s.log()); }

  /// e = ρ00 + p: the law itself (paper footnote 4, docs/materials.md).
  /// e + p = ρ00/s².
  [[nodiscard]] double enthalpy_density(Stretch s) const override { return rest_density() * std::exp(-2.0 * s.log()); }

  /// p and e + p from one exponential (e + p = ρ00 + 2p = ρ00 (1 + (1/s² − 1)), no cancellation
  /// for s ≤ 1, the whole range of the fluid).
  [[nodiscard]] LawValues laws_at(Stretch s) const override {
    const double q = std::expm1(-2.0 * s.log());
    return {0.5 * rest_density() * q, rest_density() * (1.0 + q), 1.0};
  }

  [[nodiscard]] double energy_density(Stretch s) const override { return rest_density() + pressure(s); }

  /// c_s² = dp/de = 1.
  [[nodiscard]] double sound_speed(Stretch) const override { return 1.0; }

  /// W'' = ρ00/s³.
  [[nodiscard]] double stiffness(Stretch s) const override { return rest_density() * std::exp(-3.0 * s.log()); }

  /// Ψ = −ln s (docs/physics.md with c_s = 1), ≥ 0 on the admissible range.
  [[nodiscard]] double riemann_psi(Stretch s) const override { return -s.log(); }

  /// ln s = −½ ln(1 + 2p/ρ00); reachable for 0 ≤ p < ∞ (p = 0 is the natural state).
  [[nodiscard]] Solved<Stretch> stretch_at_pressure(double p) const override {
    if (!(p >= max_tension() && p < max_pressure())) return Solved<Stretch>::failure(Status::out_of_range);
    const double log_s = -0.5 * std::log1p(2.0 * p / rest_density());
    if (!std::isfinite(log_s)) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(log_s)};
  }

  /// ln s = −Ψ; reachable for 0 ≤ Ψ < ∞.
  [[nodiscard]] Solved<Stretch> stretch_at_psi(double psi) const override {
    if (!(psi >= psi_min() && psi < psi_max())) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(-psi)};
  }

  /// s ∈ (0, 1]: compression and the natural state.
  [[nodiscard]] StretchRange admissible() const override { return {-kInfinity, 0.0}; }
  [[nodiscard]] double max_pressure() const override { return kInfinity; }
  /// p(1) = 0: a fluid carries no tension.
  [[nodiscard]] double max_tension() const override { return 0.0; }
  [[nodiscard]] double psi_max() const override { return kInfinity; }
  /// Ψ(1) = 0.
  [[nodiscard]] double psi_min() const override { return 0.0; }
  /// Below p = 0 the column parts.
  [[nodiscard]] double cavitation_pressure() const override { return 0.0; }
  /// c_s = 1: both families move at ±c.
  [[nodiscard]] bool linearly_degenerate() const override { return true; }
  [[nodiscard]] bool sound_at_light_speed() const override { return true; }
};

RIGIDITY_REGISTER_MATERIAL(RigidFluid);

}  // namespace
}  // namespace rigidity
