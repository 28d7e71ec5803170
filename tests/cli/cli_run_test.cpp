// rigidity validate and rigidity run, end to end: exit status, messages and the
// output directory (SPEC §4, §5).
#include <cmath>
#include <regex>
#include <string>

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

// SPEC §2: a hooke bar hitting a wall at v >= V collapses: no classical solution.
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

TEST_F(CliTest, RunReplacesAnEarlierRunWhole) {
  ASSERT_EQ(rigidity("run --out run").exit_status, 0);
  std::ofstream(dir() / "run" / "stale.csv") << "old\n";
  ASSERT_EQ(rigidity("run --out run").exit_status, 0);
  EXPECT_FALSE(fs::exists(dir() / "run" / "stale.csv"));
  EXPECT_TRUE(fs::exists(dir() / "run" / "summary.json"));
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
  EXPECT_FALSE(fs::exists(dir() / "out"));
}

TEST_F(CliTest, RunRefusesToReplaceADirectoryThatIsNotARun) {
  fs::create_directories(dir() / "precious");
  std::ofstream(dir() / "precious" / "notes.txt") << "keep me\n";
  const CliOutcome r = rigidity("run --out precious");
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_TRUE(contains(r.err, "precious"));
  EXPECT_EQ(read_text(dir() / "precious" / "notes.txt"), "keep me\n");
}

}  // namespace
}  // namespace rigidity::testing
