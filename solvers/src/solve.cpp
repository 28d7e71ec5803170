#include "rigidity/solvers/solve.hpp"

#include <string>

#include "rigidity/errors.hpp"
#include "rigidity/solvers/characteristics.hpp"
#include "rigidity/solvers/finite_volume.hpp"

namespace rigidity {

RunResult solve(const Scene& scene, RunRecorder& recorder) {
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
