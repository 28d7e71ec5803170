/// `constant_sound_speed`: dp/de = V² at every stretch (docs/materials.md), the Smoller–Temple
/// barotropic fluid p = V² e after a constant shift that puts p = 0, e = ρ00 at s = 1.
///
/// With k = 1 + V² and t = ln s:
///
///   e + p = ρ00 s^{−k}                       [d(e s)/ds = −p and de = dp/V² give d ln(e + p)/d ln s = −k]
///   p     = ρ00 V²/k (s^{−k} − 1)
///   e     = ρ00 (s^{−k} + V²)/k
///   W     = e s = ρ00 (s^{−V²} + V² s)/k
///   W''   = ρ00 V² s^{−(k+1)},   c_s = V,   Ψ = −V ln s.
///
/// Genuinely nonlinear for V < 1 (real shocks and rarefaction fans); at V = 1 it is the
/// `rigid` law and both families are linearly degenerate.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/parameters.hpp"
#include "rigidity/registry.hpp"

namespace rigidity {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

class ConstantSoundSpeed final : public Material {
 public:
  static constexpr std::string_view kName = "constant_sound_speed";

  static std::string doc() {
    return "Constant sound speed, dp/de = V^2 (Smoller-Temple fluid after a constant shift): "
           "p = rho00 V^2/(1 + V^2) (s^-(1 + V^2) - 1), e + p = rho00 s^-(1 + V^2). Genuinely nonlinear "
           "(real shocks and rarefaction fans) for V < 1; V = 1 is `rigid`.";
  }
  static std::vector<ParameterSpec> parameters() {
    return {rest_density_parameter(), ParameterSpec::number("sound_speed", "V: sound speed, dp/de = V^2")
                                          .with_dimension(Dimension::velocity)
                                          .require()
                                          .above(0.0)
                                          .at_most(1.0)};
  }

  explicit ConstantSoundSpeed(const ParameterValues& values)
      : Material(values.number("rest_density")), v_(values.number("sound_speed")), k_(1.0 + v_ * v_) {
    if (!(v_ > 0.0 && v_ <= 1.0)) throw std::invalid_argument("constant_sound_speed: sound_speed must be in (0, 1]");
  }

  [[nodiscard]] std::string_view model() const override { return kName; }

  /// W = ρ00 (s^{−V²} + V² s)/k.
  [[nodiscard]] double strain_energy(Stretch s) const override {
    const double t = s.log();
    return rest_density() * (std::exp(-v_ * v_ * t) + v_ * v_ * std::exp(t)) / k_;
  }

  /// p = ρ00 V²/k (s^{−k} − 1) (docs/materials.md).
  [[nodiscard]] double pressure(Stretch s) const override {
    return rest_density() * v_ * v_ / k_ * std::expm1(-k_ * s.log());
  }

  /// e + p = ρ00 s^{−k}.
  [[nodiscard]] double enthalpy_density(Stretch s) const override { return rest_density() * std::exp(-k_ * s.log()); }

  /// e = ρ00 (s^{−k} + V²)/k: as ρ00 (1 + (s^{−k} − 1)/k) in compression, and in tension as
  /// (e + p) − p with e + p = ρ00 s^{−k}, so that e + p never rounds below 0.
  [[nodiscard]] double energy_density(Stretch s) const override {
    const double t = s.log();
    if (t >= 0.0) return rest_density() * std::exp(-k_ * t) - pressure(s);
    return rest_density() * (1.0 + std::expm1(-k_ * t) / k_);
  }

  [[nodiscard]] double sound_speed(Stretch) const override { return v_; }

  /// p and e + p from one q = s^{−k} − 1: p = ρ00 V² q/k, e + p = ρ00 (1 + q), the latter
  /// from its own exponential where 1 + q would lose digits (q below −1/4, in tension).
  [[nodiscard]] LawValues laws_at(Stretch s) const override {
    const double q = std::expm1(-k_ * s.log());
    const double enthalpy = q > -0.25 ? rest_density() * (1.0 + q) : enthalpy_density(s);
    return {rest_density() * v_ * v_ / k_ * q, enthalpy, v_};
  }

  /// W'' = ρ00 V² s^{−(k+1)}.
  [[nodiscard]] double stiffness(Stretch s) const override {
    return rest_density() * v_ * v_ * std::exp(-(k_ + 1.0) * s.log());
  }

  /// Ψ = ∫_s^1 V dσ/σ = −V ln s.
  [[nodiscard]] double riemann_psi(Stretch s) const override { return -v_ * s.log(); }

  /// ln s = −ln(1 + k p/(ρ00 V²))/k; reachable for −ρ00 V²/k < p < ∞.
  [[nodiscard]] Solved<Stretch> stretch_at_pressure(double p) const override {
    if (!(p > max_tension() && p < max_pressure())) return Solved<Stretch>::failure(Status::out_of_range);
    const double log_s = -std::log1p(k_ * p / (rest_density() * v_ * v_)) / k_;
    if (!std::isfinite(log_s)) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(log_s)};
  }

  /// ln s = −Ψ/V; every finite Ψ is reachable.
  [[nodiscard]] Solved<Stretch> stretch_at_psi(double psi) const override {
    const double log_s = -psi / v_;
    if (!std::isfinite(log_s)) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(log_s)};
  }

  [[nodiscard]] double max_pressure() const override { return kInfinity; }
  /// lim_{s→∞} p = −ρ00 V²/k.
  [[nodiscard]] double max_tension() const override { return -rest_density() * v_ * v_ / k_; }
  [[nodiscard]] double psi_max() const override { return kInfinity; }
  [[nodiscard]] double psi_min() const override { return -kInfinity; }
  /// Only at V = 1, where every wave moves at ±c; for V < 1 the lab speed
  /// tanh(φ ± artanh V) changes across a wave: genuinely nonlinear.
  [[nodiscard]] bool linearly_degenerate() const override { return v_ == 1.0; }

 private:
  double v_;  ///< V: the sound speed
  double k_;  ///< 1 + V²
};

RIGIDITY_REGISTER_MATERIAL(ConstantSoundSpeed);

}  // namespace
}  // namespace rigidity
