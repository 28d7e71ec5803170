#pragma once
/// The method of characteristics as front tracking in Lagrangian coordinates.
///
/// The state is piecewise constant between fronts; every front carries its exact
/// speed. Fronts, body ends and material interfaces are nodes of a list per piece of
/// body; the next interaction (two nodes meeting, a gap closing, a piston changing
/// speed) is taken from a priority queue and resolved by an exact Riemann problem,
/// which emits the outgoing fronts. For linearly degenerate materials (rigid, hooke,
/// rigid_fluid) each interaction emits at most one front per family and the result
/// is exact to round-off; smooth waves (rarefaction fans of genuinely nonlinear
/// materials, a piston's ramps) are moved as steps of about √solver.tolerance and sampled
/// as the lines through the steps' values. solver.tolerance also bounds the
/// work: waves weaker than it allows are held back at contacts, neighbouring fronts
/// merge, and the live fronts are capped; the run reports the L1 error bound this
/// costs (solver.error_bound, docs/solvers.md, "What the tolerance means").

#include "rigidity/run_recorder.hpp"
#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"

namespace rigidity {

/// Fronts, samples and events go to `recorder` as they are produced. A budget
/// (solver.max_fronts, solver.max_interactions) or an interrupt stops the run
/// cleanly at the time reached (RunResult::status `stopped` or `interrupted`).
/// \throws InadmissibleError, NumericalError
[[nodiscard]] RunResult solve_characteristics(const Scene& scene, RunRecorder& recorder);
/// The same, keeping every output in RunResult's vectors (a MemoryRecorder).
[[nodiscard]] RunResult solve_characteristics(const Scene& scene);

/// While on (off by default, for all threads), the front tracker checks its invariants after
/// every interaction: each piece's nodes linked both ways and in label order, a light piece's
/// fronts in the order they run, the live fronts counted as they are, every front's strength
/// and carried error finite and non-negative, every error book finite and non-negative. A
/// broken one is a NumericalError naming it and the time. The randomized tests run with it on.
void check_tracker_invariants(bool on);

}  // namespace rigidity
