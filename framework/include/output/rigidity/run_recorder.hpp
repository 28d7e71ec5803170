#pragma once
/// Where a solver sends its outputs as it produces them, and whom its main loop asks
/// whether to go on (docs/cli.md, "What a run writes").
///
/// A solver hands every front segment, probe sample, snapshot sample and event to a
/// RunRecorder the moment it has it, and keeps none of them itself: the memory a run
/// needs is its state, not its history. MemoryRecorder keeps them in RunResult's
/// vectors (tests, the library API); the streaming recorder of output.hpp writes them
/// to the run directory as CSV rows.
///
/// The solver's main loop calls poll() between interactions (or steps): a budget
/// reached (stop()) or an interrupt (request_interrupt(), e.g. from a SIGINT handler)
/// makes poll() return true, and the solver closes its books at the time reached
/// instead of t_end. poll() also drives the progress line.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "rigidity/run_result.hpp"

namespace rigidity {

/// How a run ended.
enum class RunStatus {
  ok,            ///< reached t_end
  stopped,       ///< reached a budget (solver.max_fronts, solver.max_interactions)
  interrupted,   ///< interrupted (Ctrl-C)
  inadmissible,  ///< met a state with no classical solution (a material crushed to zero length, ...)
};
[[nodiscard]] constexpr const char* to_string(RunStatus s) {
  switch (s) {
    case RunStatus::ok: return "ok";
    case RunStatus::stopped: return "stopped";
    case RunStatus::interrupted: return "interrupted";
    case RunStatus::inadmissible: return "inadmissible";
  }
  return "?";
}

/// Where a run is, for a progress line.
struct RunProgress {
  double t = 0.0;          ///< simulated time reached [natural units]
  long fronts_alive = -1;  ///< fronts tracked now; -1 for a solver that tracks none
  long interactions = 0;   ///< Riemann problems solved so far (RunStats::interactions)
  double elapsed_s = 0.0;  ///< wall-clock seconds since the first poll
};

/// Asks every running solver to stop cleanly at its next poll (status `interrupted`).
/// Async-signal-safe: a SIGINT handler may call it.
void request_interrupt() noexcept;
/// Clears the request (a test that simulated an interrupt, or a new run).
void clear_interrupt() noexcept;
[[nodiscard]] bool interrupt_requested() noexcept;

namespace detail {
extern std::atomic<bool> interrupt_flag;
static_assert(std::atomic<bool>::is_always_lock_free, "the interrupt flag is set from a signal handler");
}  // namespace detail

/// The sink of a run's outputs, in natural units, in the order the solver produces them.
class RunRecorder {
 public:
  /// Events summary.json lists one by one; the rest are counted there (events.csv has all).
  static constexpr std::size_t kFirstEvents = 100;

  RunRecorder() = default;
  virtual ~RunRecorder() = default;
  RunRecorder(const RunRecorder&) = delete;
  RunRecorder& operator=(const RunRecorder&) = delete;

  // ---- outputs --------------------------------------------------------------------
  void front(const FrontSegment& segment) { record_front(segment); }
  void probe(const ProbeSample& sample) { record_probe(sample); }
  void snapshot(const SnapshotSample& sample) { record_snapshot(sample); }
  /// Counted by kind; the first kFirstEvents are kept for summary.json.
  void event(const RunEvent& event);

  // ---- stopping -------------------------------------------------------------------
  /// A budget is reached: the solver finishes what it is doing and its next poll()
  /// stops the run with status `stopped`. `reason` says which budget, when, and what
  /// to change; the first reason is kept.
  void stop(std::string reason);

  /// The solver met, at time t, a state with no classical solution (why: `reason`, the
  /// InadmissibleError's message): it stops at once, with its state complete up to t, closes
  /// its books at t (= t_reached()) and returns with status `inadmissible`.
  void halt(double t, std::string reason);

  /// Called by the solver's main loop before it advances past time t, with its state
  /// complete up to t. True: the run must stop; the solver closes its books at t
  /// (= t_reached()) and returns. Cheap enough to call at every interaction.
  [[nodiscard]] bool poll(double t, long fronts_alive, long interactions) {
    if (stop_pending_ || detail::interrupt_flag.load(std::memory_order_relaxed) || ++polls_ >= next_check_) [[unlikely]]
      return poll_slowly(t, fronts_alive, interactions);
    return false;
  }

  /// A stop was asked for (stop(), or an interrupt) that no poll() has acted on yet, or one has.
  [[nodiscard]] bool stop_asked() const {
    return stop_pending_ || stopped() || detail::interrupt_flag.load(std::memory_order_relaxed);
  }
  /// This recorder keeps a run for `outer` (`solver.resolution: auto` keeps each run it makes
  /// in memory until it has chosen one): its polls drive outer's progress callback (a progress
  /// line, Python's signal handlers) when it has none of its own, and a stop asked of outer
  /// (by that callback, or before the run) stops its run too.
  void relay_to(RunRecorder& outer) { outer_ = &outer; }

  /// Once poll() has returned true: why, and the time the run reached.
  [[nodiscard]] RunStatus status() const { return status_; }
  [[nodiscard]] bool stopped() const { return status_ != RunStatus::ok; }
  [[nodiscard]] double t_reached() const { return t_reached_; }
  [[nodiscard]] const std::string& stop_reason() const { return stop_reason_; }

  // ---- progress -------------------------------------------------------------------
  using ProgressCallback = std::function<void(const RunProgress&)>;
  /// `callback` is called from poll() every `interval_s` once the run has taken
  /// `delay_s` of wall-clock time (never for a run shorter than that).
  void on_progress(ProgressCallback callback, double delay_s = 1.0, double interval_s = 0.25);

  // ---- the end --------------------------------------------------------------------
  /// Hands `result` what the recorder holds for it: status, t_reached (t_end if the
  /// run was not stopped), stop_reason, event_counts and the first events.
  virtual void complete(RunResult& result, double t_end);

  [[nodiscard]] const std::vector<RunEvent>& first_events() const { return first_events_; }
  [[nodiscard]] const std::vector<std::pair<std::string, long>>& event_counts() const { return event_counts_; }

 protected:
  virtual void record_front(const FrontSegment& segment) = 0;
  virtual void record_probe(const ProbeSample& sample) = 0;
  virtual void record_snapshot(const SnapshotSample& sample) = 0;
  virtual void record_event(const RunEvent& event) = 0;

 private:
  using Clock = std::chrono::steady_clock;
  bool poll_slowly(double t, long fronts_alive, long interactions);
  /// A stop asked of the outer recorder (see relay_to) becomes this one's.
  void take_outer_stop() {
    if (outer_ != nullptr && outer_->stop_pending_ && !stop_pending_) {
      stop_pending_ = true;
      stop_reason_ = outer_->stop_reason_;
    }
  }

  bool stop_pending_ = false;
  RunRecorder* outer_ = nullptr;  ///< see relay_to
  RunStatus status_ = RunStatus::ok;
  double t_reached_ = 0.0;
  std::string stop_reason_;

  long polls_ = 0, next_check_ = 1;  ///< the clock is read when polls_ reaches next_check_
  long polls_at_check_ = 0;
  Clock::time_point start_, last_check_, last_report_;
  ProgressCallback progress_;
  double progress_delay_s_ = 1.0, progress_interval_s_ = 0.25;

  std::vector<RunEvent> first_events_;
  std::vector<std::pair<std::string, long>> event_counts_;  ///< by kind, in order of first appearance
};

/// Keeps every output in memory: what solve(scene) hands back in RunResult's vectors.
class MemoryRecorder final : public RunRecorder {
 public:
  /// Also moves every front, sample and event into `result`.
  void complete(RunResult& result, double t_end) override;

 private:
  void record_front(const FrontSegment& segment) override { fronts_.push_back(segment); }
  void record_probe(const ProbeSample& sample) override { probes_.push_back(sample); }
  void record_snapshot(const SnapshotSample& sample) override { snapshots_.push_back(sample); }
  void record_event(const RunEvent& event) override { events_.push_back(event); }

  std::vector<FrontSegment> fronts_;
  std::vector<ProbeSample> probes_;
  std::vector<SnapshotSample> snapshots_;
  std::vector<RunEvent> events_;
};

}  // namespace rigidity
