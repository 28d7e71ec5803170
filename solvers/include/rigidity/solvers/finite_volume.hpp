#pragma once
/// The finite-volume baseline (`solver.method: finite_volume`): the scheme a
/// physicist would write first, to measure the exact front tracking against.
///
/// Lagrangian (label) coordinates X, conservative Godunov-type update of the
/// conserved variables per unit label (docs/physics.md)
///
///     U = (s/γ, (e+p) s γ v),      F(U) = (−v, p),      ∂t U + ∂X F = 0,
///
///     U_i^{n+1} = U_i^n − Δt/ΔX_i (F_{i+1/2} − F_{i−1/2}).
///
/// - `solver.order: 1`: piecewise-constant states (Godunov 1959).
///   `solver.order: 2`: MUSCL–Hancock (van Leer 1979; Toro §14.4) on the Riemann
///   invariants J± = φ ± Ψ(s), the exact characteristic variables of the system:
///   MC-limited slopes, and the half-step predictor ∂t J± + λ± ∂X J± = 0 (docs/physics.md).
/// - `solver.flux: exact`: Godunov's flux from the exact Riemann problem,
///   F = (−v*, p*) (solve_riemann). `solver.flux: hll`: HLL (Harten, Lax & van Leer
///   1983) with the Lagrangian wave-speed estimates
///   S− = min(λ−(U_L), λ−(U_R)) < 0 < S+ = max(λ+(U_L), λ+(U_R)).
///   Walls, pistons, free ends and contacts between bodies always take the exact
///   boundary or push-only Riemann problem, whatever the flux.
/// - `solver.cells` cells per body, shared among its segments in proportion to
///   their natural length, at least one each; a cell never straddles a segment.
/// - Δt = cfl · min_i ΔX_i / max(|λ−_i|, |λ+_i|) (Lagrangian characteristic speeds,
///   recomputed every step); steps are clipped to land exactly on sample times,
///   piston changes, gap closures and t_end.
/// - Gaps between bodies, and between bodies and walls, are tracked: each body end
///   moves with its face velocity; a gap that closes starts a push-only contact
///   ("contact" event); a contact whose Riemann problem parts opens a gap
///   ("separation" event, reported once the gap exceeds round-off, dated at the
///   step that parted it).
/// - A material that cavitates (`rigid_fluid`) is never put in tension: faces part
///   at the cavitation pressure, and a cell whose conserved state has no admissible
///   stretch below the parting stretch is clamped there (p = cavitation pressure,
///   momentum kept; U itself is never altered): it holds void. A void fraction above
///   1e-9 is reported as a "cavitation" event with a warning; the body is reported
///   whole, not as pieces.
/// - Outputs as the characteristics solver fills them; samples take the value of
///   the cell that holds X; lab x sums (s/γ) ΔX from the body's left end. fronts.csv
///   stays empty. energy_dissipated is the energy the scheme removed,
///   E_initial + wall_work − E_final: physical shock dissipation and numerical
///   dissipation together (the scheme cannot tell them apart). stats.interactions
///   counts face fluxes (Riemann problems, exact or HLL): faces × steps.
///
/// Limits: the admissible set of U is not convex (for `rigid`, |U₁| U₀ < ρ00), so
/// cell averages of states close to c can leave it; the run then stops with a
/// NumericalError naming the cell and time (the paper's impact runs up to v ≈ 0.985).
/// The recovery of (φ, s) from U loses about γ² ε of relative precision.

#include <Eigen/Core>
#include <limits>

#include "rigidity/material.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/status.hpp"

namespace rigidity {

/// Samples and events go to `recorder` as they are produced; an interrupt stops the
/// run cleanly at the time reached (status `interrupted`). The scheme has no budget:
/// its cost, cells × steps, is known before it starts.
/// \throws InadmissibleError when the scene has no classical solution,
///         NumericalError when the scheme leaves the admissible states.
[[nodiscard]] RunResult solve_finite_volume(const Scene& scene, RunRecorder& recorder);
/// The same, keeping every output in RunResult's vectors (a MemoryRecorder).
[[nodiscard]] RunResult solve_finite_volume(const Scene& scene);

namespace finite_volume {

/// U = (s/γ, (e+p) s γ v): labels and momentum per unit label (docs/physics.md).
using Conserved = Eigen::Vector2d;
/// F = (−v, p): fluxes of labels and momentum through a face, per unit time.
using Flux = Eigen::Vector2d;

/// U of a state.
[[nodiscard]] Conserved conserved(const Material& material, const State& state);
/// F of a state.
[[nodiscard]] Flux flux(const Material& material, const State& state);

/// A state recovered from U.
struct Recovered {
  State state;
  Status status = Status::ok;
  /// The material cannot take U without tension beyond its cavitation pressure:
  /// the state is clamped at the parting stretch (momentum kept), and the rest of
  /// the label density s/γ is void.
  bool cavitated = false;
  /// For the next recovery of the same cell, whose U a step has moved by δU: the
  /// sensitivity of φ to U at this state, δφ = dφ/dU₁ δU₁ + dφ/d ln L δL/L (NaN where
  /// unknown), and (e+p) s there.
  Conserved u{std::numeric_limits<double>::quiet_NaN(), 0.0};
  double dphi_dmomentum = std::numeric_limits<double>::quiet_NaN();
  double dphi_dloglabels = 0.0;
  double enthalpy_per_label = std::numeric_limits<double>::quiet_NaN();
  [[nodiscard]] bool ok() const { return status == Status::ok; }
};

/// The state (φ, s) with conserved variables U. With L = s/γ fixed, s = L cosh φ and
/// the momentum G(φ) = (e+p)(s) s sinh φ is odd and strictly increasing in φ:
///     dG/dφ = (e+p) s (1 + (1 − c_s²) sinh² φ)/cosh φ > 0,
/// so U determines the state uniquely; G(φ) = U₁ is solved by Newton's method
/// safeguarded by bisection, started from `rapidity_guess`.
/// \post ok(), or cavitated (for a material with a cavitation pressure), or a
///       failed status: out_of_range if no admissible state has these U
///       (never a guess).
[[nodiscard]] Recovered recover_state(const Material& material, const Conserved& u, double rapidity_guess = 0.0);

/// What the recovery needs of a material besides its laws: the stretches a state may
/// take (the admissible range, cut at the parting stretch of a material that cavitates).
/// The same for every cell of a material: a scheme computes it once per segment of a body.
struct RecoveryBounds {
  double log_min = -std::numeric_limits<double>::infinity();
  double log_cap = std::numeric_limits<double>::infinity();
  bool parts = false;  ///< the material cavitates at log_cap
};
[[nodiscard]] RecoveryBounds recovery_bounds(const Material& material);

/// recover_state with the material's bounds computed beforehand.
[[nodiscard]] Recovered recover_state(const Material& material, const RecoveryBounds& bounds, const Conserved& u,
                                      double rapidity_guess);

/// recover_state started from the state a cell had before a step moved its U from
/// `previous.u` to `u`: Newton from the first-order prediction φ + δφ (its error is
/// second order in δU), one evaluation of the material fewer than from φ itself.
[[nodiscard]] Recovered recover_state(const Material& material, const RecoveryBounds& bounds, const Conserved& u,
                                      const Recovered& previous);

/// What goes through a face. The momentum flux p is common; the label flux is −v
/// with v the velocity of the face seen from each side, which differ only where the
/// face has parted (a free end on each side of an opening gap).
struct FaceFlux {
  double velocity_left = 0.0;   ///< velocity of the face as the cell on its left sees it
  double velocity_right = 0.0;  ///< ... as the cell on its right sees it
  double pressure = 0.0;        ///< p at the face
  bool parted = false;          ///< the Riemann problem parted the face
};

/// The Lagrangian characteristic speeds dX/dt of C− and C+ in a state, from one
/// sound speed and one exponential (as characteristic_speeds, both families at once).
struct LagrangianSpeeds {
  double minus = 0.0, plus = 0.0;
};
[[nodiscard]] LagrangianSpeeds lagrangian_speeds(const Material& material, const State& state);

/// HLL flux between two states (either material), Lagrangian wave speeds from
/// characteristic_speed on both sides.
[[nodiscard]] FaceFlux hll_flux(const Material& left_material, const State& left, const Material& right_material,
                                const State& right);

/// The monotonized-central limiter (van Leer 1977): minmod(2a, 2b, (a + b)/2).
[[nodiscard]] double mc_limited_slope(double left_slope, double right_slope);

}  // namespace finite_volume
}  // namespace rigidity
