#pragma once
/// A validated scene (docs/scenes.md), in natural units (c = 1), ready for a solver.
/// Produced only by the scene loader, which has checked every rule; solvers may
/// rely on it (bodies ordered left to right and not overlapping, |v| < 1, s admissible).

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/material.hpp"
#include "rigidity/quantity.hpp"
#include "rigidity/units.hpp"

namespace rigidity {

struct MaterialDecl {
  std::string name;   ///< the scene's name for it ("steel")
  std::string model;  ///< registry name ("rigid")
  std::shared_ptr<const Material> material;
  SourceLocation where;
  std::string parameters;  ///< "wave_speed=0.5;..." as given, natural units (rest_density left out)
};

/// A piece of a body with uniform initial state.
struct Segment {
  double length = 1.0;    ///< natural length ΔX
  double rapidity = 0.0;  ///< φ = artanh v (exact for ultra-relativistic bodies)
  Stretch stretch;        ///< initial stretch
  std::string material;   ///< scene material name (the body's unless overridden)
};

struct BodyDecl {
  std::string name;
  double position = 0.0;          ///< lab x of the left end at t = 0
  std::vector<Segment> segments;  ///< left to right; X runs from 0 to the sum of lengths
  SourceLocation where;
  [[nodiscard]] double natural_length() const;
};

enum class BoundaryType { free, wall, piston, traction };
/// A wall or a piston: a boundary with a position, which the bodies may touch and leave.
[[nodiscard]] constexpr bool stands(BoundaryType t) { return t == BoundaryType::wall || t == BoundaryType::piston; }

/// A piston's velocity history: v = velocity[i] for times[i] <= t < times[i+1]
/// (piecewise constant; times[0] = 0).
struct PistonMotion {
  std::vector<double> times;
  std::vector<double> rapidities;
  /// The table is interpolated linearly and these are the steps of its ramps: each change of
  /// speed emits a step of a smooth wave, not a jump. The rows as written are kept, for a
  /// solver that steps the ramps otherwise (linear_piston).
  bool ramps = false;
  std::vector<double> row_times, row_rapidities;
};

/// The rapidity at time t of a table (times, rapidities) whose velocity ramps linearly between
/// its rows, the last row's after it (0 for an empty table).
[[nodiscard]] double ramp_rapidity(const std::vector<double>& times, const std::vector<double>& rapidities, double t);

/// A piston whose velocity ramps linearly between the rows of its table (times, rapidities),
/// as a staircase: each ramp split into steps of at most `step` in rapidity (at most 1000 per
/// row), each holding the velocity of the ramp at its middle, each step taken when the ramp has
/// the mean of the values on its two sides (so that it leaves on that value's characteristic,
/// across the kinks between rows too); after the last row the velocity stays.
[[nodiscard]] PistonMotion linear_piston(const std::vector<double>& times, const std::vector<double>& rapidities,
                                         double step);

struct BoundaryDecl {
  BoundaryType type = BoundaryType::free;
  bool bonded = false;    ///< wall/piston pulls as well as pushes
  double position = 0.0;  ///< lab x at t = 0 (wall, piston); resolved by the loader
  PistonMotion piston;    ///< for type == piston
  /// For type == traction: the pressure applied to the end, p = pressures[i] for
  /// times[i] <= t < times[i+1] (times[0] = 0); natural units.
  std::vector<double> traction_times, traction_pressures;
  SourceLocation where;
};

enum class SolverMethod { characteristics, finite_volume };

/// The tolerance a scene with a genuinely nonlinear body runs at when it gives none: its fans
/// and the waves they cross are resolved to about this (steps of 0.7 √tolerance in Ψ), at a
/// cost every scene can afford; a scene of linearly degenerate bodies only stays exact.
inline constexpr double kNonlinearDefaultTolerance = 1.0e-4;
enum class FluxType { hll, exact };

struct SolverDecl {
  SolverMethod method = SolverMethod::characteristics;
  double tolerance = 1.0e-12;  ///< characteristics: target accuracy (fan step in Ψ)
  /// False for the default: 1e-12 where every body's material is linearly degenerate (every
  /// wave a jump: exact), else kNonlinearDefaultTolerance, which any scene can afford; the
  /// error bound is reported, not warned of.
  bool tolerance_given = false;
  /// characteristics: aim the error bound at the tolerance (`resolution: auto`, the default):
  /// runs at other resolutions measure the bound and the run keeps the one that meets the
  /// tolerance at least cost; false: resolve waves to the tolerance itself.
  bool auto_resolution = true;
  /// characteristics: what the tracker resolves waves to (fan steps, merges, weak waves); 0 for
  /// the tolerance. `resolution: auto` sets it for each run it makes.
  double resolution = 0.0;
  [[nodiscard]] double wave_resolution() const { return resolution > 0.0 ? resolution : tolerance; }
  /// characteristics, `resolution: auto`: the most interactions the aim spends over all its runs;
  /// beyond what it affords, waves are resolved more coarsely than the tolerance.
  long budget = 10000000;
  long max_fronts = 1000000;  ///< characteristics: most fronts alive at once; beyond, the run stops (status stopped)
  long max_interactions = 100000000;  ///< characteristics: most interactions of a run; beyond, the run stops
  int cells = 400;                    ///< finite volume
  int order = 2;                      ///< finite volume: 1 or 2
  double cfl = 0.5;                   ///< finite volume
  FluxType flux = FluxType::hll;
};

struct ProbeDecl {
  std::string name;
  std::string body;
  double X = 0.0;  ///< material label probed (left → 0, right → l0)
  std::vector<Quantity> quantities;
  double every = 0.0;  ///< sampling interval; samples at 0, every, 2 every, ... ≤ t_end
  SourceLocation where;
  /// A probe at a fixed lab position instead of X (at_x): the body's state wherever it covers
  /// x; no sample while it does not.
  std::optional<double> lab_x;
};

struct SnapshotDecl {
  std::vector<double> times;
  std::vector<Quantity> quantities;
  int samples = 101;                ///< per body, uniform in X, both ends included
  std::vector<std::string> bodies;  ///< empty → every body
  SourceLocation where;
};

struct OutputsDecl {
  std::vector<ProbeDecl> probes;
  std::vector<SnapshotDecl> snapshots;
  bool fronts = false;
  bool hdf5 = false;  ///< run.h5 beside the CSV files (written by the command line)
};

struct Scene {
  std::string name;
  std::string source;  ///< file the scene was read from ("<default>" for the embedded one)
  UnitSystem units = UnitSystem::natural;
  std::vector<std::string> plugins;
  std::map<std::string, MaterialDecl> materials;
  std::vector<BodyDecl> bodies;  ///< left to right
  BoundaryDecl left, right;
  SolverDecl solver;
  double t_end = 1.0;
  OutputsDecl outputs;
  std::vector<std::string> notes;  ///< what the loader changed for an override (outputs beyond a shorter end)
  /// Writes resolved_yaml(): set by the loader, which keeps the checked tree for it.
  std::function<std::string()> resolver;

  /// The scene as run, every default filled in, in the scene's units, as YAML text. Made
  /// when asked (a run that writes no files, in a sweep or from Python, never asks).
  [[nodiscard]] std::string resolved_yaml() const { return resolver ? resolver() : std::string(); }

  [[nodiscard]] const Material& material_of(const Segment& seg) const { return *materials.at(seg.material).material; }
  /// Every body's every segment is of a linearly degenerate material: every wave a jump, no
  /// fan to split into steps.
  [[nodiscard]] bool linearly_degenerate() const {
    for (const BodyDecl& body : bodies)
      for (const Segment& segment : body.segments)
        if (!material_of(segment).linearly_degenerate()) return false;
    return true;
  }
};

}  // namespace rigidity
