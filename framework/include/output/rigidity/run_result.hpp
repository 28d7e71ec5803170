#pragma once
/// What a solver hands back: everything the run outputs of docs/cli.md, "What a run writes" are written
/// from, in natural units. Only what the scene's outputs asked for is filled.
/// Fronts, samples and events go to a RunRecorder (run_recorder.hpp) as the solver
/// produces them; the vectors below hold them when the recorder keeps them in memory
/// (solve(scene)), and stay empty when it streams them to disk.

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/quantity.hpp"

namespace rigidity {

struct RunEvent {
  double t = 0.0;
  std::string kind;  ///< contact | separation | cavitation | ...
  double x = 0.0;    ///< lab position
  std::vector<std::string> bodies;
};

/// One body (or piece of a parted body) at t_end (at t_reached for a run that stopped early).
struct BodyResult {
  std::string name;
  double x_left = 0.0, x_right = 0.0;
  double velocity_mean = 0.0;  ///< weighted by rest mass
  double momentum = 0.0;       ///< per unit area
  double energy = 0.0;         ///< per unit area, rest energy included
  // Its parts, each computed on its own scale (not as differences of the total, whose
  // round-off can exceed them: a steel bar at 10 m/s has 5e-16 of its energy as motion).
  double kinetic_energy = 0.0;   ///< energy − the same body at rest in the same strain
  double internal_energy = 0.0;  ///< elastic: W(s) − ρ00 per unit natural length
  double rest_energy = 0.0;      ///< ρ00 c² per unit natural length
};

struct Conservation {
  double energy_initial = 0.0, energy_final = 0.0, energy_dissipated = 0.0;
  double momentum_initial = 0.0, momentum_final = 0.0, wall_impulse = 0.0;
  double wall_work = 0.0;  ///< energy given by walls and pistons (zero for fixed walls)
  /// What the front tracker's droplet model changed (a sliver of a body that carries no
  /// tension kept with its piece in the state the rest is released to): part of the balance.
  double energy_droplets = 0.0, momentum_droplets = 0.0;
  /// What the waves the front tracker follows approximately made: a step of a smooth wave
  /// moves at the speed that keeps lab positions continuous, which conserves energy and
  /// momentum only to third order in its strength, and a weak wave held back at an interface
  /// or contact leaves a pressure jump there. Part of the balance, like the droplets'.
  double energy_waves = 0.0, momentum_waves = 0.0;
  /// energy_final − (energy_initial + wall_work − energy_dissipated + energy_droplets + energy_waves).
  [[nodiscard]] double energy_residual() const {
    return energy_final - (energy_initial + wall_work - energy_dissipated + energy_droplets + energy_waves);
  }
  /// momentum_final − (momentum_initial + wall_impulse + momentum_droplets + momentum_waves).
  [[nodiscard]] double momentum_residual() const {
    return momentum_final - (momentum_initial + wall_impulse + momentum_droplets + momentum_waves);
  }
};

struct RunStats {
  long fronts = 0;               ///< fronts created over the run
  long interactions = 0;         ///< Riemann problems solved
  double wall_time_s = 0.0;      ///< solving only: parsing, sampling and writing apart
  double sampling_time_s = 0.0;  ///< evaluating probes and snapshots and handing them to the recorder
  /// Crossings of fronts inside light and lattice pieces: solved exactly without being
  /// visited (each piece knows where its fronts cross), so not among the interactions.
  long crossings_unvisited = 0;
};

struct ProbeSample {
  double t;
  int probe;  ///< index into scene.outputs.probes
  Quantity quantity;
  double value;
};

struct SnapshotSample {
  double t;
  int body;  ///< index into RunResult::body_names
  double X;
  Quantity quantity;
  double value;
};

/// What a line of the x–t diagram is (fronts.csv's `kind`): a shock, a contact (a jump that
/// moves with the characteristics: every wave of a linearly degenerate material), a step of a
/// rarefaction fan (or the fan's edge), a material interface, or a body's end.
enum class SegmentKind { shock, contact, rarefaction, interface, boundary };
[[nodiscard]] constexpr const char* to_string(SegmentKind k) {
  switch (k) {
    case SegmentKind::shock: return "shock";
    case SegmentKind::contact: return "contact";
    case SegmentKind::rarefaction: return "rarefaction";
    case SegmentKind::interface: return "interface";
    case SegmentKind::boundary: return "boundary";
  }
  return "?";
}

/// A straight piece of a front's world line in the lab x–t plane.
struct FrontSegment {
  double t0, x0, t1, x1;
  SegmentKind kind;
  int family;  ///< -1 left-moving (C-), +1 right-moving (C+), 0 neither
};

struct RunResult {
  /// ok | stopped (a budget) | interrupted (Ctrl-C) | inadmissible (no classical solution
  /// from t_reached on): to_string(RunStatus)
  std::string status = "ok";
  double t_reached = 0.0;   ///< where the books were closed: t_end when ok, else the time reached
  std::string stop_reason;  ///< stopped, interrupted or inadmissible: why, and what to change
  /// inadmissible: where and how (the impact, the limit and how far beyond it), whether the
  /// run's error bound could move or remove that stop, and a sentence saying which and why.
  std::optional<Inadmissibility> inadmissible;
  bool verdict_uncertain = false;
  std::string verdict;
  std::string solver;                                          ///< "characteristics" | "finite_volume"
  std::vector<std::pair<std::string, double>> solver_numbers;  ///< e.g. tolerance, cells
  /// The solver number called `name`, NaN if the run reported none.
  [[nodiscard]] double solver_number(std::string_view name) const {
    for (const auto& [key, value] : solver_numbers)
      if (key == name) return value;
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::vector<std::string> warnings;
  std::vector<RunEvent> events;  ///< every event (in memory), or the first RunRecorder::kFirstEvents (streamed)
  std::vector<std::pair<std::string, long>> event_counts;  ///< every event by kind, in order of first appearance
  std::vector<BodyResult> bodies;                          ///< at t_reached
  Conservation conservation;
  RunStats stats;
  std::vector<std::string> body_names;  ///< names snapshot samples refer to
  std::vector<ProbeSample> probes;
  std::vector<SnapshotSample> snapshots;
  std::vector<FrontSegment> fronts;
};

}  // namespace rigidity
