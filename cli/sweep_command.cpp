// rigidity sweep SWEEP.yaml: every case of a parameter sweep, in-process on threads,
// into one table (SPEC §6). Ctrl-C stops handing out cases; a re-run resumes.
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <ostream>
#include <thread>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/sweep.hpp"

namespace rigidity::cli {

namespace {

/// While in scope, SIGINT asks the running cases to stop (request_interrupt); a second
/// Ctrl-C ends the process at once.
class SweepInterruptHandler {
 public:
  SweepInterruptHandler() {
    struct sigaction action {};
    action.sa_handler = [](int) { request_interrupt(); };
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    installed_ = ::sigaction(SIGINT, &action, &previous_) == 0;
  }
  ~SweepInterruptHandler() {
    if (installed_) ::sigaction(SIGINT, &previous_, nullptr);
  }
  SweepInterruptHandler(const SweepInterruptHandler&) = delete;
  SweepInterruptHandler& operator=(const SweepInterruptHandler&) = delete;

 private:
  struct sigaction previous_ {};
  bool installed_ = false;
};

}  // namespace

int sweep_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--out", true}, {"-j", true}, {"--quiet"}};
  const Arguments parsed = parse_arguments("sweep", args, kOptions);
  if (parsed.help) {
    out << help("sweep");
    return kExitOk;
  }
  if (parsed.positional.size() != 1) throw usage_error("sweep", "sweep takes one sweep file");
  if (const auto dir = parsed.value("--out"); dir && dir->empty()) throw usage_error("sweep", "--out needs a directory");
  unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
  if (const auto j = parsed.value("-j")) {
    try {
      std::size_t used = 0;
      const long n = std::stol(*j, &used);
      if (used != j->size() || n < 1 || n > 4096) throw std::invalid_argument(*j);
      jobs = static_cast<unsigned>(n);
    } catch (const std::exception&) {
      throw usage_error("sweep", "-j needs a number of workers from 1 to 4096, not '" + *j + "'");
    }
  }
  const bool quiet = parsed.has("--quiet");
  const std::string& file = parsed.positional[0];
  const Sweep sweep = load_sweep_file(file);

  SweepOptions options;
  options.out_dir = parsed.value("--out").value_or("out/" + std::filesystem::path(file).stem().string());
  options.jobs = jobs;
  const bool terminal = !quiet && ::isatty(STDERR_FILENO) == 1;
  if (terminal)
    options.progress = [](std::size_t done, std::size_t total) {
      std::cerr << "\rsweep: " << done << " / " << total << " cases | Ctrl-C stops, a re-run resumes" << std::flush;
    };

  SweepOutcome outcome;
  try {
    clear_interrupt();
    const SweepInterruptHandler handler;
    outcome = run_sweep(sweep, options);
  } catch (const OutputRefused& e) {
    throw CommandError(kExitInvalidInput, std::string(e.what()) + "; nothing was run");
  } catch (const OutputError& e) {
    throw CommandError(kExitInternal, "cannot write the sweep: " + std::string(e.what()));
  }
  if (terminal) std::cerr << "\n";
  if (outcome.interrupted) {
    std::cerr << "interrupted: " << outcome.run << " cases run now, " << outcome.skipped << " before, of "
              << sweep.cases.size() << "; run the same command again to resume (" << options.out_dir << "/sweep.csv)\n";
    return kExitInterrupted;
  }
  if (!quiet)
    out << sweep.cases.size() << " cases (" << outcome.run << " run, " << outcome.skipped << " already in the table, "
        << outcome.failed << " not ok) in " << options.out_dir << "/sweep.csv and sweep.json\n";
  return kExitOk;
}

}  // namespace rigidity::cli
