// Where a material's law is convex in the sense the Riemann solvers assume.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rigidity/material.hpp"

namespace rigidity {

/// The genuine nonlinearity at ln s: g = dc_s/d(ln s) − c_s (1 − c_s²) (a centred difference of
/// c_s in ln s, kept inside `window`). Along a fan of the C+ family J− = φ − Ψ is constant and the
/// characteristics run at the lab speed tanh(J− + Ψ(s) + artanh c_s), along a C− fan at
/// tanh(J+ − Ψ(s) − artanh c_s); with dΨ/d(ln s) = −c_s, the argument's derivative in ln s is
/// ±g/(1 − c_s²) for either family and whatever the state. g < 0: compressions are shocks and
/// expansions fans (as for a gas); g > 0: the reverse; g = 0: linearly degenerate (rigid, hooke).
[[nodiscard]] double genuine_nonlinearity(const Material& material, double log_s, StretchRange window);

/// A change of sign of the genuine nonlinearity: where it is (bisected between two samples) and
/// the two samples of either sign around it.
struct Inflection {
  double stretch = 0.0;
  double s_before = 0.0, g_before = 0.0;  ///< the sample on one side
  double s_after = 0.0, g_after = 0.0;    ///< and on the other
  /// "at s = ...: not convex: the genuine nonlinearity ... changes sign there (g = ... at s = ...,
  /// where compressions are shocks and expansions fans; g = ... at s = ..., where ...)".
  [[nodiscard]] std::string describe() const;
};

/// Every change of sign of g on a finite `window` (less 2 % of its width in ln s at either end,
/// where numeric laws are fitted from one side), sampled at 401 stretches even in ln s and each
/// bisected to round-off, in ascending order; |g| below 2e-3 of the largest c_s there counts as
/// zero (linearly degenerate: above the round-off of numeric laws' g, below an inflection that
/// matters). Empty if g keeps one sign.
[[nodiscard]] std::vector<Inflection> find_inflections(const Material& material, StretchRange window);

/// The one of them nearest to s = 1; none if g keeps one sign.
[[nodiscard]] std::optional<Inflection> find_inflection(const Material& material, StretchRange window);

/// The window Material::inflection_logs scans: the admissible range within [1/100, 100].
[[nodiscard]] StretchRange inflection_window(const Material& material);

}  // namespace rigidity
