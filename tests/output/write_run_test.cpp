// The run output directory (docs/cli.md, "What a run writes"), written from hand-made Scene and RunResult values.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "mini_json.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"

namespace rigidity {
namespace {

namespace fs = std::filesystem;

constexpr double kC = kSpeedOfLightSI;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The paper's wall impact, as a solver would have handed it back (natural units).
Scene wall_impact_scene(UnitSystem units = UnitSystem::natural) {
  Scene scene;
  scene.name = "wall_impact";
  scene.source = "test.yaml";
  scene.units = units;
  BodyDecl bar;
  bar.name = "bar";
  bar.segments.push_back(Segment{1.0, std::atanh(0.6), Stretch::natural(), "steel"});
  scene.bodies.push_back(bar);
  scene.right.type = BoundaryType::wall;
  scene.right.position = 1.0;
  scene.t_end = 1.5;
  scene.outputs.probes.push_back(
      ProbeDecl{"wall", "bar", 1.0, {Quantity::p, Quantity::v, Quantity::s}, 0.5, {}, std::nullopt});
  scene.outputs.snapshots.push_back(SnapshotDecl{{0.5}, {Quantity::x, Quantity::p}, 3, {}, {}});
  scene.outputs.fronts = true;
  scene.resolver = [] { return std::string("name: wall_impact\n# every default filled in: \"verbatim\"\n"); };
  return scene;
}

RunResult wall_impact_result() {
  RunResult r;
  r.solver = "characteristics";
  r.solver_numbers = {{"tolerance", 1e-12}};
  r.warnings = {"a \"quoted\" warning\nover two lines"};
  r.events = {RunEvent{1.0, "separation", 1.0, {"bar"}}};
  r.bodies = {BodyResult{"bar", 0.4, 1.2, -0.6, -0.75, 1.25}};
  r.conservation = Conservation{1.25, 1.25, 0.0, 0.75, -0.75, -1.5, 0.0};
  r.stats = RunStats{3, 2, 0.001};
  r.body_names = {"bar"};
  for (const double t : {0.0, 0.5, 1.0}) {
    r.probes.push_back(ProbeSample{t, 0, Quantity::p, t < 1.0 ? 1.5 : 0.0});
    r.probes.push_back(ProbeSample{t, 0, Quantity::v, t < 1.0 ? 0.0 : -0.6});
    r.probes.push_back(ProbeSample{t, 0, Quantity::s, t < 1.0 ? 0.5 : 1.0});
  }
  for (const double X : {0.0, 0.5, 1.0}) {
    r.snapshots.push_back(SnapshotSample{0.5, 0, X, Quantity::x, 0.25 + 0.5 * X});
    r.snapshots.push_back(SnapshotSample{0.5, 0, X, Quantity::p, X < 0.5 ? 0.0 : 1.5});
  }
  r.fronts = {FrontSegment{0.0, 1.0, 0.5, 0.5, SegmentKind::shock, -1},
              FrontSegment{0.5, 0.5, 1.0, 1.0, SegmentKind::rarefaction, 1}};
  return r;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(read_file(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    rows.push_back(fields);
  }
  return rows;
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class WriteRun : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() / ("rigidity_output_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(base_);
    fs::create_directories(base_);
  }
  void TearDown() override { fs::remove_all(base_); }
  fs::path base_;
};

TEST_F(WriteRun, WritesEveryFileTheSceneAsksFor) {
  const fs::path dir = base_ / "run";
  write_run(wall_impact_scene(), wall_impact_result(), dir.string());
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"events.csv", "fronts.csv", "probes.csv", "resolved_scene.yaml",
                                                    "snapshots.csv", "summary.json"}));
  EXPECT_EQ(entries(base_), std::vector<std::string>{"run"});  // no temporary left beside it
  EXPECT_EQ(read_file(dir / "resolved_scene.yaml"), wall_impact_scene().resolved_yaml());
  EXPECT_EQ(read_file(dir / "summary.json"), summary_json(wall_impact_scene(), wall_impact_result()));
}

TEST_F(WriteRun, WritesOnlyWhatTheSceneAsksFor) {
  Scene scene = wall_impact_scene();
  scene.outputs = OutputsDecl{};
  const fs::path dir = base_ / "run";
  write_run(scene, wall_impact_result(), dir.string());
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"events.csv", "resolved_scene.yaml", "summary.json"}));
}

TEST_F(WriteRun, SummaryHasTheLayoutOfTheSpec) {
  const mini_json::Value doc = mini_json::parse(summary_json(wall_impact_scene(), wall_impact_result()));
  EXPECT_EQ(doc.keys(),
            (std::vector<std::string>{"scene", "status", "t_end", "t_reached", "solver", "warnings", "event_counts",
                                      "events", "bodies", "conservation", "stats", "units"}));
  EXPECT_EQ(doc["scene"].string, "wall_impact");
  EXPECT_EQ(doc["status"].string, "ok");
  EXPECT_EQ(doc["t_end"].number, 1.5);
  EXPECT_EQ(doc["t_reached"].number, 1.5);
  EXPECT_EQ(doc["event_counts"].keys(), std::vector<std::string>{"separation"});
  EXPECT_EQ(doc["event_counts"]["separation"].number, 1.0);
  EXPECT_EQ(doc["solver"]["method"].string, "characteristics");
  EXPECT_EQ(doc["solver"]["tolerance"].number, 1e-12);
  EXPECT_EQ(doc["warnings"][0].string, "a \"quoted\" warning\nover two lines");

  const mini_json::Value& event = doc["events"][0];
  EXPECT_EQ(event.keys(), (std::vector<std::string>{"t", "kind", "x", "bodies"}));
  EXPECT_EQ(event["kind"].string, "separation");
  EXPECT_EQ(event["bodies"][0].string, "bar");

  const mini_json::Value& bar = doc["bodies"][0];
  EXPECT_EQ(bar.keys(), (std::vector<std::string>{"name", "x_left", "x_right", "velocity_mean", "momentum", "energy",
                                                  "kinetic_energy", "internal_energy", "rest_energy"}));
  EXPECT_EQ(bar["velocity_mean"].number, -0.6);
  EXPECT_EQ(bar["energy"].number, 1.25);

  const mini_json::Value& conservation = doc["conservation"];
  for (const char* key :
       {"energy_initial", "energy_final", "energy_dissipated", "momentum_initial", "momentum_final", "wall_impulse"})
    EXPECT_TRUE(conservation.has(key)) << key;
  EXPECT_EQ(conservation["wall_impulse"].number, -1.5);

  EXPECT_EQ(doc["stats"].keys(),
            (std::vector<std::string>{"fronts", "interactions", "wall_time_s", "sampling_time_s"}));
  EXPECT_EQ(doc["stats"]["fronts"].number, 3.0);
  EXPECT_EQ(doc["units"]["system"].string, "natural");
  EXPECT_EQ(doc["units"]["velocity"].string, "c");
}

TEST_F(WriteRun, SummaryUsesTheSolverMethodOfTheSceneIfTheResultNamesNone) {
  RunResult result = wall_impact_result();
  result.solver.clear();
  Scene scene = wall_impact_scene();
  scene.solver.method = SolverMethod::finite_volume;
  EXPECT_EQ(mini_json::parse(summary_json(scene, result))["solver"]["method"].string, "finite_volume");
}

TEST_F(WriteRun, SummaryOfAnEmptyRunIsValid) {
  Scene scene;
  scene.name = "empty";
  const mini_json::Value doc = mini_json::parse(summary_json(scene, RunResult{}));
  EXPECT_TRUE(doc["events"].array.empty());
  EXPECT_TRUE(doc["bodies"].array.empty());
}

TEST_F(WriteRun, SummaryIsValidForPython) {
  if (std::system("python3 -c 'import json' > /dev/null 2>&1") != 0) GTEST_SKIP() << "python3 is not available";
  const fs::path file = base_ / "summary.json";
  std::ofstream(file) << summary_json(wall_impact_scene(), wall_impact_result());
  const std::string command = "python3 -c 'import json,sys; json.load(open(sys.argv[1]))' " + file.string();
  EXPECT_EQ(std::system(command.c_str()), 0);
}

TEST_F(WriteRun, CsvFilesHaveTheirHeadersAndOneRowPerSample) {
  const fs::path dir = base_ / "run";
  const RunResult result = wall_impact_result();
  write_run(wall_impact_scene(), result, dir.string());

  const auto probes = read_csv(dir / "probes.csv");
  ASSERT_EQ(probes.size(), result.probes.size() + 1);
  EXPECT_EQ(probes[0], (std::vector<std::string>{"t", "probe", "quantity", "value"}));
  EXPECT_EQ(probes[1], (std::vector<std::string>{"0", "wall", "p", "1.5"}));
  EXPECT_EQ(probes.back(), (std::vector<std::string>{"1", "wall", "s", "1"}));

  const auto snapshots = read_csv(dir / "snapshots.csv");
  ASSERT_EQ(snapshots.size(), result.snapshots.size() + 1);
  EXPECT_EQ(snapshots[0], (std::vector<std::string>{"t", "body", "X", "quantity", "value"}));
  EXPECT_EQ(snapshots[3], (std::vector<std::string>{"0.5", "bar", "0.5", "x", "0.5"}));

  const auto fronts = read_csv(dir / "fronts.csv");
  ASSERT_EQ(fronts.size(), result.fronts.size() + 1);
  EXPECT_EQ(fronts[0], (std::vector<std::string>{"t0", "x0", "t1", "x1", "kind", "family"}));
  EXPECT_EQ(fronts[1], (std::vector<std::string>{"0", "1", "0.5", "0.5", "shock", "-1"}));
  EXPECT_EQ(fronts[2], (std::vector<std::string>{"0.5", "0.5", "1", "1", "rarefaction", "1"}));
}

TEST_F(WriteRun, NegativeZeroIsWrittenAsZero) {
  RunResult result = wall_impact_result();
  result.snapshots[1].value = -0.0;
  result.bodies[0].momentum = -0.0;
  const fs::path dir = base_ / "run";
  write_run(wall_impact_scene(), result, dir.string());
  EXPECT_EQ(read_csv(dir / "snapshots.csv")[2], (std::vector<std::string>{"0.5", "bar", "0", "p", "0"}));
  EXPECT_NE(read_file(dir / "summary.json").find("\"momentum\": 0,"), std::string::npos);
}

TEST_F(WriteRun, CsvNamesWithCommasOrQuotesAreQuoted) {
  Scene scene = wall_impact_scene();
  scene.outputs.probes[0].name = "wall, \"right\"";
  const fs::path dir = base_ / "run";
  write_run(scene, wall_impact_result(), dir.string());
  const std::string text = read_file(dir / "probes.csv");
  EXPECT_NE(text.find("\n0,\"wall, \"\"right\"\"\",p,1.5\n"), std::string::npos) << text;
}

TEST_F(WriteRun, SiScenesAreConvertedDimensionByDimension) {
  const fs::path dir = base_ / "run";
  const Scene scene = wall_impact_scene(UnitSystem::si);
  write_run(scene, wall_impact_result(), dir.string());

  const mini_json::Value doc = mini_json::parse(read_file(dir / "summary.json"));
  EXPECT_EQ(doc["t_end"].number, 1.5 * (1.0 / kC));  // time: L/c → s
  EXPECT_EQ(doc["events"][0]["t"].number, 1.0 / kC);
  EXPECT_EQ(doc["events"][0]["x"].number, 1.0);  // length: m either way
  const mini_json::Value& bar = doc["bodies"][0];
  EXPECT_EQ(bar["x_left"].number, 0.4);
  EXPECT_EQ(bar["velocity_mean"].number, -0.6 * kC);  // velocity: c → m/s
  EXPECT_EQ(bar["momentum"].number, -0.75 * kC);      // momentum per area: ρ c L → kg/(m s)
  EXPECT_EQ(bar["energy"].number, 1.25 * (kC * kC));  // energy per area: ρ c² L → J/m²
  EXPECT_EQ(doc["conservation"]["wall_impulse"].number, -1.5 * kC);
  EXPECT_EQ(doc["conservation"]["energy_initial"].number, 1.25 * (kC * kC));
  EXPECT_EQ(doc["stats"]["wall_time_s"].number, 0.001);  // wall-clock seconds, not converted
  EXPECT_EQ(doc["units"]["system"].string, "si");
  EXPECT_EQ(doc["units"]["pressure"].string, "Pa");

  const auto probes = read_csv(dir / "probes.csv");
  ASSERT_EQ(probes.size(), 10u);
  EXPECT_EQ(std::stod(probes[4][0]), 0.5 / kC);  // t
  EXPECT_EQ(probes[4][2], "p");
  EXPECT_EQ(std::stod(probes[4][3]), 1.5 * (kC * kC));  // pressure: ρ c² → Pa
  EXPECT_EQ(probes[8][2], "v");
  EXPECT_EQ(std::stod(probes[8][3]), -0.6 * kC);
  EXPECT_EQ(probes[9][2], "s");
  EXPECT_EQ(std::stod(probes[9][3]), 1.0);  // stretch: dimensionless

  const auto snapshots = read_csv(dir / "snapshots.csv");
  EXPECT_EQ(std::stod(snapshots[1][0]), 0.5 / kC);
  EXPECT_EQ(snapshots[5][2], "1");  // X: length
  EXPECT_EQ(std::stod(snapshots[6][4]), 1.5 * (kC * kC));

  const auto fronts = read_csv(dir / "fronts.csv");
  EXPECT_EQ(std::stod(fronts[1][2]), 0.5 / kC);
  EXPECT_EQ(std::stod(fronts[1][3]), 0.5);
}

TEST_F(WriteRun, NonFiniteProbeValueIsRefusedAndNothingIsWritten) {
  RunResult result = wall_impact_result();
  result.probes[4].value = kNaN;  // t = 0.5, quantity v
  const fs::path dir = base_ / "run";
  try {
    write_run(wall_impact_scene(), result, dir.string());
    FAIL() << "a NaN was written";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("probes.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("'wall'"), std::string::npos) << what;
    EXPECT_NE(what.find("quantity v"), std::string::npos) << what;
    EXPECT_NE(what.find("t = 0.5"), std::string::npos) << what;
    EXPECT_NE(what.find("nan"), std::string::npos) << what;
  }
  EXPECT_TRUE(entries(base_).empty());
}

TEST_F(WriteRun, EveryNonFiniteNumberIsRefused) {
  using Mutation = void (*)(RunResult&);
  const std::pair<const char*, Mutation> cases[] = {
      {"summary.json", [](RunResult& r) { r.bodies[0].energy = kInf; }},
      {"summary.json", [](RunResult& r) { r.conservation.wall_impulse = kNaN; }},
      {"summary.json", [](RunResult& r) { r.events[0].t = -kInf; }},
      {"summary.json", [](RunResult& r) { r.solver_numbers[0].second = kNaN; }},
      {"summary.json", [](RunResult& r) { r.stats.wall_time_s = kNaN; }},
      {"probes.csv", [](RunResult& r) { r.probes[0].t = kNaN; }},
      {"snapshots.csv", [](RunResult& r) { r.snapshots[2].X = kInf; }},
      {"snapshots.csv", [](RunResult& r) { r.snapshots[5].value = kNaN; }},
      {"fronts.csv", [](RunResult& r) { r.fronts[1].x1 = kNaN; }},
  };
  for (const auto& [file, mutate] : cases) {
    RunResult result = wall_impact_result();
    mutate(result);
    try {
      write_run(wall_impact_scene(), result, (base_ / "run").string());
      ADD_FAILURE() << "a non-finite value in " << file << " was written";
    } catch (const NumericalError& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
    EXPECT_TRUE(entries(base_).empty()) << file;
  }
}

TEST_F(WriteRun, ConversionOverflowToInfinityIsRefused) {
  RunResult result = wall_impact_result();
  result.probes[0].value = 1e300;  // finite in natural units, inf in Pa
  EXPECT_THROW(write_run(wall_impact_scene(UnitSystem::si), result, (base_ / "run").string()), NumericalError);
  EXPECT_NO_THROW(write_run(wall_impact_scene(UnitSystem::natural), result, (base_ / "run").string()));
}

TEST_F(WriteRun, AnExistingRunIsReplacedAndOnlyItsOwnFilesGo) {
  const fs::path dir = base_ / "run";
  fs::create_directories(dir / "nested");
  std::ofstream(dir / "summary.json") << "{\"old\": true}\n";
  std::ofstream(dir / "probes.csv") << "old\n";
  std::ofstream(dir / "xt.png") << "old plot\n";
  std::ofstream(dir / "nested" / "mine.txt") << "the user's\n";
  std::ofstream(dir / "notes.md") << "the user's\n";

  Scene scene = wall_impact_scene();
  scene.outputs = OutputsDecl{};  // the new run has no probes: the old probes.csv must go too
  write_run(scene, wall_impact_result(), dir.string());
  EXPECT_EQ(entries(dir),
            (std::vector<std::string>{"events.csv", "nested", "notes.md", "resolved_scene.yaml", "summary.json"}));
  EXPECT_EQ(read_file(dir / "notes.md"), "the user's\n");
  EXPECT_EQ(read_file(dir / "nested" / "mine.txt"), "the user's\n");
  EXPECT_EQ(entries(base_), std::vector<std::string>{"run"});
  EXPECT_EQ(mini_json::parse(read_file(dir / "summary.json"))["scene"].string, "wall_impact");
}

TEST_F(WriteRun, AFailedRunLeavesTheExistingOneUntouched) {
  const fs::path dir = base_ / "run";
  write_run(wall_impact_scene(), wall_impact_result(), dir.string());
  const std::string before = read_file(dir / "probes.csv");

  RunResult bad = wall_impact_result();
  bad.fronts.back().t1 = kNaN;  // found in the last file written
  bad.probes[0].value = 42.0;
  EXPECT_THROW(write_run(wall_impact_scene(), bad, dir.string()), NumericalError);
  EXPECT_EQ(read_file(dir / "probes.csv"), before);
  EXPECT_EQ(entries(base_), std::vector<std::string>{"run"});
}

TEST_F(WriteRun, RefusesToReplaceSomethingThatIsNotARun) {
  const fs::path precious = base_ / "home";
  fs::create_directories(precious);
  std::ofstream(precious / "thesis.tex") << "years of work\n";
  EXPECT_THROW(write_run(wall_impact_scene(), wall_impact_result(), precious.string()), std::runtime_error);
  EXPECT_EQ(entries(precious), std::vector<std::string>{"thesis.tex"});

  const fs::path file = base_ / "file";
  std::ofstream(file) << "not a directory\n";
  EXPECT_THROW(write_run(wall_impact_scene(), wall_impact_result(), file.string()), std::runtime_error);
  EXPECT_EQ(read_file(file), "not a directory\n");

  EXPECT_THROW(write_run(wall_impact_scene(), wall_impact_result(), "."), std::runtime_error);
  EXPECT_THROW(write_run(wall_impact_scene(), wall_impact_result(), ""), std::runtime_error);
  EXPECT_EQ(entries(base_), (std::vector<std::string>{"file", "home"}));
}

TEST_F(WriteRun, AnEmptyDirectoryIsReplacedAndParentsAreCreated) {
  fs::create_directories(base_ / "empty");
  write_run(wall_impact_scene(), wall_impact_result(), (base_ / "empty").string());
  EXPECT_TRUE(fs::exists(base_ / "empty" / "summary.json"));

  write_run(wall_impact_scene(), wall_impact_result(), (base_ / "out" / "deep" / "run" / "").string());
  EXPECT_TRUE(fs::exists(base_ / "out" / "deep" / "run" / "summary.json"));
  EXPECT_EQ(entries(base_ / "out" / "deep"), std::vector<std::string>{"run"});
}

TEST_F(WriteRun, SampleIndicesOutOfRangeAreAnError) {
  RunResult result = wall_impact_result();
  result.probes[0].probe = 1;  // the scene has one probe
  EXPECT_THROW(write_run(wall_impact_scene(), result, (base_ / "run").string()), std::runtime_error);
  result = wall_impact_result();
  result.snapshots[0].body = -1;
  EXPECT_THROW(write_run(wall_impact_scene(), result, (base_ / "run").string()), std::runtime_error);
  EXPECT_TRUE(entries(base_).empty());
}

TEST_F(WriteRun, LargeOutputsSurviveManyBufferFlushes) {
  Scene scene = wall_impact_scene();
  RunResult result = wall_impact_result();
  result.probes.clear();
  constexpr int kRows = 300000;  // about 10 MB: many flushes of the write buffer
  for (int i = 0; i < kRows; ++i) result.probes.push_back(ProbeSample{i * 1e-5, 0, Quantity::p, 1.0 / (1.0 + i)});
  const fs::path dir = base_ / "run";
  write_run(scene, result, dir.string());

  std::ifstream in(dir / "probes.csv");
  std::string line, last;
  long lines = 0;
  while (std::getline(in, line)) {
    ++lines;
    last = line;
  }
  EXPECT_EQ(lines, kRows + 1);
  std::istringstream fields(last);
  std::string t, probe, quantity, value;
  std::getline(fields, t, ',');
  std::getline(fields, probe, ',');
  std::getline(fields, quantity, ',');
  std::getline(fields, value, ',');
  EXPECT_EQ(std::stod(t), (kRows - 1) * 1e-5);
  EXPECT_EQ(std::stod(value), 1.0 / kRows);
}

}  // namespace
}  // namespace rigidity
