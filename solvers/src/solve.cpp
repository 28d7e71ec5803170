#include "rigidity/solvers/solve.hpp"

#include "rigidity/errors.hpp"
#include "rigidity/solvers/characteristics.hpp"

namespace rigidity {

RunResult solve(const Scene& scene) {
  switch (scene.solver.method) {
    case SolverMethod::characteristics: return solve_characteristics(scene);
    case SolverMethod::finite_volume:
      throw InadmissibleError("solver.method: finite_volume is not available in this build yet; use characteristics");
  }
  throw NumericalError("unknown solver method");
}

}  // namespace rigidity
