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
/// The scout resolves waves this many times more coarsely than the pilot.
constexpr double kScout = 10.0;
/// The finest resolution a run may take, as a fraction of the tolerance.
constexpr double kFinestResolution = 0.01;
/// How the work and the bound follow the resolution r, until two runs have measured it:
/// interactions ∝ r^-work (1 where smooth waves' steps, √r apart, cross, 2 where the cap on
/// fronts holds them; measured 1.1 to 1.7 on random scenes from 1e-3 to 1e-5), bound ∝ r^bound (1 where fan steps,
/// merges and weak waves make it: 0.16 × r for a gas bar between a bonded wall and a piston from
/// 1e-4 to 1e-5; 0.7 to 1 on random scenes, where transmissions carry errors on and grow them).
struct Scaling {
  double work = 1.5, bound = 1.0;
  /// Measured between runs a (coarser) and b, where both did enough to tell.
  void measure(double r_a, double interactions_a, double bound_a, double r_b, double interactions_b, double bound_b) {
    measure_work(r_a, interactions_a, r_b, interactions_b);
    if (bound_a > 0.0 && bound_b > 0.0) bound = std::clamp(std::log(bound_a / bound_b) / std::log(r_a / r_b), 0.5, 2.0);
  }
  /// The work's alone (a scout's bound, ten times coarser than the pilot, may fall with the
  /// resolution unlike the pilot's: 0.70 from 1e-3 to 1e-4 on a quiet four-body scene whose
  /// bound falls as 0.94 from 1e-4 to 5e-5).
  void measure_work(double r_a, double interactions_a, double r_b, double interactions_b) {
    if (interactions_a > 1e3 && interactions_b > 1e3)
      work = std::clamp(std::log(interactions_b / interactions_a) / std::log(r_a / r_b), 1.0, 2.5);
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

/// The runs `resolution: auto` makes, what they spent of `solver.budget`, and why the aim
/// ended short of the tolerance where it did.
class Aim {
 public:
  Aim(const Scene& scene, RunRecorder& recorder)
      : scene_(scene),
        recorder_(recorder),
        tolerance_(scene.solver.tolerance),
        left_(static_cast<double>(scene.solver.budget)) {}

  /// The pilot. In a scene with a genuinely nonlinear body, one that takes more than
  /// 1/kPilotShare of what is left of the budget is stopped
  /// and made again as coarsely as the work it would have taken to the end, as the default
  /// Scaling has it, says fits in that share (at least ten times more coarsely; at kCoarsestAim
  /// only the scene's own budgets stop it). False where none finished: an error, or a budget
  /// (the run at the tolerance then goes on as without the aim, or reports it), unless the
  /// recorder asked to stop, when the pilot is handed on as it is.
  bool pilot() {
    try {
      double r = std::max(tolerance_, on_ladder(std::min(kPilotResolution * tolerance_, kCoarsestAim), false));
      // Only fans split into steps make the work follow the resolution: a scene of linearly
      // degenerate bodies costs about the same at any, and its pilot is not stopped.
      const bool fanned = !scene_.linearly_degenerate();
      for (;;) {
        const bool coarsest = r >= kCoarsestAim || !fanned;
        const double share = left_ / kPilotShare;
        const long cap = coarsest ? scene_.solver.max_interactions : std::max(1L, static_cast<long>(share));
        Attempt a = run(r, cap);
        if (coarsest || !a.stopped_by(cap, scene_) || recorder_.stop_asked()) {
          runs_.push_back(std::move(a));
          break;
        }
        const double to_end = a.interactions() / std::max(a.result.t_reached / scene_.t_end, 1e-12);
        r = std::min(kCoarsestAim,
                     std::max(on_ladder(10.0 * r, true),
                              on_ladder(r * std::pow(to_end / std::max(share, 1.0), 1.0 / Scaling{}.work), true)));
      }
    } catch (const std::exception&) {
      return false;
    }
    if (!runs_.front().finished() || recorder_.stop_asked()) return recorder_.stop_asked();
    scout();
    return true;
  }

  /// Where the pilot of a scene with a genuinely nonlinear body is above the tolerance (and
  /// left no droplets), a run ten times more coarsely (a tenth of its work or less, at most
  /// kCoarsestAim) measures how the work follows the resolution before the first run finer
  /// than the pilot: what is left of the budget affords a resolution as its measured work
  /// says, not a guess. The scout is never the run handed on: only its work is kept.
  void scout() {
    const Attempt& pilot = runs_.front();
    const double r = on_ladder(kScout * pilot.resolution, true);
    // (A pilot that left droplets is refined no finer than the tolerance at first: see refine.)
    if (scene_.linearly_degenerate() || pilot.bound() <= tolerance_ || pilot.droplets() || pilot.spray() ||
        r > kCoarsestAim * (1.0 + 1e-12))
      return;
    Attempt a;
    try {
      a = run(r, std::max(1L, static_cast<long>(pilot.interactions())));
    } catch (const std::exception&) {
      return;
    }
    if (!a.finished()) return;
    scout_resolution_ = r;
    scout_interactions_ = a.interactions();
  }

  /// Runs at the resolution the last bound points to (next_resolution), at most kAutoChecks,
  /// until one is within the tolerance, the bound stops falling or the next run would not be
  /// finer; short_of_ says why it ended above the tolerance.
  void refine() {
    // A pilot that left droplets (a spray, maybe) is resolved no finer than the tolerance
    // until a run at it shows its bound still falls with the resolution: a spray's droplets
    // book an error that does not, and a pilot as coarse as kCoarsestAim is coarser than any a
    // spray takes.
    const double finest_allowed = on_ladder(kFinestResolution * tolerance_, true);
    const Attempt& pilot = runs_.front();
    double finest = pilot.spray() || pilot.droplets() ? tolerance_ : finest_allowed;
    Scaling scaling;
    if (scout_interactions_ > 0.0)
      scaling.measure_work(scout_resolution_, scout_interactions_, pilot.resolution, pilot.interactions());
    while (runs_.size() <= static_cast<std::size_t>(kAutoChecks) && runs_.back().bound() > tolerance_ &&
           !recorder_.stop_asked()) {
      const Attempt& last = runs_.back();
      bool by_budget = false;
      const double r = next_resolution(last, tolerance_, finest, scaling, left_, by_budget);
      short_of_ =
          by_budget
              ? "a finer resolution would take more than solver.budget = " + std::to_string(scene_.solver.budget) +
                    " interactions over the aim's runs"
          : finest < tolerance_ ? "no finer resolution is allowed (" + shortest(kFinestResolution) + " × the tolerance)"
                                : "the pilot, at the tolerance, left droplets: a spray's error does not fall with the "
                                  "resolution, so none finer is tried";
      if (!(r < last.resolution / 1.05)) break;
      const long cap = std::max(1L, std::min(static_cast<long>(left_), scene_.solver.max_interactions));
      Attempt next;
      try {
        next = run(r, cap);
      } catch (const std::exception&) {
        short_of_ = "a run at " + shortest(r) + " met a problem the coarser ones did not";
        break;  // keep what they give
      }
      short_of_ = next.stopped_by(cap, scene_)
                      ? "a run at " + shortest(r) + " took more than what was left of solver.budget"
                      : "the bound stopped falling with the resolution";
      scaling.measure(last.resolution, last.interactions(), last.bound(), r, next.interactions(), next.bound());
      // The same run again (a fan's steps at their widest, 0.02, at both resolutions): no sign
      // the bound stopped following the resolution, which is not yet finer where it counts.
      const bool same = next.finished() && next.result.stats.interactions == last.result.stats.interactions &&
                        next.bound() == last.bound();
      const bool falls =
          same || (next.finished() && next.bound() < last.bound() * std::pow(r / last.resolution, kLeastFall));
      if (r <= tolerance_) finest = finest_allowed;
      runs_.push_back(std::move(next));
      const std::size_t chosen = choose(runs_, tolerance_);
      for (std::size_t k = 0; k < runs_.size(); ++k)
        if (k != chosen) runs_[k].drop_outputs();
      if (!falls || runs_.back().bound() <= tolerance_) break;
      short_of_ = "the aim makes at most " + std::to_string(kAutoChecks + 1) + " runs";
    }
  }

  /// The run chosen (choose), handed to the recorder, with the aim's numbers and, where its
  /// bound is above the tolerance, where and why the aim stopped.
  RunResult hand_on() {
    const double pilot_bound = runs_.front().bound();
    Attempt& best = runs_[choose(runs_, tolerance_)];
    replay(best, recorder_);
    RunResult result = std::move(best.result);
    result.solver_numbers.emplace_back("resolution", best.resolution);
    result.solver_numbers.emplace_back("pilot_error_bound", pilot_bound);
    result.solver_numbers.emplace_back("resolution_runs", static_cast<double>(made_));
    result.solver_numbers.emplace_back("aim_interactions", static_cast<double>(scene_.solver.budget) - left_);
    result.stats.wall_time_s = time_;
    if (result.solver_number("error_bound") > tolerance_ && !short_of_.empty() && scene_.solver.tolerance_given)
      result.warnings.push_back("solver.resolution: auto resolved the waves at " + shortest(best.resolution) + " (" +
                                std::to_string(made_) + " runs): " + short_of_);
    recorder_.complete(result, scene_.t_end);
    return result;
  }

 private:
  /// A run at resolution r stopped at `cap` interactions, its work and time counted.
  Attempt run(double r, long cap) {
    Attempt a = attempt(scene_, r, cap, recorder_);
    left_ -= static_cast<double>(a.result.stats.interactions);
    time_ += a.result.stats.wall_time_s;
    ++made_;
    return a;
  }

  const Scene& scene_;
  RunRecorder& recorder_;
  double tolerance_;
  double left_;  ///< of the budget
  double time_ = 0.0;
  int made_ = 0;
  std::vector<Attempt> runs_;  ///< the pilot, then the runs that finished or were stopped
  double scout_resolution_ = 0.0, scout_interactions_ = 0.0;  ///< the scout's, if one was made
  std::string short_of_;                                      ///< why the aim ended with the bound above the tolerance
};

}  // namespace

/// `solver.resolution: auto` (the default): the bound is aimed at the tolerance. A pilot at
/// kPilotResolution × tolerance (at most kCoarsestAim, at least the tolerance) measures it; a
/// scene whose pilot is within the tolerance keeps it (an exact scene's bound is 0: one run).
/// In a scene with a genuinely nonlinear body, a pilot that takes more than 1/kPilotShare of
/// `solver.budget` is stopped and made again more coarsely (Aim::pilot), and a pilot above the
/// tolerance is followed by a scout ten times coarser that measures how the work follows the
/// resolution (Aim::scout).
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
  if (scene.solver.auto_resolution) {
    Aim aim(scene, recorder);
    if (aim.pilot()) {
      aim.refine();
      return aim.hand_on();
    }
  }
  Scene at_tolerance = scene;
  at_tolerance.solver.auto_resolution = false;
  RunResult result = characteristics::Tracker(at_tolerance, recorder).run();
  recorder.complete(result, scene.t_end);
  return result;
}

RunResult solve_characteristics(const Scene& scene) {
  MemoryRecorder recorder;
  return solve_characteristics(scene, recorder);
}

}  // namespace rigidity
