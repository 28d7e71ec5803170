#pragma once
/// Materials given only by their law, everything else derived numerically:
///
///   PressureLawMaterial    the user gives p(s):  W = ρ00 − ∫_1^s p dσ,  W'' = −dp/ds
///   StrainEnergyMaterial   the user gives W(s):  p = −W',  W''
///
/// and for both e = W/s, c_s² = s W''/(e + p), Ψ = ∫_{ln s}^0 c_s d(ln σ) and the inverses.
///
/// A numeric material lives on a finite window of stretches [s_min, s_max] around s = 1, which
/// it reports as its admissible range. The limits are the values at the window ends, and the
/// inverses reach them: max_pressure = p(s_min), max_tension = p(s_max), psi_max = Ψ(s_min),
/// psi_min = Ψ(s_max).
///
/// Tables. The first call of a function of the Material interface builds, once per material,
/// Chebyshev tables (chebyshev.hpp) over the window in τ = ln s: of the law (W(τ), or s p(s),
/// whose antiderivative is ρ00 − W), its derivatives, c_s and Ψ, and of τ(Ψ). Panels are split
/// until the law's coefficients fall to 1e-14 of its scale, and end at s = 1 and at the points
/// law_breaks() names (a table's rows). Building takes some hundreds of evaluations of the law
/// and no quadrature: 0.04 ms for s in [0.5, 2], 0.8 ms for the default window. From then on
/// W, e, W'', c_s and Ψ are one or two Clenshaw sums each (40 to 80 ns), and the inverses a
/// bracket from the panel ends then Newton's method, safeguarded, to a few ulps of ln s
/// (s(Ψ) from the guess of the τ(Ψ) table, ~0.2 µs; s(p) from the secant, ~0.45 µs). p of a
/// PressureLawMaterial is the law itself, and stretch_at_pressure inverts the law; p of a
/// StrainEnergyMaterial is the table's. Building is thread-safe (std::call_once), and happens
/// only if something evaluates the material. If the law gives no number somewhere in its
/// window, no tables are built and every function falls back to the direct computation below,
/// as it does outside the window.
///
/// Accuracy of the tables for smooth laws (measured on the laws of
/// tests/core/numeric_material_test.cpp, whose tolerances are those of the direct computation):
///   PressureLawMaterial   W and e ~1e-15 relative, W'' ~1e-11, c_s ~5e-13, Ψ ~1e-11;
///   StrainEnergyMaterial  p ~4e-13 of e, W'' and c_s ~1e-10 near s = 1, degrading as W turns
///                         linear in s (~5e-8 at s = 100), Ψ ~1e-10.
/// Inherent limits: the law takes s as a double, so it resolves strains only down to ~1e-16
/// (s − 1 rounds; a closed-form material given ln s does better, and so does a law that
/// overrides pressure_law_at_log); and e + p is found from W and p, so it keeps only the relative
/// precision ε e/(e + p): in far tension, where e + p ≪ e (the rigid law at s ≫ 1), c_s degrades
/// and the window must stop short of it. A sound speed above c by less than the material's
/// accuracy is reported as c.
///
/// Direct computation (the *_estimate functions, and the fallback), with GSL: W of a
/// PressureLawMaterial by adaptive Gauss–Kronrod quadrature in ln s, W'' by central differences;
/// p of a StrainEnergyMaterial by central differences, W'' by fourth-order second differences;
/// each Ψ a quadrature of those (33 µs), each inverse Brent's method over those (Ψ's: 6 ms). Its
/// accuracy: PressureLawMaterial W ~1e-15, W'' ~2e-10, c_s ~1e-10, Ψ ~2e-11; StrainEnergyMaterial
/// p ~3e-11 of e, W'' ~1e-10 near s = 1 and ~4e-7 at s = 100, Ψ ~2e-9. The difference formulas
/// evaluate the law up to 2% beyond the window. Functions returning a double throw
/// NumericalError if GSL fails to meet its tolerance; the *_estimate functions and the inverses
/// report that as a Status and never return a guess.

#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/status.hpp"
#include "rigidity/stretch.hpp"

namespace rigidity {

/// A value computed numerically and the estimate of its absolute error.
struct Estimate {
  double value = 0.0;
  double error = 0.0;
};

namespace detail {
struct NumericTables;
}

/// The numeric machinery shared by PressureLawMaterial and StrainEnergyMaterial.
class NumericMaterial : public Material {
 public:
  ~NumericMaterial() override;

  /// The window used when a material does not choose one: s ∈ [1e-6, 1e6].
  [[nodiscard]] static StretchRange default_window();

  // ---- the Material interface, derived numerically -----------------------------
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

  /// ln s of the points inside the window where the law is not smooth (a table's rows): the
  /// tables end panels there, and finite differences should not straddle them. Ascending.
  [[nodiscard]] virtual std::vector<double> law_breaks() const { return {}; }

 protected:
  /// \param window finite, containing s = 1. \param sound_speed_accuracy the relative
  /// accuracy of c_s this material reaches: the target of the Ψ quadrature.
  /// \throws std::invalid_argument for a window that is infinite or misses s = 1.
  NumericMaterial(double rest_density, StretchRange window, double sound_speed_accuracy);

 protected:
  /// The tables if ln s is inside the window and they could be built, else nullptr.
  [[nodiscard]] const detail::NumericTables* tables_at(Stretch s) const;

 private:
  /// For a decreasing quantity with these values at the window ends: out_of_range beyond them
  /// (by more than their error), the end itself at or just beyond one, nullopt strictly inside.
  [[nodiscard]] std::optional<Solved<Stretch>> outside_or_at_window_end(double target, const Estimate& highest,
                                                                        const Estimate& lowest) const;
  /// Builds the tables from the law (PressureLawMaterial and StrainEnergyMaterial each know
  /// how); nullptr if the law gives no number somewhere in the window.
  [[nodiscard]] virtual std::unique_ptr<detail::NumericTables> build_tables() const = 0;

  StretchRange window_;
  double sound_speed_accuracy_;
  mutable std::once_flag tables_built_;
  mutable std::unique_ptr<detail::NumericTables> tables_;
};

/// A material given by its pressure law p(s); override pressure_law (and model(), plus the
/// registry pattern of registry.hpp).
class PressureLawMaterial : public NumericMaterial {
 public:
  /// p(s) from the law, exact.
  [[nodiscard]] double pressure(Stretch s) const final { return pressure_law_at_log(s.log()); }
  /// W = ρ00 − ∫_1^s p dσ (from the tables, else by quadrature).
  [[nodiscard]] double strain_energy(Stretch s) const final;
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
  /// p as a function of ln s: pressure_law(e^{ln s}), unless a law given in ln s (a table)
  /// overrides it, and so keeps its full precision at strains below 1e-16.
  [[nodiscard]] virtual double pressure_law_at_log(double log_s) const { return pressure_law(std::exp(log_s)); }

 private:
  /// W = ρ00 − ∫ s p d(ln s) from a table of s p(s) in ln s; W'' from its derivative.
  [[nodiscard]] std::unique_ptr<detail::NumericTables> build_tables() const final;
};

/// A material given by its strain energy W(s) (rest energy included, W(1) = ρ00); override
/// strain_energy_law (and model(), plus the registry pattern of registry.hpp).
class StrainEnergyMaterial : public NumericMaterial {
 public:
  /// W from the law, exact. \throws NumericalError if the law gives no number
  [[nodiscard]] double strain_energy(Stretch s) const final;
  /// p = −W' (from the tables, else by GSL central differences). \throws NumericalError if that fails
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

 private:
  /// A table of W in ln s; p and W'' from its derivatives.
  [[nodiscard]] std::unique_ptr<detail::NumericTables> build_tables() const final;
};

}  // namespace rigidity
