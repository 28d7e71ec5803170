#pragma once
/// Entry point of the solvers: evolve a validated scene to t_end and collect what
/// its outputs ask for.

#include <optional>

#include "rigidity/run_recorder.hpp"
#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"

namespace rigidity {

/// Where and when the scene's two walls (fixed walls or pistons, whose motion is given)
/// meet, if they do by time.end: the bodies between them would be squeezed to zero length
/// there, which no material survives.
struct WallMeeting {
  double t = 0.0, x = 0.0;
};
[[nodiscard]] std::optional<WallMeeting> walls_meet(const Scene& scene);

/// Runs scene.solver.method on the scene; fronts, samples and events go to
/// `recorder` as they are produced (a StreamingRecorder writes them to disk). A run
/// that reaches a budget, or is interrupted (request_interrupt()), ends normally with
/// RunResult::status `stopped` or `interrupted` and everything up to t_reached.
/// \throws InadmissibleError when the scene has no classical solution (exit 3): walls that
///         meet by time.end are refused before anything runs,
///         NumericalError when a numerical method fails (exit 1).
[[nodiscard]] RunResult solve(const Scene& scene, RunRecorder& recorder);

/// The same, every output kept in RunResult's vectors (a MemoryRecorder).
[[nodiscard]] RunResult solve(const Scene& scene);

}  // namespace rigidity
