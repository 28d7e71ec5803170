#pragma once
/// The budgets that bound a front-tracking run (solver.max_fronts,
/// solver.max_interactions), and what a run that reaches one tells its user.

#include <string>

#include "rigidity/scene.hpp"

namespace rigidity {

enum class Budget {
  fronts,        ///< solver.max_fronts: fronts alive at once (memory)
  interactions,  ///< solver.max_interactions: Riemann problems solved (time)
};

/// Which budget the run reached at time t [natural units] and, for this scene, why
/// fronts multiply and what to change: advice that can help this scene only (a
/// coarser tolerance only where fans are split, the finite-volume method only where
/// reflections multiply fronts). Times in the scene's units.
[[nodiscard]] std::string budget_stop_reason(const Scene& scene, Budget budget, double t);

}  // namespace rigidity
