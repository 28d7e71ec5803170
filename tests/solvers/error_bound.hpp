#pragma once
// What the certified error bound of a characteristics run (summary.json's solver.error_bound:
// the mean over the bodies' natural length of |δφ| + |δΨ| at t_end) allows the energy and
// momentum books to miss. Momentum per unit label is (e+p) s sinh φ, so an error δφ moves it
// by (e+p) s cosh φ δφ: within a few ρ00 per unit label for the moderate states of the test
// scenes (|v| ≤ 0.5, s ≥ 1/2), and likewise the energy. Exact runs certify 0: their books
// must close to round-off.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"
#include "rigidity/solvers/characteristics.hpp"

namespace rigidity {

/// True if every material of the scene is linearly degenerate (every wave a jump).
inline bool linearly_degenerate(const Scene& scene) {
  for (const BodyDecl& body : scene.bodies)
    for (const Segment& segment : body.segments)
      if (!scene.material_of(segment).linearly_degenerate()) return false;
  return true;
}

/// For its lifetime the front tracker checks its invariants after every interaction
/// (check_tracker_invariants): a broken one fails the run with a NumericalError.
struct CheckedInvariants {
  CheckedInvariants() { check_tracker_invariants(true); }
  ~CheckedInvariants() { check_tracker_invariants(false); }
  CheckedInvariants(const CheckedInvariants&) = delete;
  CheckedInvariants& operator=(const CheckedInvariants&) = delete;
};

/// A number the solver reported under `solver` in summary.json; NaN if it did not.
inline double solver_number(const RunResult& r, std::string_view name) { return r.solver_number(name); }

/// The energy or momentum the books of a run may miss: 4 ρ00_max × (bound × total length),
/// plus the round-off of sums of order `scale`.
inline double certified_books_tolerance(const Scene& scene, const RunResult& r, double scale) {
  double length = 0.0, density = 0.0;
  for (const BodyDecl& body : scene.bodies)
    for (const Segment& segment : body.segments) {
      length += segment.length;
      density = std::max(density, scene.material_of(segment).rest_density());
    }
  const double bound = solver_number(r, "error_bound");
  return 4.0 * density * (std::isfinite(bound) ? bound : 0.0) * length + 1e-12 * scale;
}

}  // namespace rigidity
