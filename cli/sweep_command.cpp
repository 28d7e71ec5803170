// rigidity sweep SWEEP.yaml: every case of a parameter sweep, in-process on threads,
// into one table (docs/sweeps.md). Ctrl-C stops handing out cases; a re-run resumes.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>
#include <thread>

#include "mpi_sweep.hpp"
#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/sweep.hpp"

namespace rigidity::cli {

namespace {

/// "; by rank: 6, 6": the cases each MPI rank ran (empty without MPI).
std::string by_rank(const MpiSweep* mpi) {
  if (mpi == nullptr || mpi->size() < 2) return "";
  std::string text = "; by rank:";
  for (const std::size_t n : mpi->cases_by_rank()) text += (text.back() == ':' ? " " : ", ") + std::to_string(n);
  return text;
}

}  // namespace

int sweep_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--out", true}, {"-j", true}, {"--quiet"}};
  const Arguments parsed = parse_arguments("sweep", args, kOptions);
  if (parsed.help) {
    out << help("sweep");
    return kExitOk;
  }
  if (parsed.positional.size() != 1) throw usage_error("sweep", "sweep takes one sweep file");
  if (const auto dir = parsed.value("--out"); dir && dir->empty())
    throw usage_error("sweep", "--out needs a directory");
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
  const std::string out_dir = parsed.value("--out").value_or("out/" + std::filesystem::path(file).stem().string());
  const std::unique_ptr<MpiSweep> mpi = launched_by_mpi() ? open_mpi_sweep() : nullptr;
  if (mpi && mpi->rank() != 0) {
    // Rank 0 reports the errors and the interrupt; the other ranks only run cases.
    try {
      const Sweep sweep = load_sweep_file(file);
      const StopOnSignals stop_on_signals(true);
      static_cast<void>(mpi->work(sweep, out_dir));
    } catch (const std::exception&) {
      return kExitInvalidInput;
    }
    return interrupt_requested() ? StopOnSignals::exit_status() : kExitOk;
  }
  const Sweep sweep = load_sweep_file(file);

  SweepOptions options;
  options.out_dir = out_dir;
  options.jobs = jobs;
  const bool terminal = !quiet && ::isatty(STDERR_FILENO) == 1;
  if (terminal)
    options.progress = [last = std::chrono::steady_clock::time_point{}](std::size_t done, std::size_t total) mutable {
      const auto now = std::chrono::steady_clock::now();
      if (done < total && now - last < std::chrono::milliseconds(100)) return;  // a few lines a second
      last = now;
      std::cerr << "\rsweep: " << done << " / " << total << " cases | Ctrl-C stops, a re-run resumes" << std::flush;
    };

  SweepOutcome outcome;
  try {
    clear_interrupt();
    const StopOnSignals stop_on_signals(quiet);
    outcome = mpi && mpi->size() > 1 ? run_sweep(sweep, options, mpi->dispatcher(sweep, options.out_dir))
                                     : run_sweep(sweep, options);
  } catch (const OutputRefused& e) {
    throw CommandError(kExitInvalidInput, std::string(e.what()) + "; nothing was run");
  } catch (const OutputError& e) {
    throw CommandError(kExitInternal, "cannot write the sweep: " + std::string(e.what()));
  }
  if (terminal) std::cerr << "\n";
  if (outcome.interrupted) {
    std::cerr << "interrupted (" << StopOnSignals::cause() << "): " << outcome.run << " cases run now, "
              << outcome.skipped << " before, of " << sweep.cases.size() << "; run the same command again to resume ("
              << options.out_dir << "/sweep.csv)\n";
    return StopOnSignals::exit_status();
  }
  if (!quiet)
    out << sweep.cases.size() << " cases (" << outcome.run << " run, " << outcome.skipped << " already in the table, "
        << outcome.failed << " not ok" << by_rank(mpi.get()) << ") in " << options.out_dir
        << "/sweep.csv and sweep.json\n";
  return kExitOk;
}

}  // namespace rigidity::cli
