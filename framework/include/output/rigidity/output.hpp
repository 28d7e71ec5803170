#pragma once
/// Run outputs (docs/cli.md, "What a run writes"): summary.json, probes.csv, snapshots.csv, fronts.csv,
/// events.csv, resolved_scene.yaml, converted to the scene's units. The directory is
/// written as a whole or not at all: files go to a temporary sibling that is renamed
/// into place at the end. No NaN or inf is ever written: a non-finite value is a
/// NumericalError.

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "rigidity/run_recorder.hpp"
#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"

namespace rigidity {

/// The output directory cannot be written (refused, full disk, permissions).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The output directory given cannot take a run (a file, or a directory of other things
/// that holds no earlier run): invalid input, found before anything is solved.
class OutputRefused : public OutputError {
 public:
  using OutputError::OutputError;
};

/// The files a run (and `rigidity plot` of it) writes into its directory. Re-running into
/// the directory replaces these; every other file there (a notebook, a figure of one's own)
/// stays.
[[nodiscard]] bool is_run_file(std::string_view name);

/// Streams a run's outputs to disk as the solver produces them: CSV rows go through
/// a buffer into a temporary sibling of `dir`, so memory does not grow with the run.
/// commit() adds summary.json and resolved_scene.yaml and renames the sibling to
/// `dir` (replacing an earlier run whole); destroyed without commit (a failed run),
/// it removes the sibling and any parent directory it created: nothing is left.
///
/// Files: events.csv always (`t,kind,x,bodies`, bodies joined by ';'), probes.csv,
/// snapshots.csv and fronts.csv when the scene's outputs ask for them.
class StreamingRecorder final : public RunRecorder {
 public:
  /// \throws OutputError if `dir` holds something other than an earlier run (or an
  ///         empty directory), or the temporary directory cannot be made
  StreamingRecorder(const Scene& scene, const std::string& dir);
  ~StreamingRecorder() override;

  /// Finishes the CSV files, writes summary.json from `result` (events and counts
  /// as RunRecorder::complete left them) and resolved_scene.yaml, and renames the
  /// directory into place. \throws NumericalError on a non-finite value in the
  /// summary (nothing is written then), OutputError on an I/O failure
  void commit(const RunResult& result);

  /// The directory the outputs go to once committed.
  [[nodiscard]] const std::filesystem::path& target() const;

 private:
  void record_front(const FrontSegment& segment) override;
  void record_probe(const ProbeSample& sample) override;
  void record_snapshot(const SnapshotSample& sample) override;
  void record_event(const RunEvent& event) override;

  struct Files;
  std::unique_ptr<Files> files_;
};

/// Writes every output of `result` for `scene` into `dir` (replaced if it exists):
/// the in-memory path, through a StreamingRecorder, so both give the same files.
/// \throws NumericalError on a non-finite value, OutputError on I/O failure
void write_run(const Scene& scene, const RunResult& result, const std::string& dir);

/// summary.json alone, as text: status and t_reached, the first
/// RunRecorder::kFirstEvents of result.events and the counts of events by kind
/// (result.event_counts, or the counts of result.events if that is empty).
[[nodiscard]] std::string summary_json(const Scene& scene, const RunResult& result);

}  // namespace rigidity
