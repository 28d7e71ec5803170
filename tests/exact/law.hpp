#pragma once
/// Material laws for the independent references (tests/exact): the laws of docs/materials.md written
/// out in closed form from the spec's own formulas, with none of the rewriting for
/// precision that materials/*.cpp does, so that a mistake in a material's file cannot be
/// repeated here. A law is a function of the stretch s itself (not ln s): the references
/// are meant for moderate states, where that costs nothing.
///
///   p(s) = −W'(s),  e(s) = W(s)/s,  c_s² = s W''(s)/(e + p),  Ψ(s) = ∫_s^1 c_s(σ)/σ dσ   (docs/physics.md)
///
/// `MaterialLaw` adapts a registered Material through its p, e, c_s and Ψ only (never its
/// inverses), for the tests that iterate over the registry.
///
/// Templated on the arithmetic: `long double` gives the weak-shock dissipation its digits.

#include <cmath>
#include <limits>
#include <string>

#include "exact/bisection.hpp"
#include "rigidity/material.hpp"

namespace rigidity::exact {

template <class Real>
class Law {
 public:
  virtual ~Law() = default;

  [[nodiscard]] virtual std::string name() const = 0;
  /// ρ00
  [[nodiscard]] virtual Real rest_density() const = 0;
  /// p(s), compression positive
  [[nodiscard]] virtual Real pressure(Real s) const = 0;
  /// e(s) = W(s)/s, rest energy included
  [[nodiscard]] virtual Real energy_density(Real s) const = 0;
  /// w = e + p
  [[nodiscard]] virtual Real enthalpy(Real s) const { return energy_density(s) + pressure(s); }
  /// c_s(s)
  [[nodiscard]] virtual Real sound_speed(Real s) const = 0;
  /// Ψ(s) = ∫_s^1 c_s(σ)/σ dσ
  [[nodiscard]] virtual Real psi(Real s) const = 0;
  /// Admissible stretches: ln s in [log_s_min, log_s_max].
  [[nodiscard]] virtual Real log_s_min() const { return -std::numeric_limits<Real>::infinity(); }
  [[nodiscard]] virtual Real log_s_max() const { return std::numeric_limits<Real>::infinity(); }
  /// Below this pressure the material parts (a fluid cavitates at 0).
  [[nodiscard]] virtual Real cavitation_pressure() const { return -std::numeric_limits<Real>::infinity(); }
  /// sup p (s → smallest stretch) and inf p (s → largest), by default read off the law far out.
  [[nodiscard]] virtual Real max_pressure() const { return pressure(std::exp(search_log_min())); }
  [[nodiscard]] virtual Real max_tension() const { return pressure(std::exp(search_log_max())); }

  /// The stretch at pressure p by bisection on ln s (p falls as s grows); NaN if unreachable.
  [[nodiscard]] virtual Real stretch_at_pressure(Real p) const {
    const Real log_s =
        bisect<Real>([&](Real t) { return pressure(std::exp(t)) - p; }, search_log_min(), search_log_max());
    return std::exp(log_s);
  }
  /// The stretch at Ψ = psi by bisection on ln s (Ψ falls as s grows); NaN if unreachable.
  [[nodiscard]] virtual Real stretch_at_psi(Real target) const {
    const Real log_s =
        bisect<Real>([&](Real t) { return psi(std::exp(t)) - target; }, search_log_min(), search_log_max());
    return std::exp(log_s);
  }

 protected:
  Law() = default;
  Law(const Law&) = default;
  Law& operator=(const Law&) = default;

  /// Where the bisections look: the admissible range cut to stretches from e^−40 to e^40.
  [[nodiscard]] Real search_log_min() const { return std::fmax(log_s_min(), Real(-40)); }
  [[nodiscard]] Real search_log_max() const { return std::fmin(log_s_max(), Real(40)); }
};

/// The built-in laws of docs/materials.md.
enum class Model { rigid, hooke, rigid_fluid, constant_sound_speed };

template <class Real>
class ClosedFormLaw final : public Law<Real> {
 public:
  /// `speed` is hooke's wave_speed V or constant_sound_speed's sound_speed V (ignored otherwise).
  ClosedFormLaw(Model model, Real rest_density, Real speed = Real(1)) : model_(model), rho_(rest_density), b_(speed) {
    // V = 1 is `rigid` (docs/materials.md); hooke's formulas divide by 1 − V².
    if (model_ == Model::hooke && b_ == Real(1)) model_ = Model::rigid;
  }

  [[nodiscard]] std::string name() const override {
    switch (model_) {
      case Model::rigid: return "rigid";
      case Model::hooke: return "hooke";
      case Model::rigid_fluid: return "rigid_fluid";
      case Model::constant_sound_speed: return "constant_sound_speed";
    }
    return "?";
  }
  [[nodiscard]] Model model() const { return model_; }
  [[nodiscard]] Real rest_density() const override { return rho_; }

  [[nodiscard]] Real pressure(Real s) const override {
    switch (model_) {
      case Model::rigid:
      case Model::rigid_fluid: return rho_ / 2 * (1 / (s * s) - 1);  // p = (ρ00/2)(1/s² − 1)
      case Model::hooke: return energy_density(s) / r(s) - rho_;     // p = e/R − ρ00
      case Model::constant_sound_speed: {
        const Real k = 1 + b_ * b_;  // p = ρ00 V²/(1 + V²) (s^−(1+V²) − 1)
        return rho_ * b_ * b_ / k * (std::pow(s, -k) - 1);
      }
    }
    return 0;
  }

  [[nodiscard]] Real energy_density(Real s) const override {
    switch (model_) {
      case Model::rigid: return rho_ / 2 * (1 / (s * s) + 1);             // e = (ρ00/2)(1/s² + 1)
      case Model::rigid_fluid: return rho_ + pressure(s);                 // e = ρ00 + p
      case Model::hooke: return rho_ * (r(s) - b_ * b_) / (1 - b_ * b_);  // e = ρ00 (R − b²)/(1 − b²)
      case Model::constant_sound_speed: {
        // dp/de = V² with e = ρ00 at p = 0: e = ρ00 + p/V²
        return rho_ + pressure(s) / (b_ * b_);
      }
    }
    return 0;
  }

  [[nodiscard]] Real sound_speed(Real s) const override {
    switch (model_) {
      case Model::rigid:
      case Model::rigid_fluid: return 1;
      case Model::hooke: return std::sqrt(b_ * b_ * s * s / (b_ * b_ * s * s + 1 - b_ * b_));
      case Model::constant_sound_speed: return b_;
    }
    return 0;
  }

  /// Ψ = ∫_s^1 c_s/σ dσ: −ln s for c_s = 1, −V ln s for c_s = V; for hooke
  /// c_s/σ = b/sqrt(b²σ² + a²), whose integral is asinh(bσ/a).
  [[nodiscard]] Real psi(Real s) const override {
    switch (model_) {
      case Model::rigid:
      case Model::rigid_fluid: return -std::log(s);
      case Model::hooke: {
        const Real a = std::sqrt(1 - b_ * b_);
        return std::asinh(b_ / a) - std::asinh(b_ * s / a);
      }
      case Model::constant_sound_speed: return -b_ * std::log(s);
    }
    return 0;
  }

  [[nodiscard]] Real log_s_max() const override {
    return model_ == Model::rigid_fluid ? Real(0) : std::numeric_limits<Real>::infinity();
  }
  [[nodiscard]] Real cavitation_pressure() const override {
    return model_ == Model::rigid_fluid ? Real(0) : -std::numeric_limits<Real>::infinity();
  }
  [[nodiscard]] Real max_pressure() const override {
    return model_ == Model::hooke ? rho_ * b_ * b_ / (1 - b_ * b_) : std::numeric_limits<Real>::infinity();
  }
  [[nodiscard]] Real max_tension() const override {
    switch (model_) {
      case Model::rigid: return -rho_ / 2;
      case Model::rigid_fluid: return 0;
      case Model::hooke: return -rho_ * b_ / (1 + b_);  // R → b as s → ∞
      case Model::constant_sound_speed: return -rho_ * b_ * b_ / (1 + b_ * b_);
    }
    return 0;
  }

  /// Inverse of p(s): s⁻² = 1 + 2p/ρ00 (rigid); R = b²/(b² − (1 − b²) p/ρ00) from p = e/R − ρ00,
  /// then s = a/sqrt(R² − b²) (hooke); s = (1 + (1 + V²) p/(ρ00 V²))^{−1/(1+V²)}.
  [[nodiscard]] Real stretch_at_pressure(Real p) const override {
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    if (!(p > max_tension() || (model_ == Model::rigid_fluid && p == 0)) || !(p < max_pressure())) return nan;
    switch (model_) {
      case Model::rigid:
      case Model::rigid_fluid: return 1 / std::sqrt(1 + 2 * p / rho_);
      case Model::hooke: {
        const Real a2 = 1 - b_ * b_, R = b_ * b_ / (b_ * b_ - a2 * p / rho_);
        return std::sqrt(a2 / (R * R - b_ * b_));
      }
      case Model::constant_sound_speed: {
        const Real k = 1 + b_ * b_;
        return std::pow(1 + k * p / (rho_ * b_ * b_), -1 / k);
      }
    }
    return nan;
  }

  /// Inverse of Ψ(s): e^−Ψ, e^−Ψ/V, and (a/b) sinh(asinh(b/a) − Ψ) for hooke.
  [[nodiscard]] Real stretch_at_psi(Real target) const override {
    switch (model_) {
      case Model::rigid: return std::exp(-target);
      case Model::rigid_fluid: return target >= 0 ? std::exp(-target) : std::numeric_limits<Real>::quiet_NaN();
      case Model::hooke: {
        const Real a = std::sqrt(1 - b_ * b_);
        const Real s = a / b_ * std::sinh(std::asinh(b_ / a) - target);
        return s > 0 ? s : std::numeric_limits<Real>::quiet_NaN();
      }
      case Model::constant_sound_speed: return std::exp(-target / b_);
    }
    return std::numeric_limits<Real>::quiet_NaN();
  }

 private:
  /// hooke's R(s) = sqrt(b² + (1 − b²)/s²)
  [[nodiscard]] Real r(Real s) const { return std::sqrt(b_ * b_ + (1 - b_ * b_) / (s * s)); }

  Model model_;
  Real rho_;
  Real b_;  ///< V
};

template <class Real = double>
ClosedFormLaw<Real> rigid(Real rest_density = 1) {
  return ClosedFormLaw<Real>(Model::rigid, rest_density);
}
template <class Real = double>
ClosedFormLaw<Real> rigid_fluid(Real rest_density = 1) {
  return ClosedFormLaw<Real>(Model::rigid_fluid, rest_density);
}
template <class Real = double>
ClosedFormLaw<Real> hooke(Real rest_density, Real wave_speed) {
  return ClosedFormLaw<Real>(Model::hooke, rest_density, wave_speed);
}
template <class Real = double>
ClosedFormLaw<Real> constant_sound_speed(Real rest_density, Real sound_speed) {
  return ClosedFormLaw<Real>(Model::constant_sound_speed, rest_density, sound_speed);
}

/// A registered material seen only through p, e, c_s and Ψ (and where it is admissible and
/// parts); its inverses are bisections here, not the material's own.
class MaterialLaw final : public Law<double> {
 public:
  explicit MaterialLaw(const Material& material) : m_(material) {}
  [[nodiscard]] std::string name() const override { return std::string(m_.model()); }
  [[nodiscard]] double rest_density() const override { return m_.rest_density(); }
  [[nodiscard]] double pressure(double s) const override { return m_.pressure(Stretch::from_value(s)); }
  [[nodiscard]] double energy_density(double s) const override { return m_.energy_density(Stretch::from_value(s)); }
  [[nodiscard]] double sound_speed(double s) const override { return m_.sound_speed(Stretch::from_value(s)); }
  [[nodiscard]] double psi(double s) const override { return m_.riemann_psi(Stretch::from_value(s)); }
  [[nodiscard]] double log_s_min() const override { return m_.admissible().log_min; }
  [[nodiscard]] double log_s_max() const override { return m_.admissible().log_max; }
  [[nodiscard]] double cavitation_pressure() const override { return m_.cavitation_pressure(); }

 private:
  const Material& m_;
};

}  // namespace rigidity::exact
