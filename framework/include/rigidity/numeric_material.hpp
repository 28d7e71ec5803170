#pragma once
/// Materials given only by their law, everything else derived numerically with GSL:
///
///   PressureLawMaterial    the user gives p(s):  W = ρ00 − ∫_1^s p dσ (adaptive Gauss–Kronrod,
///                          in ln s), W'' = −dp/ds (GSL central differences in ln s)
///   StrainEnergyMaterial   the user gives W(s):  p = −W' (GSL central differences in ln s),
///                          W'' from fourth-order second differences of W in ln s
///
/// and for both e = W/s, c_s² = s W''/(e + p), Ψ = ∫_{ln s}^0 c_s d(ln σ) (adaptive Gauss–Kronrod),
/// and the inverses by Brent's method on a bracket grown from s = 1.
///
/// A numeric material lives on a finite window of stretches [s_min, s_max] around s = 1, which
/// it reports as its admissible range. The limits are the values at the window ends, and the
/// inverses reach them: max_pressure = p(s_min), max_tension = p(s_max), psi_max = Ψ(s_min),
/// psi_min = Ψ(s_max). The difference formulas evaluate the law up to 2% beyond the window.
///
/// Accuracy for smooth laws (tests/core/numeric_material_test.cpp states the tolerances):
///   PressureLawMaterial   W and e ~1e-15 relative, W'' ~2e-10, c_s ~1e-10, Ψ ~2e-11;
///   StrainEnergyMaterial  p ~3e-11 of e, W'' and c_s ~1e-10 near s = 1, degrading as W turns
///                         linear in s (~4e-7 at s = 100 for the rigid law), Ψ ~2e-9.
/// Inherent limits: the law takes s as a double, so it resolves strains only down to ~1e-16
/// (s − 1 rounds; a closed-form material given ln s does better); and e + p is found from
/// W and p, so it keeps only the relative precision ε e/(e + p): in far tension, where
/// e + p ≪ e (the rigid law at s ≫ 1), c_s degrades and the window must stop short of it.
/// A sound speed above c by less than its own error estimate is reported as c.
///
/// Functions returning a double throw NumericalError if GSL fails to meet its tolerance; the
/// *_estimate functions and the inverses report that as a Status and never return a guess.
/// Nothing is cached: each W of a PressureLawMaterial is a quadrature, each Ψ a quadrature of
/// those, each inverse a root find over those.

#include <optional>

#include "rigidity/material.hpp"
#include "rigidity/status.hpp"
#include "rigidity/stretch.hpp"

namespace rigidity {

/// A value computed numerically and the estimate of its absolute error.
struct Estimate {
  double value = 0.0;
  double error = 0.0;
};

/// The numeric machinery shared by PressureLawMaterial and StrainEnergyMaterial.
class NumericMaterial : public Material {
 public:
  /// The window used when a material does not choose one: s ∈ [1e-6, 1e6].
  [[nodiscard]] static StretchRange default_window();

  // ---- the Material interface, derived numerically -----------------------------
  [[nodiscard]] double strain_energy(Stretch s) const final;
  [[nodiscard]] double energy_density(Stretch s) const final;
  [[nodiscard]] double sound_speed(Stretch s) const final;
  [[nodiscard]] double stiffness(Stretch s) const final;
  [[nodiscard]] double riemann_psi(Stretch s) const final;
  [[nodiscard]] Solved<Stretch> stretch_at_pressure(double p) const final;
  [[nodiscard]] Solved<Stretch> stretch_at_psi(double psi) const final;
  /// The window, ends included.
  [[nodiscard]] StretchRange admissible() const final { return window_; }
  /// p(s_min)
  [[nodiscard]] double max_pressure() const final;
  /// p(s_max)
  [[nodiscard]] double max_tension() const final;
  /// Ψ(s_min)
  [[nodiscard]] double psi_max() const final;
  /// Ψ(s_max)
  [[nodiscard]] double psi_min() const final;

  // ---- the same with error estimates, failures as a Status --------------------------
  [[nodiscard]] virtual Solved<Estimate> strain_energy_estimate(Stretch s) const = 0;
  [[nodiscard]] virtual Solved<Estimate> pressure_estimate(Stretch s) const = 0;
  [[nodiscard]] virtual Solved<Estimate> stiffness_estimate(Stretch s) const = 0;
  /// e + p = (W + s p)/s.
  [[nodiscard]] Solved<Estimate> enthalpy_estimate(Stretch s) const;
  /// c_s = sqrt(s W''/(e + p)); 0 where that is not positive (not hyperbolic).
  [[nodiscard]] Solved<Estimate> sound_speed_estimate(Stretch s) const;
  /// Ψ = ∫_{ln s}^0 c_s dτ by adaptive Gauss–Kronrod quadrature.
  [[nodiscard]] Solved<Estimate> riemann_psi_estimate(Stretch s) const;

 protected:
  /// \param window finite, containing s = 1. \param sound_speed_accuracy the relative
  /// accuracy of c_s this material reaches: the target of the Ψ quadrature.
  /// \throws std::invalid_argument for a window that is infinite or misses s = 1.
  NumericMaterial(double rest_density, StretchRange window, double sound_speed_accuracy);

 private:
  /// For a decreasing quantity with these values at the window ends: out_of_range beyond them
  /// (by more than their error), the end itself at or just beyond one, nullopt strictly inside.
  [[nodiscard]] std::optional<Solved<Stretch>> outside_or_at_window_end(double target, const Estimate& highest,
                                                                        const Estimate& lowest) const;

  StretchRange window_;
  double sound_speed_accuracy_;
};

/// A material given by its pressure law p(s); override pressure_law (and model(), plus the
/// registry pattern of registry.hpp).
class PressureLawMaterial : public NumericMaterial {
 public:
  /// p(s) from the law, exact.
  [[nodiscard]] double pressure(Stretch s) const final { return pressure_law(s.value()); }
  /// W = ρ00 − ∫_0^{ln s} p(e^τ) e^τ dτ.
  [[nodiscard]] Solved<Estimate> strain_energy_estimate(Stretch s) const final;
  /// p itself, error 0.
  [[nodiscard]] Solved<Estimate> pressure_estimate(Stretch s) const final;
  /// W'' = −(dp/d ln s)/s.
  [[nodiscard]] Solved<Estimate> stiffness_estimate(Stretch s) const final;

 protected:
  explicit PressureLawMaterial(double rest_density, StretchRange window = default_window());
  /// p(s), compression positive, p(1) = 0. \pre s in the window (or up to 2% beyond)
  [[nodiscard]] virtual double pressure_law(double s) const = 0;
};

/// A material given by its strain energy W(s) (rest energy included, W(1) = ρ00); override
/// strain_energy_law (and model(), plus the registry pattern of registry.hpp).
class StrainEnergyMaterial : public NumericMaterial {
 public:
  /// p = −W'. \throws NumericalError if the derivative fails
  [[nodiscard]] double pressure(Stretch s) const final;
  /// W from the law, exact.
  [[nodiscard]] Solved<Estimate> strain_energy_estimate(Stretch s) const final;
  /// p = −(dW/d ln s)/s.
  [[nodiscard]] Solved<Estimate> pressure_estimate(Stretch s) const final;
  /// W'' = (d²W/dτ² − dW/dτ)/s², τ = ln s, by second differences of W.
  [[nodiscard]] Solved<Estimate> stiffness_estimate(Stretch s) const final;

 protected:
  explicit StrainEnergyMaterial(double rest_density, StretchRange window = default_window());
  /// W(s) = e(s) s. \pre s in the window (or up to 2% beyond)
  [[nodiscard]] virtual double strain_energy_law(double s) const = 0;
};

}  // namespace rigidity
