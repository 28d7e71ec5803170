// rigidity sweep SWEEP.yaml: every case of a parameter sweep, in-process on threads,
// into one table (SPEC §6). Ctrl-C stops handing out cases; a re-run resumes.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <ostream>
#include <thread>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/sweep.hpp"

#ifdef RIGIDITY_HAVE_MPI
#include <mpi.h>
#endif

namespace rigidity::cli {

namespace {

#ifdef RIGIDITY_HAVE_MPI
/// Started by mpirun or srun (which set these), not by hand.
bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}

/// MPI for the life of the command.
class MpiSession {
 public:
  MpiSession() {
    MPI_Init(nullptr, nullptr);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

constexpr int kTagRow = 1;   // worker -> rank 0: a finished row ("EXIT_CODE ROW"), or "" for the first request
constexpr int kTagCase = 2;  // rank 0 -> worker: a case index to run
constexpr int kTagStop = 3;  // rank 0 -> worker: no more cases

/// Rank 0: hands out case indices one at a time to whichever rank asks (dynamic load
/// balancing) and takes the rows back; it runs no case itself.
SweepExecutor mpi_dispatcher(int ranks) {
  return [ranks](const std::vector<std::size_t>& pending, const SweepRowSink& done) {
    std::size_t next = 0;
    int running = ranks - 1;
    std::vector<bool> busy(static_cast<std::size_t>(ranks), false);
    std::vector<std::size_t> assigned(static_cast<std::size_t>(ranks), 0);
    while (running > 0) {
      MPI_Status status;
      MPI_Probe(MPI_ANY_SOURCE, kTagRow, MPI_COMM_WORLD, &status);
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      std::string message(static_cast<std::size_t>(length), '\0');
      MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagRow, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const auto source = static_cast<std::size_t>(status.MPI_SOURCE);
      if (!message.empty() && busy[source]) {
        const std::size_t space = message.find(' ');
        done(assigned[source], std::stoi(message.substr(0, space)), message.substr(space + 1));
      }
      busy[source] = false;
      if (next < pending.size() && !interrupt_requested()) {
        const unsigned long index = pending[next++];
        assigned[source] = index;
        busy[source] = true;
        MPI_Send(&index, 1, MPI_UNSIGNED_LONG, status.MPI_SOURCE, kTagCase, MPI_COMM_WORLD);
      } else {
        MPI_Send(nullptr, 0, MPI_UNSIGNED_LONG, status.MPI_SOURCE, kTagStop, MPI_COMM_WORLD);
        --running;
      }
    }
  };
}

/// Ranks 1..N-1: ask for a case, run it, send its row back, until told to stop.
void mpi_worker(const Sweep& sweep, const std::string& out_dir) {
  std::string message;  // empty: the first request
  for (;;) {
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kTagRow, MPI_COMM_WORLD);
    MPI_Status status;
    unsigned long index = 0;
    MPI_Recv(&index, 1, MPI_UNSIGNED_LONG, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kTagStop) return;
    const SweepRow row = run_sweep_case(sweep, index, sweep_case_dir(sweep, out_dir, index));
    // A case cut short by Ctrl-C goes back as no row: it runs again next time.
    message =
        row.status == "interrupted" ? std::string() : std::to_string(row.exit_code) + " " + sweep_csv_row(sweep, row);
  }
}
#endif

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
#ifdef RIGIDITY_HAVE_MPI
  std::optional<MpiSession> mpi;
  if (launched_by_mpi()) mpi.emplace();
  const bool worker_rank = mpi && mpi->rank() != 0;
  if (worker_rank) {
    // Rank 0 reports the errors; the other ranks only run cases.
    try {
      const Sweep sweep = load_sweep_file(file);
      const StopOnSignals stop_on_signals(true);  // rank 0 says what happens
      mpi_worker(sweep, parsed.value("--out").value_or("out/" + std::filesystem::path(file).stem().string()));
    } catch (const std::exception&) {
      return kExitInvalidInput;
    }
    return kExitOk;
  }
#endif
  const Sweep sweep = load_sweep_file(file);

  SweepOptions options;
  options.out_dir = parsed.value("--out").value_or("out/" + std::filesystem::path(file).stem().string());
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
#ifdef RIGIDITY_HAVE_MPI
    if (mpi && mpi->size() > 1) {
      outcome = run_sweep(sweep, options, mpi_dispatcher(mpi->size()));
    } else {
      outcome = run_sweep(sweep, options);
    }
#else
    outcome = run_sweep(sweep, options);
#endif
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
        << outcome.failed << " not ok) in " << options.out_dir << "/sweep.csv and sweep.json\n";
  return kExitOk;
}

}  // namespace rigidity::cli
