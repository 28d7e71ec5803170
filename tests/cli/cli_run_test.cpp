// rigidity validate and rigidity run, end to end: exit status, messages and the
// output directory (docs/cli.md, §5).
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "../output/mini_json.hpp"
#include "run_cli.hpp"

namespace rigidity::testing {
namespace {

const std::string kPaperScene = std::string(RIGIDITY_SOURCE_DIR) + "/configs/paper_wall_impact.yaml";

// Line 8 holds the misspelt key.
const std::string kTypoScene =
    "name: typo\n"
    "materials:\n"
    "  steel: {model: rigid}\n"
    "bodies:\n"
    "  - name: bar\n"
    "    material: steel\n"
    "    length: 1.0\n"
    "    velcity: 0.6\n"
    "boundaries:\n"
    "  left: {type: free}\n"
    "  right: {type: wall}\n"
    "time: {end: 1.0}\n";

// docs/materials.md: a hooke bar hitting a wall at v >= V collapses: no classical solution.
const std::string kHookeTooFastScene =
    "name: hooke_too_fast\n"
    "units: natural\n"
    "materials:\n"
    "  soft: {model: hooke, wave_speed: 0.5}\n"
    "bodies:\n"
    "  - {name: bar, material: soft, position: 0.0, length: 1.0, velocity: 0.6}\n"
    "boundaries:\n"
    "  left: {type: free}\n"
    "  right: {type: wall}\n"
    "time: {end: 1.0}\n";

// ---- validate ------------------------------------------------------------------------

TEST_F(CliTest, ValidateAcceptsThePaperScene) {
  const CliOutcome r = rigidity("validate " + shell_quote(kPaperScene));
  EXPECT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, kPaperScene + ": ok (1 body, 1 material)"));
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_F(CliTest, ValidateReportsABadSceneWithFileLineAndColumn) {
  const std::string scene = write_file("typo.yaml", kTypoScene);
  const CliOutcome r = rigidity("validate " + scene);
  EXPECT_EQ(r.exit_status, 2) << r.out;
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(typo\.yaml:8:[0-9]+: error: )"))) << r.err;
  EXPECT_TRUE(contains(r.err, "velocity"));  // the nearest valid key
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(CliTest, ValidateAppliesOverrides) {
  const std::string paper = shell_quote(kPaperScene);
  EXPECT_EQ(rigidity("validate " + paper + " --set bodies.0.velocity=0.8").exit_status, 0);
  const CliOutcome r = rigidity("validate " + paper + " --set bodies.0.velocity=1.5");  // |v| >= c
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "error:"));
}

TEST_F(CliTest, ValidateNeedsAReadableScene) {
  EXPECT_EQ(rigidity("validate").exit_status, 2);
  const CliOutcome r = rigidity("validate missing.yaml");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "missing.yaml"));
}

// ---- run -------------------------------------------------------------------------------

TEST_F(CliTest, RunWithoutASceneRunsThePaperWallImpact) {
  const CliOutcome r = rigidity("run");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const fs::path out = dir() / "out" / "paper_wall_impact";
  for (const char* file : {"summary.json", "probes.csv", "snapshots.csv", "fronts.csv", "resolved_scene.yaml"})
    EXPECT_TRUE(fs::exists(out / file)) << file;

  const mini_json::Value summary = mini_json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["scene"].string, "paper_wall_impact");
  EXPECT_EQ(summary["status"].string, "ok");
  EXPECT_EQ(summary["t_end"].number, 1.5);
  bool separated = false;
  for (const mini_json::Value& event : summary["events"].array) {
    if (event["kind"].string != "separation") continue;
    separated = true;
    EXPECT_NEAR(event["t"].number, 1.0, 1e-9);  // 2 l0 s / c with s = 0.5
  }
  EXPECT_TRUE(separated);
  ASSERT_EQ(summary["bodies"].array.size(), 1u);
  EXPECT_NEAR(summary["bodies"][0]["velocity_mean"].number, -0.6, 1e-9);  // rebound at -v

  // The human summary, with the comparison against the paper's formulas.
  EXPECT_TRUE(contains(r.out, "paper_wall_impact"));
  EXPECT_TRUE(contains(r.out, "separation"));
  EXPECT_TRUE(contains(r.out, "conservation"));
  EXPECT_TRUE(contains(r.out, "out/paper_wall_impact"));
  EXPECT_TRUE(contains(r.out, "against the paper"));
  EXPECT_TRUE(contains(r.out, "relative difference"));
  EXPECT_TRUE(contains(r.out, "rebound velocity"));
  EXPECT_FALSE(contains(r.out, "no separation"));
  // The solver's line: what it was asked, its bound and its cost; the bound's parts and
  // the thresholds are in summary.json.
  EXPECT_TRUE(contains(r.out,
                       "solver: characteristics (tolerance 1e-12, error bound 0); 2 fronts, 4 interactions, "
                       "solved in "))
      << r.out;
  EXPECT_FALSE(contains(r.out, "weak_wave_threshold"));
  EXPECT_EQ(summary["solver"]["error_bound"].number, 0.0);
  EXPECT_EQ(summary["solver"]["fronts_alive_max"].number, 1.0);
}

// Three bars after a short push of a piston; at tolerance 1e-2 to t = 9.36 the merges book
// an error bound of about 0.01011 (tests/solvers/bounded_tracking_test.cpp).
const std::string kThreeBarsScene =
    "name: three_bars\n"
    "materials:\n"
    "  light: {model: rigid, rest_density: 0.5}\n"
    "  heavy: {model: rigid, rest_density: 2.5}\n"
    "  soft: {model: hooke, wave_speed: 0.7, rest_density: 1.3}\n"
    "bodies:\n"
    "  - {name: a, material: light, position: 0.0, length: 0.8, velocity: 0.0}\n"
    "  - {name: b, material: heavy, position: 0.8, length: 0.6, velocity: 0.0}\n"
    "  - {name: c, material: soft, position: 1.4, length: 1.0, velocity: 0.0}\n"
    "boundaries:\n"
    "  left: {type: piston, table: [[0.0, 0.2], [0.5, 0.0]]}\n"
    "  right: {type: wall, bonded: true}\n"
    "solver: {method: characteristics, tolerance: 0.01}\n"
    "time: {end: 9.36}\n";

TEST_F(CliTest, RunShowsABoundJustAboveTheToleranceAboveIt) {
  const std::string scene = write_file("three_bars.yaml", kThreeBarsScene);
  // Resolved to the tolerance (`auto` would bring the bound under it).
  const CliOutcome r = rigidity("run " + scene + " --out run --set solver.resolution=tolerance");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const mini_json::Value summary = mini_json::parse(read_text(dir() / "run" / "summary.json"));
  const double bound = summary["solver"]["error_bound"].number;
  ASSERT_GT(bound, 0.01);
  ASSERT_LT(bound, 0.0105);  // two significant digits would print it as 0.01
  std::smatch line;
  ASSERT_TRUE(std::regex_search(
      r.out, line,
      std::regex(
          R"(solver: characteristics \(tolerance 0\.01, error bound ([0-9.e+-]+)\); [0-9]+ fronts, [0-9]+ interactions, )")))
      << r.out;
  EXPECT_GT(std::stod(line[1].str()), 0.01) << line[0];
  std::smatch warning;
  ASSERT_TRUE(std::regex_search(r.err, warning,
                                std::regex(R"(the error bound ([0-9.e+-]+) is above solver\.tolerance = 0\.01:)")))
      << r.err;
  EXPECT_GT(std::stod(warning[1].str()), 0.01) << warning[0];
}

TEST_F(CliTest, RunOfFiniteVolumeShowsItsCellsOrderAndSteps) {
  const CliOutcome r = rigidity("run --out fv --set solver.method=finite_volume --set solver.cells=40");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(std::regex_search(
      r.out, std::regex(R"(solver: finite_volume \(40 cells per body, order 2\); [0-9]+ steps, solved in )")))
      << r.out;
}

TEST_F(CliTest, RunWritesWhereToldAndAppliesOverrides) {
  const CliOutcome r = rigidity("run --out results/fast --set bodies.0.velocity=0.8");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "out"));
  const mini_json::Value summary = mini_json::parse(read_text(dir() / "results" / "fast" / "summary.json"));
  ASSERT_EQ(summary["bodies"].array.size(), 1u);
  EXPECT_NEAR(summary["bodies"][0]["velocity_mean"].number, -0.8, 1e-9);
  EXPECT_TRUE(contains(r.out, "results/fast"));
}

TEST_F(CliTest, RunOfASceneFileNamesItsOutputAfterTheScene) {
  const CliOutcome r = rigidity("run " + shell_quote(kPaperScene) + " --set name=again");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir() / "out" / "again" / "summary.json"));
  EXPECT_FALSE(contains(r.out, "against the paper"));  // only for the default scene
}

TEST_F(CliTest, RunReplacesAnEarlierRunAndKeepsTheUsersFiles) {
  // The default scene writes fronts.csv; the re-run without fronts must not leave the old
  // one behind, and must leave a notebook and a folder of the user's exactly as they were.
  ASSERT_EQ(rigidity("run --out run").exit_status, 0);
  ASSERT_TRUE(fs::exists(dir() / "run" / "fronts.csv"));
  const std::string old_summary = read_text(dir() / "run" / "summary.json");
  std::ofstream(dir() / "run" / "analysis.ipynb") << "{\"cells\": []}\n";
  fs::create_directories(dir() / "run" / "figures");
  std::ofstream(dir() / "run" / "figures" / "mine.svg") << "<svg/>\n";
  ASSERT_EQ(rigidity("run --out run --set outputs.fronts=false --set bodies.0.velocity=0.8").exit_status, 0);
  EXPECT_FALSE(fs::exists(dir() / "run" / "fronts.csv")) << "a file of the earlier run outlived it";
  EXPECT_NE(read_text(dir() / "run" / "summary.json"), old_summary);
  EXPECT_EQ(read_text(dir() / "run" / "analysis.ipynb"), "{\"cells\": []}\n");
  EXPECT_EQ(read_text(dir() / "run" / "figures" / "mine.svg"), "<svg/>\n");
  for (const auto& entry : fs::directory_iterator(dir()))  // no temporary or old sibling left
    EXPECT_EQ(entry.path().filename().string().find("run."), std::string::npos) << entry.path();
}

TEST_F(CliTest, RunOfAnInvalidSceneExitsTwoAndWritesNothing) {
  const std::string scene = write_file("typo.yaml", kTypoScene);
  const CliOutcome r = rigidity("run " + scene);
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(typo\.yaml:8:[0-9]+: error: )"))) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "out"));
}

TEST_F(CliTest, RunOfAnInadmissibleSceneExitsThree) {
  const std::string scene = write_file("hooke.yaml", kHookeTooFastScene);
  EXPECT_EQ(rigidity("validate " + scene).exit_status, 0);  // valid as a scene
  const CliOutcome r = rigidity("run " + scene);
  EXPECT_EQ(r.exit_status, 3) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
  // Crushed at its first impact: the outputs up to then, status inadmissible.
  const mini_json::Value summary = mini_json::parse(read_text(dir() / "out" / "hooke_too_fast" / "summary.json"));
  EXPECT_EQ(summary["status"].string, "inadmissible");
}

TEST_F(CliTest, PistonsThatMeetBeforeTheEndAreRefusedWithExitThree) {
  // Pistons closing at 0.25 c each on a bar of length 1 meet at t = 2 in the middle: the scene
  // has no classical solution to t = 3, which the run says before either solver starts.
  const std::string scene = write_file("closing.yaml", R"yaml(name: closing
materials:
  steel: {model: hooke, wave_speed: 0.5}
bodies:
  - {name: bar, material: steel, position: 0.0, length: 1.0}
boundaries:
  left: {type: piston, velocity: 0.25}
  right: {type: piston, velocity: -0.25}
time: {end: 3.0}
)yaml");
  const CliOutcome r = rigidity("run " + scene + " --out run");
  EXPECT_EQ(r.exit_status, 3) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("error: no classical solution", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("meet at t = 2 L/c, x = 0.5 L"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("run.h5"), std::string::npos) << r.err;  // not taken for an output's failure
  EXPECT_FALSE(fs::exists(dir() / "run"));
}

// ---- a run that meets no classical solution mid-way (exit 3) ------------------------------

const std::string kCrushedScene = std::string(RIGIDITY_SOURCE_DIR) + "/tests/scenes/crushed_hooke.yaml";
constexpr double kCrushTime = 2.4501400240519637;  // where the bar's reflected compression crushes it

/// Every CSV cell of `text` that reads as NaN or an infinity ("nan", "-inf", ...), as "row:column".
std::vector<std::string> non_finite_cells(const std::string& text) {
  std::vector<std::string> found;
  std::istringstream lines(text);
  std::string line;
  for (int row = 1; std::getline(lines, line); ++row) {
    std::istringstream cells(line);
    std::string cell;
    for (int column = 1; std::getline(cells, cell, ','); ++column) {
      std::string lower;
      for (const char c : cell) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (!lower.empty() && (lower[0] == '-' || lower[0] == '+')) lower.erase(0, 1);
      if (lower == "nan" || lower == "inf" || lower == "infinity")
        found.push_back(std::to_string(row) + ":" + std::to_string(column));
    }
  }
  return found;
}

/// The rows of a CSV file after its header, each split at its commas.
std::vector<std::vector<std::string>> csv_rows(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(read_text(path));
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) {
    std::vector<std::string> cells;
    std::istringstream split(line);
    for (std::string cell; std::getline(split, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST_F(CliTest, ACrushMidRunWritesItsOutputsUpToThatInstantWithItsErrorBound) {
  const CliOutcome r = rigidity("run " + shell_quote(kCrushedScene) + " --out run");
  ASSERT_EQ(r.exit_status, 3) << r.out << r.err;
  // The terminal says what happened, when, at what impact speed, and what the bound makes of it.
  EXPECT_TRUE(contains(r.err, "error: no classical solution at t = 2.4501400240519637 L/c, x = 1.8 L")) << r.err;
  EXPECT_TRUE(contains(r.err, "an impact at relative speed 0.547")) << r.err;
  EXPECT_TRUE(contains(r.err, "would crush the material 'hooke' to zero length")) << r.err;
  EXPECT_TRUE(contains(r.err,
                       "the run stopped there, at t = 2.450140024 L/c of t_end = 5 L/c (status inadmissible); "
                       "the outputs up to then are in run"))
      << r.err;
  EXPECT_TRUE(contains(r.err, "is small against the margin by which the material would be taken beyond its limit"))
      << r.err;
  EXPECT_TRUE(contains(r.out, "crushed_hooke (" + kCrushedScene + "): inadmissible at t = 2.450140024")) << r.out;

  // Complete: renamed into place, nothing left beside it.
  const fs::path out = dir() / "run";
  for (const auto& entry : fs::directory_iterator(dir()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  for (const char* file :
       {"summary.json", "events.csv", "probes.csv", "snapshots.csv", "fronts.csv", "resolved_scene.yaml"})
    EXPECT_TRUE(fs::exists(out / file)) << file;

  const mini_json::Value summary = mini_json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["status"].string, "inadmissible");
  EXPECT_DOUBLE_EQ(summary["t_reached"].number, kCrushTime);
  EXPECT_TRUE(contains(summary["stop_reason"].string, "would crush the material 'hooke' to zero length"));
  const mini_json::Value& at = summary["inadmissible"];
  EXPECT_DOUBLE_EQ(at["t"].number, kCrushTime);
  EXPECT_DOUBLE_EQ(at["x"].number, 1.8);  // at the wall
  EXPECT_EQ(at["material"].string, "hooke");
  EXPECT_FALSE(at["in_tension"].boolean);
  EXPECT_NEAR(at["psi_limit"].number, std::atanh(0.6), 1e-12);  // tanh Psi_max = V
  EXPECT_GT(at["psi_needed"].number, at["psi_limit"].number);
  EXPECT_NEAR(at["margin"].number, at["psi_needed"].number - at["psi_limit"].number, 1e-15);
  EXPECT_GT(at["relative_speed"].number, 0.5);
  EXPECT_LT(at["relative_speed"].number, 0.6);
  // The bound at that instant: finite, not negative, not zero (the gas's fans made errors), and
  // the solver's own.
  const double bound = at["error_bound"].number;
  EXPECT_TRUE(std::isfinite(bound));
  EXPECT_GT(bound, 0.0);
  EXPECT_LT(bound, 0.01);
  EXPECT_EQ(bound, summary["solver"]["error_bound"].number);
  EXPECT_FALSE(at["verdict_uncertain"].boolean);  // a margin of 0.54 in Psi, over 100 times the bound

  // The books at that instant close: what the stop left is a state of the run, not a half-done
  // interaction.
  const mini_json::Value& c = summary["conservation"];
  const double energy_residual =
      c["energy_final"].number + c["energy_dissipated"].number - c["energy_initial"].number - c["wall_work"].number;
  const double momentum_residual = c["momentum_final"].number - c["momentum_initial"].number - c["wall_impulse"].number;
  EXPECT_LT(std::abs(energy_residual), 1e-3 * c["energy_initial"].number);
  EXPECT_LT(std::abs(momentum_residual), 1e-3 * c["momentum_initial"].number);
  EXPECT_GE(c["energy_dissipated"].number, 0.0);

  // Outputs up to the stop and not beyond; no NaN anywhere.
  for (const char* file : {"events.csv", "probes.csv", "snapshots.csv", "fronts.csv"})
    EXPECT_TRUE(non_finite_cells(read_text(out / file)).empty()) << file;
  const auto probes = csv_rows(out / "probes.csv");
  ASSERT_FALSE(probes.empty());
  double last_probe = 0.0;
  for (const auto& row : probes) last_probe = std::max(last_probe, std::stod(row.at(0)));
  EXPECT_LE(last_probe, kCrushTime);
  EXPECT_GT(last_probe, kCrushTime - 0.05);  // every 0.05 up to the stop
  std::set<std::string> snapshot_times;
  for (const auto& row : csv_rows(out / "snapshots.csv")) snapshot_times.insert(row.at(0));
  EXPECT_EQ(snapshot_times, (std::set<std::string>{"0.5", "1"}));  // 4 is after the stop
  const auto fronts = csv_rows(out / "fronts.csv");
  ASSERT_FALSE(fronts.empty());
  for (const auto& row : fronts) EXPECT_LE(std::stod(row.at(2)), kCrushTime);
  const auto events = csv_rows(out / "events.csv");
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].at(1), "contact");
}

TEST_F(CliTest, ACrushTheBoundCouldMoveSaysAFinerToleranceMayMoveOrRemoveIt) {
  // Resolved to a tolerance of 0.05 the bound at the stop is about 0.05: not small against anything.
  const CliOutcome r = rigidity("run " + shell_quote(kCrushedScene) +
                                " --out run --set solver.tolerance=0.05 --set solver.resolution=tolerance");
  ASSERT_EQ(r.exit_status, 3) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "a finer solver.tolerance may move or remove this stop")) << r.err;
  const mini_json::Value summary = mini_json::parse(read_text(dir() / "run" / "summary.json"));
  EXPECT_EQ(summary["status"].string, "inadmissible");
  EXPECT_TRUE(summary["inadmissible"]["verdict_uncertain"].boolean);
  EXPECT_GE(summary["inadmissible"]["error_bound"].number, 0.01);
  EXPECT_TRUE(contains(summary["inadmissible"]["verdict"].string, "may move or remove this stop"));
}

TEST_F(CliTest, AnInadmissibleSiSceneSaysWhyInItsOwnUnits) {
  // A Hooke bar (V = 5000 m/s) hitting a wall at 6000 m/s: crushed at the impact, at t = 0.
  write_file("si.yaml",
             "name: si\nunits: si\nmaterials: {steel: {model: hooke, wave_speed: 5000, rest_density: 7850}}\n"
             "bodies: [{name: bar, material: steel, length: 1, velocity: 6000}]\n"
             "boundaries: {right: {type: wall}}\ntime: {end: 1.0e-3}\n");
  const CliOutcome r = rigidity("run si.yaml --out si");
  ASSERT_EQ(r.exit_status, 3) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "at t = 0 s, x = 0.9999999997997231 m")) << r.err;  // 1 m contracted by γ
  EXPECT_TRUE(contains(r.err, "relative speed 6000 m/s (2.0013845711889123e-05 c)")) << r.err;
  EXPECT_TRUE(contains(r.err, "tanh Psi_max = 5000 m/s")) << r.err;
}

TEST_F(CliTest, RunQuietPrintsNothingButWritesEverything) {
  const CliOutcome r = rigidity("run --quiet --out run");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  for (const char* file : {"summary.json", "events.csv", "probes.csv", "snapshots.csv", "fronts.csv"})
    EXPECT_TRUE(fs::exists(dir() / "run" / file)) << file;
  EXPECT_EQ(rigidity("run --quiet --set bodies.0.velocity=2").exit_status, 2);  // errors still say why
}

TEST_F(CliTest, RunWritesEveryEventToEventsCsv) {
  ASSERT_EQ(rigidity("run --out run").exit_status, 0);
  const std::string events = read_text(dir() / "run" / "events.csv");
  EXPECT_EQ(events.rfind("t,kind,x,bodies\n", 0), 0u) << events;
  EXPECT_TRUE(std::regex_search(events, std::regex(R"(\n1,separation,0.8,bar\n)"))) << events;
  const mini_json::Value summary = mini_json::parse(read_text(dir() / "run" / "summary.json"));
  EXPECT_EQ(summary["event_counts"]["separation"].number, 1.0);
}

// The fronts of a constant_sound_speed bar against a wall multiply after t = 2.
const std::string kCascadeScene =
    "name: cascade\n"
    "materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}\n"
    "bodies: [{name: bar, material: gas, position: 0, length: 1, velocity: 0.4}]\n"
    "boundaries: {left: {type: free}, right: {type: wall}}\n"
    "solver: {method: characteristics, tolerance: 1.0e-6}\n"
    "time: {end: 2.1}\n"
    "outputs:\n"
    "  probes: [{name: wall, body: bar, at: right, quantities: [p, v], every: 0.01}]\n";

TEST_F(CliTest, RunThatReachesABudgetStopsWithTheOutputsSoFarAndExitsOne) {
  const std::string scene = write_file("cascade.yaml", kCascadeScene);
  const CliOutcome r =
      rigidity("run " + scene + " --out run --set solver.max_interactions=200 --set solver.resolution=tolerance");
  EXPECT_EQ(r.exit_status, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "stopped: more than solver.max_interactions = 200 interactions by t = 2.0"));
  EXPECT_TRUE(contains(r.err, "solver.tolerance"));  // the advice for this scene
  EXPECT_TRUE(contains(r.out, "cascade (cascade.yaml): stopped at t = 2.0"));
  const mini_json::Value summary = mini_json::parse(read_text(dir() / "run" / "summary.json"));
  EXPECT_EQ(summary["status"].string, "stopped");
  EXPECT_GT(summary["t_reached"].number, 2.0);
  EXPECT_LT(summary["t_reached"].number, 2.1);
  EXPECT_TRUE(fs::exists(dir() / "run" / "probes.csv"));
  EXPECT_FALSE(contains(read_text(dir() / "run" / "probes.csv"), "nan"));
}

/// `rigidity ARGS...` started in the background in `dir`, stdout and stderr to files there.
pid_t start_rigidity(const fs::path& dir, const std::vector<std::string>& args) {
  std::vector<std::string> argv_text{RIGIDITY_EXECUTABLE};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string out = (dir / "stdout").string(), err = (dir / "stderr").string();
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  if (posix_spawn(&pid, RIGIDITY_EXECUTABLE, &actions, nullptr, argv.data(), environ) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

class CliSignalTest : public CliTest {
 protected:
  /// Starts a run of minutes into dir()/run, of a bar of `segments` Hooke segments, and
  /// returns once it is under way.
  pid_t start_long_run(int segments);
  /// Whether the run's temporary directory is there (it is renamed into place at the end).
  bool temporary_directory_exists();
  /// Starts a run of minutes, sends `signal` once it is under way (and again `again` later,
  /// if given), and checks that it stopped cleanly: exit `expected_exit`, status
  /// interrupted, outputs up to then renamed into place.
  void expect_signal_stops_run_cleanly(int signal, int expected_exit, const char* cause, int segments = 300,
                                       std::optional<std::chrono::milliseconds> again = std::nullopt);
};

pid_t CliSignalTest::start_long_run(int segments) {
  // Hooke segments, 3 long in all, ringing between bonded walls for 10^6 crossing times:
  // minutes of work.
  std::string scene =
      "name: ringing\n"
      "materials: {soft: {model: hooke, wave_speed: 0.5}}\n"
      "bodies:\n  - name: bar\n    material: soft\n    segments:\n";
  const std::string length = std::to_string(3.0 / segments);
  for (int k = 0; k < segments; ++k)
    scene += "      - {length: " + length + ", velocity: " + std::string(k % 2 == 0 ? "0.2" : "-0.2") + "}\n";
  scene +=
      "boundaries: {left: {type: wall, bonded: true}, right: {type: wall, bonded: true}}\n"
      "time: {end: 1.0e6}\n"
      "outputs:\n  probes: [{name: mid, body: bar, at: 1.5, quantities: [p], every: 1.0}]\n";
  write_file("ringing.yaml", scene);
  const pid_t pid =
      start_rigidity(dir(), {"run", (dir() / "ringing.yaml").string(), "--out", (dir() / "run").string()});
  if (pid <= 0) return pid;
  // Once the run is under way (its temporary directory exists), and a second more to let it
  // advance past t = 0 even under a sanitizer on a loaded machine.
  for (int i = 0; i < 200 && !temporary_directory_exists(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  return pid;
}

bool CliSignalTest::temporary_directory_exists() {
  for (const auto& entry : fs::directory_iterator(dir()))
    if (entry.path().filename().string().rfind("run.tmp-", 0) == 0) return true;
  return false;
}

void CliSignalTest::expect_signal_stops_run_cleanly(int signal, int expected_exit, const char* cause, int segments,
                                                    std::optional<std::chrono::milliseconds> again) {
  const pid_t pid = start_long_run(segments);
  ASSERT_GT(pid, 0);
  ASSERT_EQ(::kill(pid, signal), 0);
  if (again) {
    std::this_thread::sleep_for(*again);
    ::kill(pid, signal);  // may find the run already ended
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by the signal, not cleanly";
  EXPECT_EQ(WEXITSTATUS(status), expected_exit);

  const fs::path out = dir() / "run";
  const std::string err = read_text(dir() / "stderr");
  EXPECT_TRUE(contains(err, "stopping: writing the outputs up to now (Ctrl-C again to quit without them)")) << err;
  EXPECT_TRUE(contains(err, std::string("interrupted (") + cause + ") at t = ")) << err;
  const mini_json::Value summary = mini_json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["status"].string, "interrupted");
  EXPECT_GT(summary["t_reached"].number, 0.0);
  EXPECT_LT(summary["t_reached"].number, 1.0e6);
  const std::string probes = read_text(out / "probes.csv");
  EXPECT_GT(probes.size(), std::string("t,probe,quantity,value\n").size());
  EXPECT_FALSE(temporary_directory_exists());  // renamed into place
}

TEST_F(CliSignalTest, CtrlCStopsARunCleanlyWithTheOutputsSoFarAndExits130) {
  expect_signal_stops_run_cleanly(SIGINT, 130, "Ctrl-C");
}

TEST_F(CliSignalTest, SigtermStopsARunCleanlyWithTheOutputsSoFarAndExits143) {
  // What `timeout`, `kill` and a batch system's time limit send: a killed run used to leave
  // its temporary directory behind (gigabytes of fronts.csv for a long run).
  expect_signal_stops_run_cleanly(SIGTERM, 143, "SIGTERM");
}

// A bar of 20 000 segments takes about a quarter of a second from the signal to its end, so
// that a signal 20 ms after the first arrives while the outputs are being written.
TEST_F(CliSignalTest, ASigtermRepeatedAfter20MsIsTheSameRequest) {
  // GNU timeout sends SIGTERM to the program and then to its process group, 10-40 ms apart:
  // the second must not abandon the outputs the first is writing.
  expect_signal_stops_run_cleanly(SIGTERM, 143, "SIGTERM", 20000, std::chrono::milliseconds(20));
}

TEST_F(CliSignalTest, ACtrlCRepeatedAfter20MsIsTheSameRequest) {
  // A terminal's Ctrl-C reaches every process of its group; a launcher may pass it on.
  expect_signal_stops_run_cleanly(SIGINT, 130, "Ctrl-C", 20000, std::chrono::milliseconds(20));
}

TEST_F(CliTest, RunRefusesADirectoryThatIsNotARunAsInvalidInputBeforeSolving) {
  fs::create_directories(dir() / "precious");
  std::ofstream(dir() / "precious" / "notes.txt") << "keep me\n";
  const CliOutcome r = rigidity("run --out precious");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "precious"));
  EXPECT_TRUE(contains(r.err, "nothing was run"));
  EXPECT_FALSE(contains(r.out, "bodies at")) << "it solved before refusing";
  EXPECT_EQ(read_text(dir() / "precious" / "notes.txt"), "keep me\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir() / "precious"), fs::directory_iterator{}), 1);
}

// A tabulated law follows the scene's units (materials/tabulated.cpp): in an SI scene its
// pressures are in Pa. The table samples Hooke steel (rest density 7850 kg/m^3, V = 5100 m/s,
// p = rho00 c^2 b^2 (1/s^2 - 1)/((R + 1) R), b = V/c, R = sqrt(b^2 + (1 - b^2)/s^2)) every 0.002
// in s; the bar hits the wall at 1000 m/s: wall pressure rho00 V v = 4.0035e10 Pa, the bar
// leaves at -1000 m/s, momentum books closed, no negative dissipation.
TEST_F(CliTest, TabulatedLawInPascalRunsTheSteelWallImpact) {
  constexpr double rho = 7850.0, c = 299792458.0, b = 5100.0 / c;
  {
    std::ofstream table(dir() / "steel.csv");
    table << "s,p\n";
    table.precision(17);
    for (int i = 0; i <= 400; ++i) {
      const double s = i == 200 ? 1.0 : 0.6 + 0.002 * i;
      const double r = std::sqrt(b * b + (1.0 - b * b) / (s * s));
      table << s << "," << rho * c * c * b * b * (1.0 / (s * s) - 1.0) / ((r + 1.0) * r) << "\n";
    }
  }
  std::ofstream(dir() / "steel.yaml")
      << "name: steel_table\nunits: si\n"
         "materials:\n  steel: {model: tabulated, table: steel.csv, rest_density: 7850}\n"
         "bodies:\n  - {name: bar, material: steel, length: 1.0, velocity: 1000}\n"
         "boundaries: {left: {type: free}, right: {type: wall}}\n"
         "time: {end: 0.001}\n"
         "outputs:\n  probes:\n"
         "    - {name: wall, body: bar, at: right, quantities: [p], every: 1.0e-5}\n";
  const CliOutcome r = rigidity("run steel.yaml --out run --quiet");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const mini_json::Value summary = mini_json::parse(read_text(dir() / "run" / "summary.json"));
  EXPECT_EQ(summary["status"].string, "ok");
  ASSERT_EQ(summary["bodies"].array.size(), 1u);
  EXPECT_NEAR(summary["bodies"][0]["velocity_mean"].number, -1000.0, 1e-6);
  const mini_json::Value& books = summary["conservation"];
  EXPECT_GE(books["energy_dissipated"].number, 0.0);
  const double momentum = books["momentum_initial"].number;
  EXPECT_NEAR(books["momentum_final"].number - momentum, books["wall_impulse"].number, 1e-12 * momentum);
  double wall_pressure = 0.0;
  std::istringstream probes(read_text(dir() / "run" / "probes.csv"));
  for (std::string line; std::getline(probes, line);)
    if (line.find(",wall,p,") != std::string::npos)
      wall_pressure = std::max(wall_pressure, std::stod(line.substr(line.rfind(',') + 1)));
  EXPECT_NEAR(wall_pressure, rho * 5100.0 * 1000.0, 1e-6 * 4.0035e10);
}

}  // namespace
}  // namespace rigidity::testing
