// `solver.resolution: auto`, the default: the run aims its error bound at the tolerance. Runs
// at several resolutions measure how the scene's bound and work follow the resolution, each
// keeping its outputs in memory; the one chosen is handed to the recorder.
#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "rigidity/number_text.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/solvers/characteristics.hpp"
#include "tracker.hpp"

namespace rigidity {

namespace {

/// `solver.resolution: auto`: the first run resolves waves this many times more coarsely than
/// the tolerance (its work is 10 to 100 times smaller).
constexpr double kPilotResolution = 10.0;
/// The runs after it aim their bound at this fraction of the tolerance, so that a bound that
/// scales a little more slowly than the runs so far said still lands within it.
constexpr double kAutoTarget = 0.8;
/// A run whose bound fell by less than (the resolution's refinement)^kLeastFall from the run
/// before ends the aim: the bound has stopped following the resolution.
constexpr double kLeastFall = 0.3;
/// No run resolves waves more coarsely than this: the bound's picture of small errors that add
/// up fails beyond it (random Hooke and rigid bars pushed into a wall: error 9.2e-3 against a
/// bound of 5.6e-3 at 0.1), so a tolerance coarser than a tenth of it has a pilot no coarser.
constexpr double kCoarsestAim = 1e-2;
/// A pilot may spend this fraction of `solver.budget`: a scene whose pilot takes more could not
/// afford a run at the tolerance (10^1.2 to 10^2.5 times the pilot's work) within it.
constexpr double kPilotShare = 10.0;
/// Runs after the pilot, at most.
constexpr int kAutoChecks = 3;
/// The finest resolution a run may take, as a fraction of the tolerance.
constexpr double kFinestResolution = 0.01;
/// How the work and the bound follow the resolution r, until two runs have measured it:
/// interactions ∝ r^-work (at least 1.2: 1 where fan steps cross, 2 where the cap on fronts holds them;
/// measured 1.1 to 1.7 on random scenes from 1e-3 to 1e-5), bound ∝ r^bound (1 where fan steps,
/// merges and weak waves make it: 0.16 × r for a gas bar between a bonded wall and a piston from
/// 1e-4 to 1e-5; 0.7 to 1 on random scenes, where transmissions carry errors on and grow them).
struct Scaling {
  double work = 1.5, bound = 1.0;
  /// Measured between runs a (coarser) and b, where both did enough to tell.
  void measure(double r_a, double interactions_a, double bound_a, double r_b, double interactions_b, double bound_b) {
    const double refinement = std::log(r_a / r_b);
    if (interactions_a > 1e3 && interactions_b > 1e3)
      work = std::clamp(std::log(interactions_b / interactions_a) / refinement, 1.2, 2.5);
    if (bound_a > 0.0 && bound_b > 0.0) bound = std::clamp(std::log(bound_a / bound_b) / refinement, 0.5, 2.0);
  }
};

/// A run of the scene at `resolution`, its outputs kept in memory until it is chosen.
struct Attempt {
  double resolution = 0.0;
  RunResult result;
  [[nodiscard]] bool finished() const { return result.status == "ok" || result.status == "inadmissible"; }
  [[nodiscard]] double bound() const { return result.solver_number("error_bound"); }
  [[nodiscard]] double interactions() const { return static_cast<double>(std::max(1L, result.stats.interactions)); }
  /// Stopped at `cap` interactions, a budget the aim set below the scene's own.
  [[nodiscard]] bool stopped_by(long cap, const Scene& scene) const {
    return result.status == "stopped" && cap < scene.solver.max_interactions && result.stats.interactions >= cap;
  }
  /// Droplets were left: the scene may be a spray.
  [[nodiscard]] bool droplets() const { return result.solver_number("droplets") > 0.0; }
  /// A spray coarsened the resolution: its droplets' error does not fall with it.
  [[nodiscard]] bool spray() const { return result.solver_number("wave_resolution") > resolution; }
  /// Frees what it recorded: a run that will not be chosen keeps only its numbers.
  void drop_outputs() {
    std::vector<FrontSegment>().swap(result.fronts);
    std::vector<ProbeSample>().swap(result.probes);
    std::vector<SnapshotSample>().swap(result.snapshots);
    std::vector<RunEvent>().swap(result.events);
  }
};

/// The run to hand on: the coarsest within the tolerance, else the finished one with the least
/// bound (the first, the pilot, if none finished).
std::size_t choose(const std::vector<Attempt>& runs, double tolerance) {
  std::size_t chosen = 0;
  const auto within = [&](const Attempt& a) { return a.finished() && a.bound() <= tolerance; };
  for (std::size_t k = 1; k < runs.size(); ++k) {
    const Attempt &run = runs[k], &so_far = runs[chosen];
    if (within(so_far)) break;  // the runs grow finer
    if (within(run) || (run.finished() && run.bound() < so_far.bound())) chosen = k;
  }
  return chosen;
}

Attempt attempt(const Scene& scene, double resolution, long max_interactions, RunRecorder& outer) {
  Scene s = scene;
  s.solver.resolution = resolution;
  s.solver.max_interactions = std::min(max_interactions, scene.solver.max_interactions);
  MemoryRecorder memory;
  memory.relay_to(outer);
  Attempt a{resolution, characteristics::Tracker(s, memory).run()};
  memory.complete(a.result, scene.t_end);
  return a;
}

/// Hands what `run` recorded in memory to `recorder`, as if it had run there.
void replay(Attempt& run, RunRecorder& recorder) {
  RunResult& chosen = run.result;
  for (const FrontSegment& f : chosen.fronts) recorder.front(f);
  for (const ProbeSample& p : chosen.probes) recorder.probe(p);
  for (const SnapshotSample& s : chosen.snapshots) recorder.snapshot(s);
  for (const RunEvent& e : chosen.events) recorder.event(e);
  run.drop_outputs();
  if (chosen.status == "inadmissible") {
    recorder.halt(chosen.t_reached, chosen.stop_reason);
  } else if (chosen.status != "ok") {  // stopped by a budget, or interrupted
    if (chosen.status == "stopped") recorder.stop(chosen.stop_reason);
    (void)recorder.poll(chosen.t_reached, -1, chosen.stats.interactions);
  }
}

/// The value of the ladder of preferred numbers (Renard's R10: 1, 1.25, 1.6, 2, 2.5, 3.2, 4, 5,
/// 6.3, 8 in each decade) at or below `r` (`up`: at or above it). Resolutions the aim picks
/// come from it, so that two scenes whose pilots book nearly the same (one law written two
/// ways) take the same resolution, not two a hair apart.
double on_ladder(double r, bool up) {
  // Each rung as hundredths × a power of ten, divided by an exact power of ten where the
  // exponent is negative, so that 1e-6 prints as 1e-06, not 1.0000000000000002e-06.
  const int exponent = static_cast<int>(std::floor(std::log10(r))) - 2;
  const auto at = [exponent](double hundredths) {
    return exponent < 0 ? hundredths / std::pow(10.0, -exponent) : hundredths * std::pow(10.0, exponent);
  };
  constexpr double kRungs[] = {100, 125, 160, 200, 250, 320, 400, 500, 630, 800, 1000};
  double rung = at(kRungs[0]);
  for (const double k : kRungs) {
    const double value = at(k);
    if (up ? value >= r * (1.0 - 1e-12) : value <= r * (1.0 + 1e-12)) {
      rung = value;
      if (up) break;
    }
  }
  return rung;
}

/// The next resolution to try after `last`: the rung of the ladder (on_ladder) at or below the
/// one that would bring its bound to kAutoTarget × the tolerance, as `scaling` has it, no finer
/// than `finest`, and no finer than what is `left` of the budget affords (`by_budget`: that held
/// it back).
double next_resolution(const Attempt& last, double tolerance, double finest, const Scaling& scaling, double left,
                       bool& by_budget) {
  const double aimed = last.resolution * std::pow(kAutoTarget * tolerance / last.bound(), 1.0 / scaling.bound);
  const double r = std::max(finest, on_ladder(aimed, false));
  // The coarsest rung whose work, as `scaling` has it, fits within what is left.
  const double affordable =
      on_ladder(last.resolution * std::pow(last.interactions() / std::max(left, 1.0), 1.0 / scaling.work), true);
  by_budget = affordable > r;
  return std::min(std::max(r, affordable), last.resolution);
}

}  // namespace

/// `solver.resolution: auto` (the default): the bound is aimed at the tolerance. A pilot at
/// kPilotResolution × tolerance (at most kCoarsestAim, at least the tolerance) measures it; a
/// scene whose pilot is within the tolerance keeps it (an exact scene's bound is 0: one run).
/// A pilot that takes more than 1/kPilotShare of `solver.budget` is stopped and made again ten
/// times more coarsely (at kCoarsestAim, only the scene's own budgets stop it).
/// Otherwise runs at the resolution the last bound points to (next_resolution) follow, at
/// most kAutoChecks, until one is within the tolerance:
/// finer than the tolerance where the scene books more than it (transmissions and reflections
/// carry errors on and grow them); where the pilot left
/// droplets, only once a run at the tolerance has shown the bound still falls (a spray's
/// droplets' error does not); never finer than what is left of `solver.budget` affords, and
/// each run is stopped where it would spend more. Where the bound stops falling, or the next
/// run would not be finer, the aim ends. Each run records into memory,
/// and keeps its outputs while it is the one to choose (choose); that one is handed to
/// `recorder`. A pilot stopped by a budget of the scene's, or by an error, leaves the run to
/// the tolerance, as without the aim; a pilot interrupted, or stopped at `recorder`'s request,
/// is handed on as it is, and a later run so stopped ends the aim.
RunResult solve_characteristics(const Scene& scene, RunRecorder& recorder) {
  const double tolerance = scene.solver.tolerance;
  std::vector<Attempt> runs;
  double left = static_cast<double>(scene.solver.budget);  // of the aim's budget
  int made = 0;
  double time = 0.0;
  const auto spend = [&](const Attempt& a) {
    left -= static_cast<double>(a.result.stats.interactions);
    time += a.result.stats.wall_time_s;
    ++made;
  };
  if (scene.solver.auto_resolution) {
    try {
      double pilot = std::max(tolerance, on_ladder(std::min(kPilotResolution * tolerance, kCoarsestAim), false));
      for (;;) {
        const bool coarsest = pilot >= kCoarsestAim;
        const long cap = coarsest ? scene.solver.max_interactions : std::max(1L, static_cast<long>(left / kPilotShare));
        Attempt a = attempt(scene, pilot, cap, recorder);
        spend(a);
        if (coarsest || !a.stopped_by(cap, scene) || recorder.stop_asked()) {
          runs.push_back(std::move(a));
          break;
        }
        pilot = on_ladder(std::min(10.0 * pilot, kCoarsestAim), true);
      }
    } catch (const std::exception&) {
      runs.clear();  // the run at the tolerance meets the problem and reports it
    }
  }
  if (runs.empty() || (!runs.front().finished() && !recorder.stop_asked())) {
    Scene at_tolerance = scene;
    at_tolerance.solver.auto_resolution = false;
    RunResult result = characteristics::Tracker(at_tolerance, recorder).run();
    recorder.complete(result, scene.t_end);
    return result;
  }
  const double pilot_bound = runs.front().bound();
  // A pilot that left droplets (a spray, maybe) is resolved no finer than the tolerance until a
  // run at it shows its bound still falls with the resolution: a spray's droplets book an error
  // that does not, and a pilot as coarse as kCoarsestAim is coarser than any a spray takes.
  double finest =
      runs.front().spray() || runs.front().droplets() ? tolerance : on_ladder(kFinestResolution * tolerance, true);
  Scaling scaling;
  const std::string over_budget =
      "a finer resolution would take more than solver.budget = " + std::to_string(scene.solver.budget) +
      " interactions over the aim's runs";
  std::string short_of;  // why the aim ended with the bound above the tolerance
  while (runs.size() <= static_cast<std::size_t>(kAutoChecks) && runs.back().bound() > tolerance &&
         !recorder.stop_asked()) {
    const Attempt& last = runs.back();
    bool by_budget = false;
    const double r = next_resolution(last, tolerance, finest, scaling, left, by_budget);
    short_of = by_budget ? over_budget
               : finest < tolerance
                   ? "no finer resolution is allowed (" + shortest(kFinestResolution) + " × the tolerance)"
                   : "the pilot, at the tolerance, left droplets: a spray's error does not fall with the resolution, "
                     "so none finer is tried";
    if (!(r < last.resolution / 1.05)) break;
    const long cap = std::max(1L, std::min(static_cast<long>(left), scene.solver.max_interactions));
    Attempt next;
    try {
      next = attempt(scene, r, cap, recorder);
    } catch (const std::exception&) {
      short_of = "a run at " + shortest(r) + " met a problem the coarser ones did not";
      break;  // keep what they give
    }
    spend(next);
    short_of = next.stopped_by(cap, scene)
                   ? "a run at " + shortest(r) + " took more than what was left of solver.budget"
                   : "the bound stopped falling with the resolution";
    scaling.measure(last.resolution, last.interactions(), last.bound(), r, next.interactions(), next.bound());
    // The same run again (a fan's steps at their widest, 0.02, at both resolutions): no sign
    // the bound stopped following the resolution, which is not yet finer where it counts.
    const bool same = next.finished() && next.result.stats.interactions == last.result.stats.interactions &&
                      next.bound() == last.bound();
    const bool falls =
        same || (next.finished() && next.bound() < last.bound() * std::pow(r / last.resolution, kLeastFall));
    if (r <= tolerance) finest = on_ladder(kFinestResolution * tolerance, true);
    runs.push_back(std::move(next));
    const std::size_t chosen = choose(runs, tolerance);
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (k != chosen) runs[k].drop_outputs();
    if (!falls || runs.back().bound() <= tolerance) break;
    short_of = "the aim makes at most " + std::to_string(kAutoChecks + 1) + " runs";
  }
  Attempt& best = runs[choose(runs, tolerance)];
  replay(best, recorder);
  RunResult result = std::move(best.result);
  result.solver_numbers.emplace_back("resolution", best.resolution);
  result.solver_numbers.emplace_back("pilot_error_bound", pilot_bound);
  result.solver_numbers.emplace_back("resolution_runs", static_cast<double>(made));
  result.stats.wall_time_s = time;
  if (result.solver_number("error_bound") > tolerance && !short_of.empty() && scene.solver.tolerance_given)
    result.warnings.push_back("solver.resolution: auto resolved the waves at " + shortest(best.resolution) + " (" +
                              std::to_string(made) + " runs): " + short_of);
  recorder.complete(result, scene.t_end);
  return result;
}

RunResult solve_characteristics(const Scene& scene) {
  MemoryRecorder recorder;
  return solve_characteristics(scene, recorder);
}

}  // namespace rigidity
