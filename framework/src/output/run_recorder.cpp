// The sink of a run's outputs, its stop requests and its progress reports.
#include "rigidity/run_recorder.hpp"

#include <algorithm>

namespace rigidity {

namespace detail {
std::atomic<bool> interrupt_flag{false};
}  // namespace detail

void request_interrupt() noexcept { detail::interrupt_flag.store(true, std::memory_order_relaxed); }
void clear_interrupt() noexcept { detail::interrupt_flag.store(false, std::memory_order_relaxed); }
bool interrupt_requested() noexcept { return detail::interrupt_flag.load(std::memory_order_relaxed); }

namespace {
/// Wall-clock time between two readings of the clock in poll(): the stride of polls
/// between readings adapts to it, so that a solver polling ten million times a
/// second pays for a clock reading about every 20 ms, and one polling ten times a
/// second at every poll.
constexpr double kCheckEvery_s = 0.02;
constexpr long kMaxStride = 1L << 20;
}  // namespace

void RunRecorder::event(const RunEvent& e) {
  const auto count = std::find_if(event_counts_.begin(), event_counts_.end(),
                                  [&](const std::pair<std::string, long>& c) { return c.first == e.kind; });
  if (count == event_counts_.end()) {
    event_counts_.emplace_back(e.kind, 1);
  } else {
    ++count->second;
  }
  if (first_events_.size() < kFirstEvents) first_events_.push_back(e);
  record_event(e);
}

void RunRecorder::stop(std::string reason) {
  if (stop_pending_ || stopped()) return;
  stop_pending_ = true;
  stop_reason_ = std::move(reason);
}

void RunRecorder::halt(double t, std::string reason) {
  stop_pending_ = false;
  status_ = RunStatus::inadmissible;
  t_reached_ = t;
  stop_reason_ = std::move(reason);
}

void RunRecorder::on_progress(ProgressCallback callback, double delay_s, double interval_s) {
  progress_ = std::move(callback);
  progress_delay_s_ = delay_s;
  progress_interval_s_ = interval_s;
}

bool RunRecorder::poll_slowly(double t, long fronts_alive, long interactions) {
  take_outer_stop();
  if (stop_pending_) {
    stop_pending_ = false;
    status_ = RunStatus::stopped;
    t_reached_ = t;
    return true;
  }
  if (detail::interrupt_flag.load(std::memory_order_relaxed)) {
    status_ = RunStatus::interrupted;
    t_reached_ = t;
    stop_reason_ = "interrupted (Ctrl-C)";
    return true;
  }
  const Clock::time_point now = Clock::now();
  if (polls_at_check_ == 0) {  // the first poll starts the clock
    start_ = last_check_ = last_report_ = now;
    polls_at_check_ = polls_;
    next_check_ = polls_ + 1;
    return false;
  }
  // The next reading about kCheckEvery_s from now, at the rate of polls seen since the last.
  const double since_check = std::chrono::duration<double>(now - last_check_).count();
  const long polls_since = polls_ - polls_at_check_;
  long stride = since_check > 0.0 ? static_cast<long>(static_cast<double>(polls_since) * kCheckEvery_s / since_check)
                                  : 2 * polls_since;
  stride = std::clamp(stride, 1L, std::min(kMaxStride, 2 * polls_since + 1));
  last_check_ = now;
  polls_at_check_ = polls_;
  next_check_ = polls_ + stride;

  const RunRecorder& reporter = progress_ || outer_ == nullptr ? *this : *outer_;
  if (!reporter.progress_) return false;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < reporter.progress_delay_s_) return false;
  if (last_report_ != start_ &&
      std::chrono::duration<double>(now - last_report_).count() < reporter.progress_interval_s_)
    return false;
  last_report_ = now;
  reporter.progress_(RunProgress{t, fronts_alive, interactions, elapsed});
  take_outer_stop();  // the outer's callback may have asked for it: the next poll() stops
  return false;
}

void RunRecorder::complete(RunResult& result, double t_end) {
  result.status = to_string(status_);
  result.t_reached = stopped() ? t_reached_ : t_end;
  result.stop_reason = stopped() ? stop_reason_ : std::string();
  result.events = first_events_;
  result.event_counts = event_counts_;
}

void MemoryRecorder::complete(RunResult& result, double t_end) {
  RunRecorder::complete(result, t_end);
  result.events = std::move(events_);
  result.fronts = std::move(fronts_);
  result.probes = std::move(probes_);
  result.snapshots = std::move(snapshots_);
}

}  // namespace rigidity
