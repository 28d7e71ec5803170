#pragma once
// Closed forms the front tracker is built on: the strength of a wave, the speed of a front
// from the label jump condition, the wave curves and the exact star state of two states of
// one material (the Hugoniot in closed form is the Riemann module's, hugoniot_rapidity).
#include <limits>
#include <string>

#include "rigidity/material.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/status.hpp"

namespace rigidity::characteristics {

/// The strength of a wave of family `family` between two states of one material: the jump
/// of its own Riemann invariant (J+ = φ + Ψ for a C+ wave, J− = φ − Ψ for a C− wave), in
/// units of rapidity whatever the material. Signed: from `a` to `b`.
double wave_strength(const Material& m, const State& a, const State& b, int family);

/// Both speeds of a front between states a (left) and b (right) from the label jump condition
/// m [s/γ] = −[v]; its lab speed is then the same seen from either side, so lab positions
/// stay continuous across it. Written without cancellation for weak fronts:
/// m = −sinh(φb − φa) / (sb cosh φa − sa cosh φb). Falls back to the mean characteristic
/// speed of family `family` where the jump is too small to define it, or where that speed
/// would run against the family's direction or faster than light (coarse fan steps).
FrontSpeeds label_jump_speeds(const Material& m, const State& a, const State& b, int family);
/// label_jump_speeds with the label jump between a and b at hand.
FrontSpeeds label_jump_speeds(const Material& m, const State& a, const State& b, int family, const LabelJump& jump);

/// One end of a wave curve: its state, Ψ there, the characteristic speed (dX/dt) of the
/// curve's family there, and p and e + p once a Hugoniot asks for them.
struct CurveEnd {
  State state;
  double psi = 0.0;
  double speed = 0.0;
  JumpLaws laws;
};

/// A stretch e^z tried on both curves of a crossing: s, Ψ and c_s there, and p and e + p once
/// a Hugoniot asks for them.
struct TrialStretch {
  double z = 0.0;
  double stretch = 0.0;  ///< e^z
  double psi = 0.0;
  double sound_speed = 0.0;
  JumpLaws laws;
};

/// The rapidity at stretch e^z on the wave curve of family `family` through `outer`: the
/// closed-form Hugoniot where that wave is a shock, else the integral curve (the other
/// family's invariant carried across: φ = φ_outer + family (Ψ − Ψ_outer)). Both curves of a
/// crossing are asked at the same trial stretch, and a root find along one curve asks at
/// the same outer state, so each evaluates its material there once. `shock`, if given, says
/// which of the two it was; `fan_speeds`, if given, receives the characteristic speeds of the
/// family at the state on the integral curve where the wave is a fan step (NaN otherwise).
Solved<double> curve_rapidity(const Material& m, CurveEnd& outer, TrialStretch& at, int family, bool* shock = nullptr,
                              FrontSpeeds* fan_speeds = nullptr);

/// The star state of two states of one material, with what its two waves are: [0] the C−
/// wave (from `left`), [1] the C+ wave (from `right`). `off` is how far the star's rapidity
/// is from each wave's curve at its stretch (the secant's last mismatch, split in two);
/// `converged`: that mismatch is at round-off.
struct SameMaterialStar {
  State state;
  bool shock[2] = {false, false};
  double off[2] = {0.0, 0.0};
  bool converged = false;
  /// The star's characteristic speeds of each family where its wave is a fan step: those of
  /// the last trial's state on that curve (NaN otherwise). Converged, that state is the
  /// star's to round-off.
  FrontSpeeds speeds[2] = {{std::numeric_limits<double>::quiet_NaN(), 0.0},
                           {std::numeric_limits<double>::quiet_NaN(), 0.0}};
  /// p and e + p at the star's stretch, where a Hugoniot asked for them (NaN stretch otherwise).
  JumpLaws laws;
};

/// Two states of one material with what the curves through them need: Ψ, and the
/// characteristic speed of the family whose curve leaves each (C− from the left state, C+
/// from the right one). A crossing has them at hand.
struct CrossingEnds {
  CurveEnd left;   ///< of the C− curve
  CurveEnd right;  ///< of the C+ curve
};

/// The exact star state between two states of one material: ln s* where the C− curve
/// through `left` meets the C+ curve through `right`, by secant steps from `guess` (the
/// two-rarefaction star, within third order of the answer for weak waves). Every curve is
/// closed form, so a weak interaction costs a few evaluations of the material; the last
/// evaluation is the answer: the search ends at a mismatch at round-off, or at one below
/// `accept` (a caller that books `off` as an error may take the guess of a weak crossing as
/// it is).
Solved<SameMaterialStar> same_material_star(const Material& m, CrossingEnds& ends, const State& guess,
                                            double accept = 0.0);

bool same_state(const State& a, const State& b);

/// Lab positions equal up to the round-off of summing segment lengths.
bool touching(double x1, double x2);

std::string number(double v);

}  // namespace rigidity::characteristics
