#include "rigidity/solvers/solve.hpp"

#include "rigidity/errors.hpp"
#include "rigidity/solvers/characteristics.hpp"
#include "rigidity/solvers/finite_volume.hpp"

namespace rigidity {

RunResult solve(const Scene& scene) {
  switch (scene.solver.method) {
    case SolverMethod::characteristics: return solve_characteristics(scene);
    case SolverMethod::finite_volume: return solve_finite_volume(scene);
  }
  throw NumericalError("unknown solver method");
}

}  // namespace rigidity
