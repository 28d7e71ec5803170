// Signals that stop a run or a sweep cleanly (see StopOnSignals in rigidity/cli.hpp).
#include <csignal>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/run_recorder.hpp"

namespace rigidity::cli {

namespace {
volatile std::sig_atomic_t stopping_signal = 0;

void ask_to_stop(int signal) {
  stopping_signal = signal;
  request_interrupt();
}
}  // namespace

StopOnSignals::StopOnSignals() {
  struct sigaction action {};
  action.sa_handler = ask_to_stop;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // a second signal ends the process at once
  for (int k = 0; k < 2; ++k) installed_[k] = ::sigaction(kSignals[k], &action, &previous_[k]) == 0;
}

StopOnSignals::~StopOnSignals() {
  for (int k = 0; k < 2; ++k)
    if (installed_[k]) ::sigaction(kSignals[k], &previous_[k], nullptr);
}

int StopOnSignals::exit_status() { return stopping_signal == SIGTERM ? kExitTerminated : kExitInterrupted; }

const char* StopOnSignals::cause() { return stopping_signal == SIGTERM ? "SIGTERM" : "Ctrl-C"; }

}  // namespace rigidity::cli
