#pragma once
/// Entry point of the solvers: evolve a validated scene to t_end and collect what
/// its outputs ask for.

#include <memory>
#include <optional>
#include <string>

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

/// A run that met a state with no classical solution (a material crushed to zero length, ...):
/// the solver stopped there and closed its books at that instant. result() is the run up to
/// then, with status `inadmissible`, t_reached the instant, RunResult::inadmissible where and
/// how, its error bound there, and verdict_uncertain set where that bound could move or remove
/// the stop (RunResult::verdict says which, and why). what() is the solver's message.
class InadmissibleStop : public InadmissibleError {
 public:
  explicit InadmissibleStop(RunResult result);
  [[nodiscard]] const RunResult& result() const noexcept { return *result_; }

 private:
  std::shared_ptr<const RunResult> result_;  ///< shared: an exception is copied
};

/// The sentence that says whether the error bound of a run stopped as inadmissible could move
/// or remove that stop (and sets result.verdict_uncertain): the stop is taken as firm only
/// where the bound is small against how far beyond its limit the material would be taken.
[[nodiscard]] std::string judge_inadmissible_stop(RunResult& result, UnitSystem units);

/// Runs scene.solver.method on the scene; fronts, samples and events go to
/// `recorder` as they are produced (a StreamingRecorder writes them to disk). A run
/// that reaches a budget, or is interrupted (request_interrupt()), ends normally with
/// RunResult::status `stopped` or `interrupted` and everything up to t_reached.
/// \throws InadmissibleStop when the run meets a state with no classical solution (exit 3),
///         with the run up to that instant (the recorder has had everything up to then),
///         InadmissibleError when the scene has no classical solution before anything runs
///         (walls that meet by time.end),
///         NumericalError when a numerical method fails (exit 1).
[[nodiscard]] RunResult solve(const Scene& scene, RunRecorder& recorder);

/// The same, every output kept in RunResult's vectors (a MemoryRecorder).
[[nodiscard]] RunResult solve(const Scene& scene);

}  // namespace rigidity
