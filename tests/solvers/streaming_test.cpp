// Outputs streamed as the solvers produce them (docs/cli.md, "What a run writes"): the same files as the
// in-memory path, every event in events.csv, and runs that stop early (a budget, an
// interrupt) or fail.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../output/mini_json.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& line, char separator = ',') {
  std::vector<std::string> fields;
  std::istringstream cells(line);
  for (std::string cell; std::getline(cells, cell, separator);) fields.push_back(cell);
  return fields;
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// summary.json without the one line that differs between two runs of a scene.
std::string without_wall_time(const std::string& summary) {
  return std::regex_replace(summary, std::regex(R"("(wall|sampling)_time_s": [^\n]*)"), "\"$1_time_s\": -");
}

/// Every number of every data row of a CSV file is finite (no "nan", "inf").
::testing::AssertionResult all_finite(const fs::path& csv) {
  const std::vector<std::string> lines = lines_of(read_file(csv));
  for (std::size_t i = 1; i < lines.size(); ++i)
    for (const std::string& field : split(lines[i])) {
      if (field.find("nan") != std::string::npos || field.find("inf") != std::string::npos)
        return ::testing::AssertionFailure() << csv << " line " << i + 1 << ": " << lines[i];
    }
  return ::testing::AssertionSuccess();
}

/// The largest value of column `column` (a time) over the data rows of a CSV file.
double last_time(const fs::path& csv, std::size_t column = 0) {
  double last = -1.0;
  const std::vector<std::string> lines = lines_of(read_file(csv));
  for (std::size_t i = 1; i < lines.size(); ++i) last = std::max(last, std::stod(split(lines[i]).at(column)));
  return last;
}

class Streaming : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() / ("rigidity_streaming_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(base_);
    fs::create_directories(base_);
  }
  void TearDown() override {
    clear_interrupt();
    fs::remove_all(base_);
  }

  /// Solves `scene` streaming into base/NAME, as `rigidity run` does.
  RunResult run_streaming(const Scene& scene, const std::string& name) const {
    StreamingRecorder recorder(scene, (base_ / name).string());
    const RunResult result = solve(scene, recorder);
    recorder.commit(result);
    return result;
  }

  fs::path base_;
};

/// A rigid bar bouncing between two walls: a contact and a separation per bounce.
const char* const kBouncingBar = R"(
name: bouncing
materials: {steel: {model: rigid}}
bodies: [{name: bar, material: steel, position: 0.0, length: 1.0, velocity: 0.6}]
boundaries: {left: {type: wall, position: -0.1}, right: {type: wall, position: 1.0}}
time: {end: 150.0}
outputs:
  probes: [{name: left, body: bar, at: left, quantities: [x, v, p], every: 0.5}]
)";

/// The issue's scene: the fronts of a constant_sound_speed bar against a wall
/// multiply without bound after t = 2 at a fine tolerance.
const char* const kCascade = R"(
name: cascade
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies: [{name: bar, material: gas, position: 0, length: 1, velocity: 0.4}]
boundaries: {left: {type: free}, right: {type: wall}}
solver: {method: characteristics, tolerance: 1.0e-6, max_interactions: 20000}
time: {end: 2.1}
outputs:
  probes: [{name: wall, body: bar, at: right, quantities: [p, v, s], every: 0.01}]
  snapshots: [{times: [1.0, 2.0, 2.09], quantities: [x, v, p], samples: 21}]
  fronts: true
)";

// ---- the same files either way ------------------------------------------------------

TEST_F(Streaming, WritesTheSameFilesAsTheInMemoryPath) {
  std::vector<std::string> scenes;
  for (const char* name : {"paper_wall_impact", "bar_on_bar", "flyer_plates", "piston_compression", "shock_tube"})
    scenes.push_back(std::string(RIGIDITY_SOURCE_DIR) + "/configs/" + name + ".yaml");
  for (const std::string& file : scenes) {
    for (const char* method : {"characteristics", "finite_volume"}) {
      SCOPED_TRACE(file + " " + method);
      const Scene scene = load_scene_file(file, {std::string("solver.method=") + method, "solver.cells=100"});
      const RunResult in_memory = solve(scene);
      write_run(scene, in_memory, (base_ / "memory").string());
      const RunResult streamed = run_streaming(scene, "streamed");

      EXPECT_TRUE(streamed.fronts.empty() && streamed.probes.empty() && streamed.snapshots.empty());
      EXPECT_EQ(streamed.event_counts, in_memory.event_counts);
      ASSERT_EQ(entries(base_ / "memory"), entries(base_ / "streamed"));
      for (const std::string& name : entries(base_ / "memory")) {
        const std::string a = read_file(base_ / "memory" / name), b = read_file(base_ / "streamed" / name);
        if (name == "summary.json") {
          EXPECT_EQ(without_wall_time(a), without_wall_time(b));
        } else {
          EXPECT_EQ(a, b) << name;
        }
      }
      fs::remove_all(base_ / "memory");
      fs::remove_all(base_ / "streamed");
    }
  }
}

// ---- every event in events.csv, their counts in summary.json ---------------------------

TEST_F(Streaming, EventsCsvHasEveryEventAndTheSummaryTheCountsAndTheFirstOnes) {
  for (const char* method : {"characteristics", "finite_volume"}) {
    SCOPED_TRACE(method);
    const Scene scene =
        load_scene_string(kBouncingBar, "<test>", {std::string("solver.method=") + method, "solver.cells=50"});
    const RunResult result = run_streaming(scene, method);
    const fs::path dir = base_ / method;

    const std::vector<std::string> rows = lines_of(read_file(dir / "events.csv"));
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows[0], "t,kind,x,bodies");
    const long events = static_cast<long>(rows.size()) - 1;
    EXPECT_GT(events, static_cast<long>(RunRecorder::kFirstEvents));  // more than the summary lists

    const mini_json::Value summary = mini_json::parse(read_file(dir / "summary.json"));
    long counted = 0;
    for (const auto& entry : summary["event_counts"].object) {
      const std::string& kind = entry.first;  // not a structured binding: clang 14 cannot capture one
      const long count = static_cast<long>(entry.second.number);
      counted += count;
      const long rows_of_kind =
          std::count_if(rows.begin() + 1, rows.end(), [&](const std::string& row) { return split(row)[1] == kind; });
      EXPECT_EQ(rows_of_kind, count) << kind;
    }
    EXPECT_EQ(counted, events);
    EXPECT_TRUE(summary["event_counts"].has("contact"));
    EXPECT_TRUE(summary["event_counts"].has("separation"));

    // The summary lists the first events, the same as the first rows of events.csv, in time order.
    const auto& listed = summary["events"].array;
    ASSERT_EQ(listed.size(), RunRecorder::kFirstEvents);
    ASSERT_EQ(result.events.size(), RunRecorder::kFirstEvents);
    double previous = -1.0;
    for (std::size_t i = 0; i < listed.size(); ++i) {
      const std::vector<std::string> row = split(rows[i + 1]);
      EXPECT_EQ(std::stod(row[0]), listed[i]["t"].number) << i;
      EXPECT_EQ(row[1], listed[i]["kind"].string) << i;
      EXPECT_EQ(row[3], listed[i]["bodies"][0].string) << i;
      EXPECT_LE(previous, listed[i]["t"].number);
      previous = listed[i]["t"].number;
    }
    for (std::size_t i = 2; i < rows.size(); ++i)
      EXPECT_LE(std::stod(split(rows[i - 1])[0]), std::stod(split(rows[i])[0])) << "events.csv out of order";

    // In memory, every event is kept.
    const RunResult in_memory = solve(scene);
    EXPECT_EQ(static_cast<long>(in_memory.events.size()), events);
  }
}

TEST_F(Streaming, EventsCsvJoinsTheBodiesOfAnEvent) {
  const Scene scene = load_scene_file(std::string(RIGIDITY_SOURCE_DIR) + "/configs/bar_on_bar.yaml");
  run_streaming(scene, "run");
  const std::vector<std::string> rows = lines_of(read_file(base_ / "run" / "events.csv"));
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(split(rows[1])[1], "contact");
  EXPECT_EQ(split(rows[1])[3], "flyer;target");
}

// `resolution: auto` keeps each of its runs in memory and hands the one it chose to the
// recorder: the files are those a run at that resolution streams as it goes, fronts, probes,
// snapshots and events alike.
TEST_F(Streaming, AnAimedRunWritesWhatARunAtItsResolutionWrites) {
  const Scene aimed_scene = load_scene_string(
      kCascade, "<test>", {"solver.tolerance=1e-4", "solver.max_interactions=100000000", "time.end=6"});
  ASSERT_TRUE(aimed_scene.solver.auto_resolution);
  const RunResult aimed = run_streaming(aimed_scene, "aimed");
  ASSERT_EQ(aimed.status, "ok");
  ASSERT_GE(aimed.solver_number("resolution_runs"), 2.0) << "one run: nothing was kept in memory";
  Scene fixed_scene = aimed_scene;
  fixed_scene.solver.auto_resolution = false;
  fixed_scene.solver.resolution = aimed.solver_number("resolution");
  const RunResult fixed = run_streaming(fixed_scene, "fixed");
  EXPECT_EQ(aimed.solver_number("error_bound"), fixed.solver_number("error_bound"));
  EXPECT_EQ(aimed.event_counts, fixed.event_counts);
  for (const char* name : {"fronts.csv", "probes.csv", "snapshots.csv", "events.csv"}) {
    const std::string a = read_file(base_ / "aimed" / name), b = read_file(base_ / "fixed" / name);
    EXPECT_GT(lines_of(a).size(), 1u) << name;
    EXPECT_EQ(a, b) << name;
  }
}

// ---- a budget stops the run cleanly ---------------------------------------------------------

TEST_F(Streaming, ABudgetStopsTheRunWithTheOutputsUpToTheTimeReached) {
  for (const char* budget : {"solver.max_interactions=200", "solver.max_fronts=200"}) {
    SCOPED_TRACE(budget);
    // Resolved to the tolerance: `auto` would take a pilot that finishes within the budget.
    const Scene scene = load_scene_string(kCascade, "<test>", {budget, "solver.resolution=tolerance"});
    const RunResult result = run_streaming(scene, "run");
    const fs::path dir = base_ / "run";

    EXPECT_EQ(result.status, "stopped");
    // The cascade starts after t = 2 (0.02 s and 3 interactions to get there).
    EXPECT_GT(result.t_reached, 2.0);
    EXPECT_LT(result.t_reached, scene.t_end);
    const std::string which = std::string(budget).substr(0, std::string(budget).find('='));
    EXPECT_NE(result.stop_reason.find("more than " + which), std::string::npos) << result.stop_reason;
    // Advice for this scene: its fans are split at the tolerance, so a coarser one helps.
    EXPECT_NE(result.stop_reason.find("solver.tolerance"), std::string::npos) << result.stop_reason;

    const mini_json::Value summary = mini_json::parse(read_file(dir / "summary.json"));
    EXPECT_EQ(summary["status"].string, "stopped");
    EXPECT_EQ(summary["t_reached"].number, result.t_reached);
    EXPECT_EQ(summary["t_end"].number, 2.1);
    EXPECT_EQ(summary["stop_reason"].string, result.stop_reason);

    // Outputs up to t_reached, none beyond, and no NaN anywhere.
    for (const char* csv : {"probes.csv", "snapshots.csv", "fronts.csv", "events.csv"})
      EXPECT_TRUE(all_finite(dir / csv)) << csv;
    EXPECT_LE(last_time(dir / "probes.csv"), result.t_reached);
    EXPECT_GT(last_time(dir / "probes.csv"), result.t_reached - 0.01 - 1e-12);  // every sample before it
    EXPECT_EQ(last_time(dir / "snapshots.csv"), 2.0);                           // not the one at 2.09
    EXPECT_LE(last_time(dir / "fronts.csv", 2), result.t_reached);              // t1

    // The books are closed at t_reached: momentum still balances, to what fan steps of ΔΨ
    // (at most fan_step_max) miss the jump conditions by, O(ΔΨ²).
    const Conservation& c = result.conservation;
    const double step = result.solver_number("fan_step_max");
    EXPECT_NEAR(c.momentum_final - c.momentum_initial, c.wall_impulse, 4.0 * step * step);
    EXPECT_GE(c.energy_dissipated, 0.0);
    EXPECT_NEAR(c.energy_final + c.energy_dissipated, c.energy_initial, 1e-6);
    ASSERT_EQ(result.bodies.size(), 1u);
    EXPECT_TRUE(std::isfinite(result.bodies[0].x_left) && std::isfinite(result.bodies[0].x_right));
    EXPECT_LT(result.bodies[0].x_left, result.bodies[0].x_right);
    fs::remove_all(dir);
  }
}

TEST_F(Streaming, TheStopAdviceFitsTheScene) {
  // Linearly degenerate bodies only: no fan is split, so a coarser tolerance cannot help
  // and the advice does not offer it.
  const Scene scene = load_scene_string(R"(
name: ringing
materials: {soft: {model: hooke, wave_speed: 0.5}}
bodies:
  - name: bar
    material: soft
    segments:
      - {length: 0.5, velocity: 0.3}
      - {length: 0.5, velocity: -0.3}
boundaries: {left: {type: wall, bonded: true}, right: {type: wall, bonded: true}}
solver: {max_interactions: 50}
time: {end: 100.0}
)",
                                        "<test>");
  const RunResult result = solve(scene);
  EXPECT_EQ(result.status, "stopped");
  EXPECT_EQ(result.stop_reason.find("solver.tolerance"), std::string::npos) << result.stop_reason;
  EXPECT_NE(result.stop_reason.find("solver.max_interactions"), std::string::npos) << result.stop_reason;
  EXPECT_NE(result.stop_reason.find("time.end"), std::string::npos) << result.stop_reason;
}

// ---- an interrupt stops the run cleanly -------------------------------------------------------

/// Streams into a run directory and presses Ctrl-C once a probe sample at `t_interrupt`
/// has gone by: request_interrupt() is all a SIGINT handler does.
class InterruptingRecorder final : public RunRecorder {
 public:
  InterruptingRecorder(RunRecorder& files, double t_interrupt) : files_(files), t_interrupt_(t_interrupt) {}

 private:
  void record_front(const FrontSegment& segment) override { files_.front(segment); }
  void record_probe(const ProbeSample& sample) override {
    if (sample.t >= t_interrupt_) request_interrupt();
    files_.probe(sample);
  }
  void record_snapshot(const SnapshotSample& sample) override { files_.snapshot(sample); }
  void record_event(const RunEvent& event) override { files_.event(event); }

  RunRecorder& files_;
  double t_interrupt_;
};

TEST_F(Streaming, AnInterruptStopsTheRunWithStatusInterrupted) {
  for (const char* method : {"characteristics", "finite_volume"}) {
    SCOPED_TRACE(method);
    // Resolved to the tolerance: the run streams into the recorder as it goes (`auto` keeps
    // its runs in memory and hands on the one it takes).
    const Scene scene =
        load_scene_string(kBouncingBar, "<test>",
                          {std::string("solver.method=") + method, "solver.cells=50", "solver.resolution=tolerance"});
    const fs::path dir = base_ / method;
    StreamingRecorder files(scene, dir.string());
    InterruptingRecorder recorder(files, 40.0);
    const RunResult result = solve(scene, recorder);
    files.commit(result);
    clear_interrupt();

    EXPECT_EQ(result.status, "interrupted");
    EXPECT_GE(result.t_reached, 40.0);
    EXPECT_LT(result.t_reached, 42.0);  // the next interaction (or step) after the sample at 40
    const mini_json::Value summary = mini_json::parse(read_file(dir / "summary.json"));
    EXPECT_EQ(summary["status"].string, "interrupted");
    EXPECT_EQ(summary["t_reached"].number, result.t_reached);
    EXPECT_LE(last_time(dir / "probes.csv"), result.t_reached);
    EXPECT_GT(last_time(dir / "probes.csv"), result.t_reached - 0.5 - 1e-9);
    EXPECT_LE(last_time(dir / "events.csv"), result.t_reached);
    EXPECT_TRUE(all_finite(dir / "probes.csv"));
    const Conservation& c = result.conservation;
    EXPECT_NEAR(c.momentum_final - c.momentum_initial, c.wall_impulse, 1e-6);
  }
}

TEST_F(Streaming, AnInterruptBeforeTheRunStopsItAtTheStart) {
  const Scene scene = load_scene_string(kBouncingBar, "<test>");
  request_interrupt();
  const RunResult result = solve(scene);
  EXPECT_EQ(result.status, "interrupted");
  EXPECT_EQ(result.t_reached, 0.0);
  ASSERT_EQ(result.bodies.size(), 1u);
  EXPECT_NEAR(result.bodies[0].velocity_mean, 0.6, 1e-12);
}

// ---- a failed run leaves nothing ------------------------------------------------------------

TEST_F(Streaming, AFailedRunLeavesNoDirectory) {
  // Two hooke bars (V = 0.5) at ±0.6 c meet at t = 0.5, after samples and fronts
  // have been streamed: no classical solution.
  const Scene scene = load_scene_string(R"(
name: crushed
materials: {soft: {model: hooke, wave_speed: 0.5}}
bodies:
  - {name: a, material: soft, position: 0.0, length: 1.0, velocity: 0.6}
  - {name: b, material: soft, position: 1.4, length: 1.0, velocity: -0.6}
time: {end: 2.0}
outputs:
  probes: [{name: p, body: a, at: right, quantities: [p, v], every: 0.001}]
  fronts: true
)",
                                        "<test>");
  const fs::path dir = base_ / "out" / "deep" / "run";
  {
    StreamingRecorder recorder(scene, dir.string());
    EXPECT_EQ(entries(base_), std::vector<std::string>{"out"});  // the temporary directory, beside the target
    EXPECT_THROW((void)solve(scene, recorder), InadmissibleError);
  }
  EXPECT_TRUE(entries(base_).empty());  // neither the run, nor its temporary, nor the parents made for it
}

TEST_F(Streaming, AFailedRunLeavesAnEarlierRunUntouched) {
  const Scene good = load_scene_file(std::string(RIGIDITY_SOURCE_DIR) + "/configs/paper_wall_impact.yaml");
  run_streaming(good, "run");
  const std::string before = read_file(base_ / "run" / "probes.csv");
  const Scene bad = load_scene_file(std::string(RIGIDITY_SOURCE_DIR) + "/configs/paper_wall_impact.yaml",
                                    {"materials.rigid_steel.model=hooke", "materials.rigid_steel.wave_speed=0.5"});
  {
    StreamingRecorder recorder(bad, (base_ / "run").string());
    EXPECT_THROW((void)solve(bad, recorder), InadmissibleError);
  }
  EXPECT_EQ(read_file(base_ / "run" / "probes.csv"), before);
  EXPECT_EQ(entries(base_), std::vector<std::string>{"run"});
}

}  // namespace
}  // namespace rigidity
