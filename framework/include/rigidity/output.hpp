#pragma once
/// Run outputs (SPEC §5): summary.json, probes.csv, snapshots.csv, fronts.csv,
/// resolved_scene.yaml, converted to the scene's units. The directory is written
/// as a whole or not at all: files go to a temporary sibling that is renamed
/// into place at the end. No NaN or inf is ever written: a non-finite value is a
/// NumericalError.

#include <string>

#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"

namespace rigidity {

/// Writes every output of `result` for `scene` into `dir` (replaced if it exists).
/// \throws NumericalError on a non-finite value, std::runtime_error on I/O failure
void write_run(const Scene& scene, const RunResult& result, const std::string& dir);

/// summary.json alone, as text.
[[nodiscard]] std::string summary_json(const Scene& scene, const RunResult& result);

}  // namespace rigidity
