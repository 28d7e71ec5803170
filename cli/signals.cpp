// Signals that stop a run or a sweep cleanly (see StopOnSignals in rigidity/cli.hpp).
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <ctime>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/run_recorder.hpp"

namespace rigidity::cli {

namespace {
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<std::int64_t>::is_always_lock_free,
              "the signal state is set from a signal handler");

/// The first signal of the run (0 while none has arrived), and when it arrived [ns, CLOCK_MONOTONIC].
std::atomic<int> stopping_signal{0};
std::atomic<std::int64_t> stopping_since_ns{0};

/// The notice written on the first signal (empty under --quiet), built before any signal.
char notice[160] = {};
std::atomic<std::size_t> notice_length{0};

std::int64_t monotonic_ns() {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe (POSIX)
  return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

void on_signal(int signal) {
  const int saved_errno = errno;
  int none = 0;
  if (stopping_signal.compare_exchange_strong(none, signal)) {
    // The first: ask the solve or sweep to stop cleanly, and say so.
    stopping_since_ns.store(monotonic_ns());
    request_interrupt();
    const std::size_t length = notice_length.load();
    if (length > 0 && ::write(STDERR_FILENO, notice, length) < 0) {
      // Nothing to do: the run stops all the same.
    }
  } else if (signal == SIGINT && monotonic_ns() - stopping_since_ns.load() >= StopOnSignals::kGraceNs) {
    // A second Ctrl-C after the notice: end at once by SIGINT, abandoning the outputs. The
    // signal is blocked in its own handler, so it is delivered, with its default action, on return.
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    ::sigaction(SIGINT, &default_action, nullptr);
    ::raise(SIGINT);
  }
  // Any other repeat is the same request: GNU timeout sends SIGTERM to the program and then to
  // its process group, and a terminal's Ctrl-C reaches every process of the foreground group.
  errno = saved_errno;
}
}  // namespace

StopOnSignals::StopOnSignals(bool quiet) {
  stopping_signal.store(0);
  notice_length.store(0);
  if (!quiet) {
    // On a terminal the notice starts a line of its own, below the progress line.
    const char* text = ::isatty(STDERR_FILENO) == 1
                           ? "\nstopping: writing the outputs up to now (Ctrl-C again to quit without them)\n"
                           : "stopping: writing the outputs up to now (Ctrl-C again to quit without them)\n";
    std::strncpy(notice, text, sizeof notice - 1);
    notice_length.store(std::strlen(notice));
  }
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  for (const int signal : kSignals) sigaddset(&action.sa_mask, signal);  // one handler at a time per thread
  for (int k = 0; k < 2; ++k) installed_[k] = ::sigaction(kSignals[k], &action, &previous_[k]) == 0;
}

StopOnSignals::~StopOnSignals() {
  // Once a signal has asked to stop, the handler stays for the rest of the process, which is
  // ending: a repeat arriving after the outputs are written must not end it by that signal.
  if (stopping_signal.load() != 0) return;
  for (int k = 0; k < 2; ++k)
    if (installed_[k]) ::sigaction(kSignals[k], &previous_[k], nullptr);
}

int StopOnSignals::exit_status() { return stopping_signal.load() == SIGTERM ? kExitTerminated : kExitInterrupted; }

const char* StopOnSignals::cause() { return stopping_signal.load() == SIGTERM ? "SIGTERM" : "Ctrl-C"; }

}  // namespace rigidity::cli
