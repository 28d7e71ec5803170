#pragma once
/// Exact Riemann problems of relativistic elasticity in Lagrangian form (docs/physics.md).
///
/// A state is (rapidity φ, stretch s). Two states meeting at a point resolve into a
/// left-moving wave (C− family) into the left state, a right-moving wave (C+) into
/// the right state, and between them a star region of common pressure p* and
/// rapidity φ* (two star stretches if the materials differ). Along a wave curve:
///
///   rarefaction (p* < p_side), and every wave of a linearly degenerate material:
///       the Riemann invariant of the other family is constant,
///       J+ = φ + Ψ(s) across a C− wave,  J− = φ − Ψ(s) across a C+ wave;
///   shock (p* > p_side, genuinely nonlinear material only): the jump conditions
///       of the label and momentum laws in the lab frame,
///           m [s/γ] = −[v],   m [(e+p) s γ v] = [p],
///       m the Lagrangian shock speed dX/dt; energy is not conserved across it
///       (the loss is the shock's dissipation), so these conditions, like the
///       dissipation, refer to the lab frame of the scene.
///
/// Contacts that cannot pull (a push-only contact, a fluid that cavitates) are
/// treated with a minimum pressure: if the sides would need less than that to stay
/// together, they part, and each side relaxes through its own wave to that pressure.

#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

#include "rigidity/hyperbolic.hpp"
#include "rigidity/material.hpp"
#include "rigidity/status.hpp"
#include "rigidity/units.hpp"

namespace rigidity {

/// A uniform state of a bar: rapidity φ = artanh v and stretch s.
struct State {
  double rapidity = 0.0;
  Stretch stretch;
};

/// Which side of the meeting point a state lies on; the left state is crossed by a
/// C− (left-moving) wave, the right state by a C+ (right-moving) wave.
enum class Side { left, right };

/// The star state reached from `state` (on `side`) through one wave of the family
/// facing the meeting point, at star pressure p.
struct WaveCurvePoint {
  double rapidity = 0.0;
  Stretch stretch;
  Status status = Status::ok;
  [[nodiscard]] bool ok() const { return status == Status::ok; }
};

/// The wave curve through a state: the states one wave can connect it to.
class WaveCurve {
 public:
  WaveCurve(const Material& material, const State& state, Side side);
  /// The star state at pressure p. out_of_range beyond the material's limits; another failed
  /// status (never a guessed state) if the material's inverse or the shock jump conditions fail.
  [[nodiscard]] WaveCurvePoint at_pressure(double p) const;
  [[nodiscard]] double pressure() const { return pressure_; }
  [[nodiscard]] const Material& material() const { return *material_; }
  [[nodiscard]] const State& state() const { return state_; }
  [[nodiscard]] Side side() const { return side_; }
  /// The Riemann invariant carried across this wave: J+ (left side) or J− (right side).
  [[nodiscard]] double invariant() const { return invariant_; }

 private:
  const Material* material_;
  State state_;
  Side side_;
  double pressure_;
  double psi_;
  double invariant_;
};

/// The solution at the meeting point.
///
/// A failed status is never a number: out_of_range means the problem has no classical solution
/// for a physical reason (a side would leave its material's admissible range: crushed, or in a
/// bonded pull stretched beyond it), with `material`, `impact_rapidity` and `limit_psi` (and
/// `demanded_psi` where known) filled in; any other status is a numerical failure, with
/// `failure` naming the computation that failed (and `material` the material it concerned).
struct RiemannSolution {
  Status status = Status::ok;    ///< out_of_range: no classical solution (a side leaves its material's range)
  bool parted = false;           ///< the sides separate (pressure would fall below the minimum)
  double pressure = 0.0;         ///< p* (the minimum pressure if parted)
  State left, right;             ///< star states next to the left and the right state
  double demanded_psi = 0.0;     ///< with out_of_range: the Ψ the limiting side would need (NaN if not known)
  double limit_psi = 0.0;        ///< with out_of_range: that material's Ψ_max (Ψ_min if in_tension)
  double impact_rapidity = 0.0;  ///< with out_of_range: rapidity of the left state relative to the right (or the wall)
  const Material* material = nullptr;  ///< if failed: the material whose range is left, or that failed
  bool in_tension = false;             ///< with out_of_range: the range is left in tension (pulled apart), not crushed
  std::string_view failure;            ///< with a numerical failure: the computation that failed (static text)
};

/// Two states meeting. min_pressure: -inf for a bonded interface; 0 for a push-only
/// contact; a fluid's cavitation pressure.
[[nodiscard]] RiemannSolution solve_riemann(const Material& left_material, const State& left,
                                            const Material& right_material, const State& right, double min_pressure);

/// A state against a wall or piston moving at rapidity `wall_rapidity`; `side` is the
/// side the material is on (Side::left: the wall is on its right).
[[nodiscard]] RiemannSolution solve_wall(const Material& material, const State& state, Side side, double wall_rapidity,
                                         double min_pressure);

/// A state at a free end (p = 0, or the material's cavitation pressure if higher).
[[nodiscard]] RiemannSolution solve_free_end(const Material& material, const State& state, Side side);

/// A state at an end held at pressure `pressure` (a traction: > 0 pushes on the material, < 0
/// pulls); an end pulled harder than the material's cavitation pressure holds that pressure
/// (the material carries no more tension). Never parted.
[[nodiscard]] RiemannSolution solve_traction_end(const Material& material, const State& state, Side side,
                                                 double pressure);

/// Speeds of a front or characteristic.
struct FrontSpeeds {
  double lagrangian = 0.0;  ///< dX/dt
  double lab = 0.0;         ///< dx/dt
};

/// Both speeds of the characteristic of family `family` (+1 or -1) in a state:
/// dX/dt = ± c_s / (s γ (1 ± v c_s)),  dx/dt = (v ± c_s)/(1 ± v c_s).
[[nodiscard]] FrontSpeeds characteristic_speeds(const Material& material, const State& state, int family);
/// The same with the sound speed c_s of the state's stretch given (a caller that has it),
/// and with the stretch s itself given.
[[nodiscard]] FrontSpeeds characteristic_speeds(double sound_speed, const State& state, int family);
[[nodiscard]] FrontSpeeds characteristic_speeds(double sound_speed, double rapidity, double stretch, int family);
/// The characteristic speeds of both families in a state, [0] C− and [1] C+, each equal to
/// characteristic_speeds(material, state, ±1), from the exponentials they share.
void characteristic_speeds_both(const Material& material, const State& state, FrontSpeeds (&speeds)[2]);
/// True if the wave of family `family` from `outer` to the star stretch is a shock (Lax:
/// the characteristics run into it), false if it is a rarefaction fan or a jump of a
/// linearly degenerate material. Decided on the rarefaction curve: a fan must spread,
/// its characteristic speed growing from the left of the fan to its right. For the usual
/// convexity this makes compressions shocks; for a material whose Lagrangian wave speed
/// grows under tension it makes expansions shocks and compressions fans.
[[nodiscard]] bool wave_is_shock(const Material& material, const State& outer, Stretch star, int family);

/// The rapidity of the state at stretch `star` that a shock of family `family` connects to
/// `outer`. The jump conditions hold in the lab frame (docs/physics.md: m [τ] = −[v], m [M] = [p]);
/// since a shock of an elastic material dissipates energy, the momentum condition alone is
/// not Lorentz covariant, and the outer state's rest frame gives a slightly different curve
/// unless the outer state is at rest in the lab (third order in the strength). So: first the
/// rest-frame closed form, where the conditions with u = γv of the star give
/// Δp s0 γ = s (Δp + w u²) (w = e + p at the star), a quadratic in Y = u²/Δp,
/// s²w² Y² + (2 s² w − Δp s0²) Y + (s² − s0²) = 0, whose root of the sign of Δp is taken in
/// its stable form (rapidities add along the line); then Newton steps on the lab-frame
/// condition [p][τ] + [v][M] = 0, with [τ] and [v] free of cancellation, to round-off
/// (not_converged if Newton does not settle there: the caller then brackets the root).
Solved<double> hugoniot_rapidity(const Material& m, const State& outer, Stretch star, int family);

/// The state inside a centred rarefaction fan of family `family` where its characteristics
/// run at label speed `speed` (dX/dt = (X − X0)/(t − t0) from its centre): the other family's
/// invariant `j_other` is the same across the fan (J− = φ − Ψ for a C+ fan, J+ = φ + Ψ for a
/// C− one), and Ψ is where, between psi_a and psi_b (its two edges), the family's speed is
/// `speed` (Brent's method, to round-off). `speed` must lie between the edges' speeds.
[[nodiscard]] Solved<State> centred_fan_state(const Material& m, int family, double j_other, double psi_a, double psi_b,
                                              double speed);

/// The rapidity of the state at stretch `star` that a shock of family `family` connects to
/// `outer`, on the Hugoniot locus of the lab-frame jump conditions (hugoniot_rapidity's
/// closed form and Newton steps, bracketed where they do not settle), to round-off.
Solved<double> shock_rapidity(const Material& m, const State& outer, Stretch star, int family);

/// True if the material's genuine nonlinearity changes sign strictly between stretches a and b
/// (Material::inflection_logs): a wave between them may then be composite.
[[nodiscard]] bool crosses_inflection(const Material& m, Stretch a, Stretch b);

/// One piece of a wave: a shock or a centred fan from the state before it (the wave's outer
/// state, or the end of the piece before) to `end`.
struct WavePiece {
  bool shock = false;
  State end;
};

/// The wave of family `family` from `outer` (the state it runs into) to the star stretch, as
/// Liu's entropy condition builds it for a law whose genuine nonlinearity changes sign: pieces
/// from the outer state inwards, each shock or fan, whose speeds never increase inwards; a shock
/// attached to a fan runs at the fan edge's characteristic speed (it is sonic there). Built as a
/// march from the outer state: where some chord from the current state along its Hugoniot locus
/// is faster than its characteristic, a shock to the farthest fastest chord (sonic at its end
/// where that is inside the wave, by Lax's lemma: the chord speed is stationary along the locus
/// exactly where it equals the far state's characteristic speed); otherwise a fan along the
/// integral curve up to the first state from which a chord catches up with the fan's own speed
/// (at the latest the next inflection), with the shock attached there. Chords are sampled at
/// 48 stretches per piece and each sonic point found by Brent's method to round-off: a feature
/// of the law narrower than ~1/48 of a piece's range in ln s can be missed. For a convex law,
/// or a wave between two inflections, one piece (wave_is_shock decides which).
struct CompositeWave {
  std::vector<WavePiece> pieces;
};
[[nodiscard]] Solved<CompositeWave> composite_wave(const Material& m, const State& outer, Stretch star, int family);

/// What the jump conditions ask of a stretch: s, p and e + p (NaN until evaluated).
struct JumpLaws {
  double stretch = std::numeric_limits<double>::quiet_NaN();
  double pressure = 0.0;
  double enthalpy = 0.0;
  /// Evaluates them once.
  const JumpLaws& at(const Material& m, Stretch s) {
    if (std::isnan(stretch)) {
      const LawValues laws = m.laws_at(s);
      stretch = s.value();
      pressure = laws.pressure;
      enthalpy = laws.enthalpy;
    }
    return *this;
  }
};

/// hugoniot_rapidity with s, p and e + p of both stretches given.
Solved<double> hugoniot_rapidity(const State& outer, const JumpLaws& at_outer, Stretch star, const JumpLaws& at_star,
                                 int family);

/// Lagrangian speed dX/dt of a characteristic of family `family` (+1 or -1) in a state.
[[nodiscard]] double characteristic_speed(const Material& material, const State& state, int family);
/// Lab-frame speed dx/dt of that characteristic.
[[nodiscard]] double characteristic_lab_speed(const Material& material, const State& state, int family);

/// Conserved densities per unit label (docs/physics.md): labels s/γ (the lab length of a unit
/// of label), momentum (e+p) s γ v, energy ((e+p)γ² − p) s/γ, rest energy included.
[[nodiscard]] double label_density(const State& state);
[[nodiscard]] double momentum_density(const Material& material, const State& state);
[[nodiscard]] double energy_density(const Material& material, const State& state);
/// The same densities from what a caller has at hand: the stretch s, sinh φ or cosh φ of the
/// rapidity, the pressure p and e + p. Momentum (e+p) s γ v = (e+p) s sinh φ; energy
/// ((e+p)γ² − p) s/γ = (e+p) s cosh φ − p s / cosh φ.
[[nodiscard]] inline double momentum_density(double s, double sinh_phi, double enthalpy) {
  return enthalpy * s * sinh_phi;
}
[[nodiscard]] inline double energy_density(double s, double cosh_phi, double p, double enthalpy) {
  return enthalpy * s * cosh_phi - p * s / cosh_phi;
}
/// energy_density split into its parts per unit label, each on its own scale: kinetic
/// s [e (cosh φ − 1) + p sinh φ tanh φ] (with cosh φ − 1 = 2 sinh²(φ/2)), internal
/// W(s) − ρ00 and rest ρ00; they add up to energy_density.
struct EnergyParts {
  double kinetic = 0.0, internal = 0.0, rest = 0.0;
};
[[nodiscard]] EnergyParts energy_parts(const Material& material, const State& state);

/// Does nothing for a solved problem; otherwise throws InadmissibleError for out_of_range (no
/// classical solution: the message names the impact speed, the material (solution.material, else
/// `material`) and its limit, tanh Ψ_max, the largest impact speed an unstrained bar of it takes
/// against a wall) or NumericalError for any other status (naming the computation that failed),
/// naming the place (t, x) of the interaction. Numbers are printed in shortest round-trip form.
void require_solved(const RiemannSolution& solution, const Material& material, double t, double x,
                    UnitSystem units = UnitSystem::natural);

/// ln s within which a stretch, its inverse and the pressures of the built-in laws stay
/// within double precision: s in [1e-300, 1e300].
inline constexpr double kRepresentableLogStretch = 690.0;
/// True if s lies within that range.
[[nodiscard]] bool representable(Stretch s);

/// A shock between an outer state and a star state (same material), family -1 or +1.
[[nodiscard]] FrontSpeeds shock_speeds(const Material& material, const State& outer, const State& star, int family);

/// A front between states a (left) and b (right) of one material, as its label jump
/// condition m [τ] = −[v] (τ = s/γ) sees it, written without cancellation however weak:
/// with h = (φb − φa)/2 and r = sb/sa − 1,
///   [v] cosh φa cosh φb = sinh(φb − φa) = 2 sinh h cosh h,
///   [τ] cosh φa cosh φb = sa (r cosh φa − 2 sinh(φa + h) sinh h).
struct LabelJump {
  Hyperbolic left;                ///< of φa
  double left_stretch = 1.0;      ///< sa
  double stretch_ratio_m1 = 0.0;  ///< r = sb/sa − 1
  double scaled_v = 0.0;          ///< [v] cosh φa cosh φb
  double scaled_tau = 0.0;        ///< [τ] cosh φa cosh φb
  Hyperbolic right;               ///< of φb, where right_known (a caller had it at hand)
  bool right_known = false;
  /// m = −[v]/[τ] (infinite or NaN where [τ] vanishes).
  [[nodiscard]] double speed() const { return -scaled_v / scaled_tau; }
};
[[nodiscard]] LabelJump label_jump(const State& a, const State& b);
/// label_jump with hyperbolic(a.rapidity) at hand.
[[nodiscard]] LabelJump label_jump(const State& a, const Hyperbolic& at_a, const State& b);

/// The energy a shock removes per unit time and area, D = m [E] − [p v] (docs/physics.md), between its
/// left and right states (one material, joined by the label and momentum jump conditions; m
/// from the label condition). D is cubic in the strength of a weak shock while [E] and [p v]
/// are linear: it is computed from the jump itself, without that cancellation, as
///   D = m ([p] δτ − [v] δM),   δf = ∫₀¹ f dθ − (f₀ + f₁)/2 = ∫₀¹ (½ − θ) f'(θ) dθ,
/// along the straight path from left to right in (p, v), with τ = s(p)/γ(v), M = h(p) γ(v) v,
/// h = (e + p) s, dh/dp = s (from dE = −p dτ + v dM and the jump conditions). Strong shocks
/// (|ln(s_r/s_l)| > 0.3) use the difference directly, and so does any shock where the
/// difference's round-off, 8 ε (|m| (|E_l| + |E_r|) + |p_l v_l| + |p_r v_r|), is below
/// `relative_precision` × |D| (0: never): a front tracker at a coarse tolerance asks for
/// only the digits its books need, at a fraction of the cost. Fails only if a stretch on the
/// path cannot be found.
[[nodiscard]] Solved<double> shock_dissipation_rate(const Material& material, const State& left, const State& right,
                                                    double relative_precision = 0.0);
/// shock_dissipation_rate with what a caller has at hand: p and e + p of either state (NaN
/// stretch: evaluated here) and the label jump between them.
[[nodiscard]] Solved<double> shock_dissipation_rate(const Material& material, const State& left, JumpLaws at_left,
                                                    const State& right, JumpLaws at_right, const LabelJump& jump,
                                                    double relative_precision = 0.0);

}  // namespace rigidity
