#pragma once
/// Parameter sweeps (docs/sweeps.md): a base scene, parameters by their `--set` key paths
/// (grids crossed or zipped, or seeded random samples), and figures of merit collected
/// per case into one table, sweep.csv. Cases run in-process, on threads; an invalid or
/// inadmissible case is a row with its exit code and message, never a stop.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rigidity {

/// One figure of merit: `name: probe.wall.p.max`, `event.separation.first.t`,
/// `body.bar.velocity_mean`, or a scalar of summary.json by its path.
struct SweepCollect {
  std::string name;
  std::string path;
};

/// A sweep file, read and checked; `cases` holds every case's parameter values, as
/// the text `--set` would be given, in case order.
struct Sweep {
  std::string source;                   ///< the sweep file
  std::string scene_path;               ///< the base scene (relative paths resolved); empty: the embedded default
  std::vector<std::string> parameters;  ///< key paths, in file order
  std::vector<std::vector<std::string>> cases;  ///< cases[i][k]: parameter k of case i
  std::vector<SweepCollect> collect;
  bool keep_outputs = false;
};

/// Reads and validates a sweep file and lays out its cases.
/// \throws InputError "FILE:LINE:COL: error: key 'k': rule" on anything invalid
[[nodiscard]] Sweep load_sweep_file(const std::string& path);

/// One case as run.
struct SweepRow {
  std::size_t index = 0;
  std::string status;  ///< ok | stopped | interrupted | invalid | inadmissible | failed
  int exit_code = 0;
  std::string message;
  std::vector<std::optional<double>> figures;  ///< one per collect entry; empty: undefined
  double wall_time_s = 0.0;
};

/// Runs one case in this thread (no files unless `case_dir` is given).
[[nodiscard]] SweepRow run_sweep_case(const Sweep& sweep, std::size_t index, const std::string& case_dir = "");

struct SweepOptions {
  std::string out_dir;  ///< where sweep.csv and sweep.json go
  unsigned jobs = 1;    ///< worker threads
  /// Called (under a lock) after every case: cases done (this run and earlier), total.
  std::function<void(std::size_t, std::size_t)> progress;
};

struct SweepOutcome {
  std::size_t skipped = 0;  ///< cases already in sweep.csv
  std::size_t run = 0;      ///< cases run now
  std::size_t failed = 0;   ///< of those, cases whose exit code is not 0
  bool interrupted = false;
};

/// The header of sweep.csv: case, parameters, status, exit_code, message, collect names, wall_time_s.
[[nodiscard]] std::vector<std::string> sweep_header(const Sweep& sweep);
/// One row of sweep.csv (without the line end): numbers in shortest round-trip form,
/// an undefined figure as an empty cell, text quoted as CSV needs.
[[nodiscard]] std::string sweep_csv_row(const Sweep& sweep, const SweepRow& row);

/// Runs every case not already in out_dir/sweep.csv, appending rows as cases finish,
/// then rewrites sweep.csv in case order and writes sweep.json. A request to interrupt
/// (request_interrupt(), Ctrl-C) stops handing out cases; the rows written stay.
/// \throws OutputError if the directory cannot be written or its sweep.csv is another sweep's
SweepOutcome run_sweep(const Sweep& sweep, const SweepOptions& options);

/// What runs the cases for run_sweep: it runs the case indices `pending` (in any order,
/// anywhere: threads, MPI ranks) and hands each finished row to `done` (one call at a time),
/// and stops handing out cases once interrupt_requested().
using SweepRowSink = std::function<void(std::size_t index, int exit_code, const std::string& csv_row)>;
using SweepExecutor = std::function<void(const std::vector<std::size_t>& pending, const SweepRowSink& done)>;

/// Where a case's run directory goes (keep_outputs: DIR/cases/NNNN), or "" (no files).
[[nodiscard]] std::string sweep_case_dir(const Sweep& sweep, const std::string& out_dir, std::size_t index);
/// Loads the base scene once, so that the plugins it needs are in the registry before
/// cases run concurrently (errors are left to the cases).
void warm_up(const Sweep& sweep);

/// run_sweep with the cases run by `executor` instead of options.jobs threads.
SweepOutcome run_sweep(const Sweep& sweep, const SweepOptions& options, const SweepExecutor& executor);

}  // namespace rigidity
