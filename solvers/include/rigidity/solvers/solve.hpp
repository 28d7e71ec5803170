#pragma once
/// Entry point of the solvers: evolve a validated scene to t_end and collect what
/// its outputs ask for.

#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"

namespace rigidity {

/// Runs scene.solver.method on the scene.
/// \throws InadmissibleError when the scene has no classical solution (exit 3),
///         NumericalError when a numerical method fails (exit 1).
[[nodiscard]] RunResult solve(const Scene& scene);

}  // namespace rigidity
