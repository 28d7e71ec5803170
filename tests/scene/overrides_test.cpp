// `--set key.path=value` overrides: applied to the YAML tree before validation; errors
// in them point into "<--set>" (line n = the n-th override, column within it).

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "rigidity/scene_loader.hpp"
#include "scene_test_util.hpp"

namespace rigidity::test {
namespace {

const std::string kScene(default_scene_text());

TEST(Overrides, ReplaceValues) {
  const Scene scene =
      load_ok(kScene, {"bodies.0.velocity=0.8", "outputs.fronts=false", "solver.method=finite_volume", "time.end=3"});
  EXPECT_TRUE(close_relative(scene.bodies[0].segments[0].rapidity, std::atanh(0.8)));
  EXPECT_FALSE(scene.outputs.fronts);
  EXPECT_EQ(scene.solver.method, SolverMethod::finite_volume);
  EXPECT_EQ(scene.t_end, 3.0);
  EXPECT_NE(scene.resolved_yaml().find("velocity: 0.8"), std::string::npos);
}

TEST(Overrides, AddKeysAndMaps) {
  const Scene scene = load_ok(
      kScene, {"solver.cells=800", "boundaries.left={type: wall, bonded: true}", "outputs.snapshots.0.bodies=[bar]"});
  EXPECT_EQ(scene.solver.cells, 800);
  EXPECT_EQ(scene.left.type, BoundaryType::wall);
  EXPECT_TRUE(scene.left.bonded);
  EXPECT_EQ(scene.outputs.snapshots[0].bodies, (std::vector<std::string>{"bar"}));
  // A map the file does not have is created.
  const Scene minimal =
      load_ok("name: n\nmaterials: {m: {model: rigid}}\nbodies: [{name: b, material: m, length: 1}]\ntime: {end: 1}\n",
              {"solver.flux=exact", "units=natural"});
  EXPECT_EQ(minimal.solver.flux, FluxType::exact);
}

TEST(Overrides, LaterOnesWin) {
  const Scene scene = load_ok(kScene, {"bodies.0.velocity=0.8", "bodies.0.velocity=0.1"});
  EXPECT_TRUE(close_relative(scene.bodies[0].segments[0].rapidity, std::atanh(0.1)));
}

TEST(Overrides, ReplaceAWholeList) {
  const Scene scene = load_ok(kScene, {"outputs.probes=[]", "bodies.0={name: rod, material: rigid_steel, length: 2}"});
  EXPECT_TRUE(scene.outputs.probes.empty());
  EXPECT_EQ(scene.bodies[0].name, "rod");
  EXPECT_EQ(scene.bodies[0].natural_length(), 2.0);
}

struct BadOverride {
  std::vector<std::string> overrides;
  int line;
  int column;
  std::string key;
  std::string message;
};

class OverrideError : public testing::TestWithParam<BadOverride> {};

TEST_P(OverrideError, PointsIntoTheOverride) {
  const BadOverride& bad = GetParam();
  try {
    (void)load_scene_string(kScene, "scene.yaml", bad.overrides);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "<--set>") << e.what();
    EXPECT_EQ(e.where().line, bad.line) << e.what();
    EXPECT_EQ(e.where().column, bad.column) << e.what();
    EXPECT_EQ(e.key(), bad.key) << e.what();
    EXPECT_NE(e.message().find(bad.message), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Overrides, OverrideError,
    testing::Values(
        // malformed overrides
        BadOverride{{"no_equals_sign"}, 1, 1, "", "expected key.path=value"},
        BadOverride{{"=0.5"}, 1, 1, "", "missing key path"},
        BadOverride{{"bodies..velocity=1"}, 1, 8, "bodies..velocity", "empty component"},
        BadOverride{{"bodies.0.velocity="}, 1, 19, "bodies.0.velocity", "missing value"},
        BadOverride{{"name=[unclosed"}, 1, 6, "name", "malformed value"},
        // bad paths
        BadOverride{{"bodies.5.velocity=0.1"}, 1, 8, "bodies.5", "expected an index from 0 to 0"},
        BadOverride{{"bodies.first.velocity=0.1"}, 1, 8, "bodies.first", "expected an index"},
        BadOverride{{"outputs.probes=[]", "outputs.probes.0.name=x"}, 2, 16, "outputs.probes.0", "it is empty"},
        // a map the override creates where the schema wants a list
        BadOverride{{"plugins.0=lib.so"}, 1, 1, "plugins", "must be a list, got a map"},
        BadOverride{{"name.x=1"}, 1, 6, "name.x", "'name' is the value 'paper_wall_impact', not a map or list"},
        // overrides that break the scene's rules: reported at the override
        BadOverride{{"bodies.0.velcity=0.8"}, 1, 10, "bodies.0.velcity", "did you mean 'velocity'?"},
        BadOverride{{"time.end=2", "bodies.0.velocity=1.5"}, 2, 19, "bodies.0.velocity", "|v| < c"},
        BadOverride{{"boundaries.left={type: free, bonded: true}"}, 1, 30, "boundaries.left.bonded", "only applies"},
        BadOverride{{"solver.cells=many"}, 1, 14, "solver.cells", "got 'many'"}),
    [](const testing::TestParamInfo<BadOverride>& param) {
      // case3_bodies_0_velocity_ : the override that breaks the rule, readable in a report.
      std::string name = "case" + std::to_string(param.index) + "_";
      for (const char c : param.param.overrides.back().substr(0, 32))
        name += std::isalnum(static_cast<unsigned char>(c)) != 0 ? c : '_';
      return name;
    });

}  // namespace
}  // namespace rigidity::test
