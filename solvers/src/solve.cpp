#include "rigidity/solvers/solve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
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

}  // namespace

std::optional<WallMeeting> walls_meet(const Scene& scene) {
  if (scene.left.type == BoundaryType::free || scene.right.type == BoundaryType::free) return std::nullopt;
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
  switch (scene.solver.method) {
    case SolverMethod::characteristics: return solve_characteristics(scene, recorder);
    case SolverMethod::finite_volume: return solve_finite_volume(scene, recorder);
  }
  throw NumericalError("unknown solver method " + std::to_string(static_cast<int>(scene.solver.method)) +
                       " (not characteristics or finite_volume)");
}

RunResult solve(const Scene& scene) {
  MemoryRecorder recorder;
  return solve(scene, recorder);
}

}  // namespace rigidity
