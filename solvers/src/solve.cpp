#include "rigidity/solvers/solve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/number_text.hpp"
#include "rigidity/solvers/characteristics.hpp"
#include "rigidity/solvers/finite_volume.hpp"

namespace rigidity {

namespace {

/// A wall's lab velocity from time t on, up to its next change, and when that is.
struct WallLeg {
  double velocity = 0.0;
  double until = 0.0;
};

WallLeg wall_leg(const BoundaryDecl& wall, double t) {
  const PistonMotion& motion = wall.piston;
  if (wall.type != BoundaryType::piston || motion.times.empty()) return {0.0, std::numeric_limits<double>::infinity()};
  const auto after = std::upper_bound(motion.times.begin(), motion.times.end(), t);
  const std::size_t k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, after - motion.times.begin() - 1));
  return {std::tanh(motion.rapidities[k]),
          after == motion.times.end() ? std::numeric_limits<double>::infinity() : *after};
}

/// A stop as inadmissible is firm where the margin by which the material would be taken beyond
/// its limit (in Ψ) is at least this many times the run's error bound. The bound is a mean over
/// the bodies' natural length of |δφ| + |δΨ|: the state where two sides meet can be off by more
/// than that mean. Measured on the 13 scenes of random_scene.py (seeds 1-100, tolerance 1e-3,
/// time.end 20) that stop this way, each against the same scene at 1e-4: the Ψ needed moved by
/// up to 14 times the 1e-3 run's bound (seed 24: 0.033 against 2.3e-3, the stop 0.01 later), and
/// the two stops that moved far (by 0.65 and 0.07 in time, at 0.014 c instead of 0.42 c and
/// 0.08 c instead of 0.61 c) had margins of 0.1 and 0.3 times their bounds.
constexpr double kFirmMargin = 100.0;
/// A bound at least this large is not small against anything a verdict rests on.
constexpr double kLargeBound = 0.01;

}  // namespace

InadmissibleStop::InadmissibleStop(RunResult result)
    : InadmissibleError(result.stop_reason, result.inadmissible.value_or(Inadmissibility::at(result.t_reached))),
      result_(std::make_shared<const RunResult>(std::move(result))) {}

std::string judge_inadmissible_stop(RunResult& result, UnitSystem units) {
  const Inadmissibility at = result.inadmissible.value_or(Inadmissibility::at(result.t_reached));
  const double bound = result.solver_number("error_bound");
  const double margin = at.margin();
  const std::string when = "at t = " + in_units(result.t_reached, Dimension::time, units);
  const std::string beyond = "the margin by which the material would be taken beyond its limit (Psi " +
                             (std::isfinite(margin) ? shortest(margin) : std::string("not known")) + ")";
  std::string why;
  if (!std::isfinite(bound)) {
    why = "the " + (result.solver.empty() ? std::string("solver") : result.solver) +
          " solver reports no error bound to set against " + beyond +
          ": a finer resolution may move or remove this stop";
  } else if (!std::isfinite(margin)) {
    why = "the error bound " + when + " is " + shortest(bound) + " and " + beyond +
          ": a finer solver.tolerance may move or remove this stop";
  } else if (bound >= kLargeBound || kFirmMargin * bound > margin) {
    why = "the error bound " + when + ", " + shortest(bound) + ", is not small against " + beyond +
          " (a mean over the bodies, it allows larger errors where the sides meet): a finer solver.tolerance "
          "may move or remove this stop";
  } else {
    result.verdict_uncertain = false;
    return "the error bound " + when + ", " + shortest(bound) + ", is small against " + beyond + " (more than " +
           shortest(kFirmMargin) +
           " times it): a finer solver.tolerance is not expected to remove this stop, though it may move it a little";
  }
  result.verdict_uncertain = true;
  return why;
}

std::optional<WallMeeting> walls_meet(const Scene& scene) {
  if (!stands(scene.left.type) || !stands(scene.right.type)) return std::nullopt;
  // Both walls move on straight lines between the changes of either: the room between them
  // is linear on each leg, and they meet on the first leg where it reaches zero.
  double t = 0.0, x_left = scene.left.position, x_right = scene.right.position;
  while (t < scene.t_end) {
    const WallLeg left = wall_leg(scene.left, t), right = wall_leg(scene.right, t);
    const double end = std::min({left.until, right.until, scene.t_end});
    const double closing = left.velocity - right.velocity;
    if (closing > 0.0) {
      const double meet = t + (x_right - x_left) / closing;
      if (meet <= end) return WallMeeting{meet, x_left + left.velocity * (meet - t)};
    }
    x_left += left.velocity * (end - t);
    x_right += right.velocity * (end - t);
    t = end;
  }
  return std::nullopt;
}

RunResult solve(const Scene& scene, RunRecorder& recorder) {
  if (const std::optional<WallMeeting> meeting = walls_meet(scene)) {
    // Known from the scene alone: no method needs to ring the bodies ever faster as the room
    // closes to find it.
    double length = 0.0;
    for (const BodyDecl& b : scene.bodies) length += b.natural_length();
    const auto wall = [](const BoundaryDecl& d) { return d.type == BoundaryType::piston ? "piston" : "wall"; };
    throw InadmissibleError(
        std::string("no classical solution up to time.end = ") + in_units(scene.t_end, Dimension::time, scene.units) +
        ": the left " + wall(scene.left) + " and the right " + wall(scene.right) +
        " meet at t = " + in_units(meeting->t, Dimension::time, scene.units) +
        ", x = " + in_units(meeting->x, Dimension::length, scene.units) +
        ", and would crush the bodies between them (" + in_units(length, Dimension::length, scene.units) +
        " of natural length) to zero length there; end the run before they meet (time.end below " +
        in_units(meeting->t, Dimension::time, scene.units) + ")");
  }
  RunResult result;
  if (scene.solver.method == SolverMethod::characteristics) {
    result = solve_characteristics(scene, recorder);
  } else if (scene.solver.method == SolverMethod::finite_volume) {
    result = solve_finite_volume(scene, recorder);
  } else {
    throw NumericalError("unknown solver method " + std::to_string(static_cast<int>(scene.solver.method)) +
                         " (not characteristics or finite_volume)");
  }
  if (result.status == to_string(RunStatus::inadmissible)) {
    result.verdict = judge_inadmissible_stop(result, scene.units);
    throw InadmissibleStop(std::move(result));
  }
  return result;
}

RunResult solve(const Scene& scene) {
  MemoryRecorder recorder;
  return solve(scene, recorder);
}

}  // namespace rigidity
