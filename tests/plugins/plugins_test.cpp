// Material plugins (plugins.hpp): a library built outside the framework registers its materials
// exactly as a built-in does, is refused with a clear message when it cannot be used, and is
// loaded from a scene's `plugins` or from RIGIDITY_PLUGIN_PATH. The plugins are the example
// (examples/plugin/murnaghan.cpp) and the variants of modules/test_plugin.cpp, each built in its
// own directory under RIGIDITY_TEST_PLUGIN_DIR; this binary links the shared library, as the
// `rigidity` executable does, so that the plugins and it share one registry.

#include "rigidity/plugins.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../cli/run_cli.hpp"
#include "../solvers/error_bound.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/run_result.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity::testing {
namespace {

/// The module of a test plugin variant ("good", "acausal", ...) or of the example ("murnaghan").
fs::path plugin(const std::string& variant) {
  const std::string file = variant == "murnaghan" ? "libmurnaghan.so" : "libtest_plugin_" + variant + ".so";
  return fs::path(RIGIDITY_TEST_PLUGIN_DIR) / variant / file;
}

/// The message load_plugin refuses `variant` with ("" if it loads).
std::string refusal(const std::string& variant) {
  try {
    static_cast<void>(load_plugin(plugin(variant)));
  } catch (const PluginError& e) {
    return e.what();
  }
  return "";
}

bool registered(const std::string& name) { return MaterialRegistry::instance().find(name) != nullptr; }

const std::string kMurnaghanScene = R"(name: murnaghan_wall_impact
plugins: [PLUGIN]
materials:
  solid: {model: murnaghan, sound_speed: 0.1}
bodies:
  - {name: bar, material: solid, position: 0.0, length: 1.0, velocity: 0.05}
boundaries:
  left: {type: free}
  right: {type: wall}
solver: {method: characteristics, tolerance: 1.0e-3}
time: {end: 30.0}
)";

std::string with_plugin(std::string scene, const std::string& path) {
  scene.replace(scene.find("PLUGIN"), 6, path);
  return scene;
}

TEST(Plugins, APluginRegistersItsMaterialsAsABuiltinDoes) {
  MaterialRegistry::instance().seal();  // as the executable does before loading anything
  const LoadedPlugin& loaded = load_plugin(plugin("good"));
  EXPECT_EQ(loaded.path, fs::canonical(plugin("good")).string());
  EXPECT_EQ(loaded.materials, std::vector<std::string>{"test_plugin_material"});
  EXPECT_TRUE(loaded.notes.empty());
  const MaterialInfo& info = MaterialRegistry::instance().at("test_plugin_material");
  EXPECT_TRUE(info.file.ends_with("test_plugin.cpp")) << info.file;
  ParameterValues values;
  values.set("rest_density", 2.0);
  const auto material = build_material(info, values);
  EXPECT_EQ(material->model(), "test_plugin_material");
  EXPECT_NEAR(material->sound_speed(Stretch::natural()), 0.5, 1e-12);
  // Once per process: loading it again (by another path to the same file) changes nothing.
  const fs::path again = plugin("good").parent_path() / ".." / "good" / plugin("good").filename();
  EXPECT_EQ(&load_plugin(again), &loaded);
  EXPECT_NO_THROW(MaterialRegistry::instance().check());
}

TEST(Plugins, APluginForAnotherAbiIsRefusedAndLeavesNothingBehind) {
  const std::string message = refusal("wrong_abi");
  EXPECT_TRUE(contains(message, "libtest_plugin_wrong_abi.so"));
  EXPECT_TRUE(contains(message, "built against rigidity 9.9.9 (plugin ABI " + std::to_string(kPluginAbiVersion + 1)));
  EXPECT_TRUE(contains(message, "rebuild it against this version"));
  EXPECT_FALSE(registered("test_plugin_wrong_abi"));
  EXPECT_NO_THROW(MaterialRegistry::instance().check());
}

TEST(Plugins, AnAcausalMaterialIsRefusedWhenItsPluginLoads) {
  const std::string message = refusal("acausal");
  EXPECT_TRUE(contains(message, "libtest_plugin_acausal.so"));
  EXPECT_TRUE(contains(message, "material 'test_plugin_acausal' is acausal at stretch"));
  EXPECT_TRUE(contains(message, "its admissible range"));
  EXPECT_FALSE(registered("test_plugin_acausal"));
}

TEST(Plugins, ALibraryWithoutRigidityPluginIsNotAPlugin) {
  const std::string message = refusal("not_a_plugin");
  EXPECT_TRUE(contains(message, "is not a rigidity plugin"));
  EXPECT_TRUE(contains(message, "RIGIDITY_PLUGIN()"));
  EXPECT_FALSE(registered("test_plugin_not_a_plugin"));
}

TEST(Plugins, AMaterialNameTakenIsRefusedNamingBothPlaces) {
  const std::string original = MaterialRegistry::instance().at("rigid").file;
  const std::string message = refusal("duplicate");
  EXPECT_TRUE(contains(message, "material 'rigid' is registered twice"));
  EXPECT_TRUE(contains(message, original));
  EXPECT_TRUE(contains(message, "test_plugin.cpp"));
  EXPECT_EQ(MaterialRegistry::instance().at("rigid").file, original);
  EXPECT_NO_THROW(MaterialRegistry::instance().check());
}

TEST(Plugins, AMaterialWithRequiredParametersIsLoadedWithANote) {
  const LoadedPlugin& loaded = load_plugin(plugin("required"));
  ASSERT_EQ(loaded.notes.size(), 1u);
  EXPECT_TRUE(contains(loaded.notes[0], "'test_plugin_required' was not checked at load: it requires 'scale'"));
  EXPECT_TRUE(registered("test_plugin_required"));
}

TEST(Plugins, AMissingFileIsRefused) {
  EXPECT_TRUE(contains(refusal("no_such_variant"), "does not exist"));
  const fs::path directory = plugin("good").parent_path();
  try {
    static_cast<void>(load_plugin(directory));
    FAIL() << "a directory was loaded";
  } catch (const PluginError& e) {
    EXPECT_TRUE(contains(e.what(), "is not a file"));
  }
}

TEST(Plugins, ASceneUsesTheMaterialsOfThePluginsItLists) {
  // The example plugin, by absolute path: loaded before the materials are checked.
  const Scene scene = load_scene_string(with_plugin(kMurnaghanScene, plugin("murnaghan").string()), "<test>");
  EXPECT_EQ(scene.materials.at("solid").material->model(), "murnaghan");
  // The generic path (a material given only by p(s)) through the exact solver.
  const RunResult result = solve(scene);
  EXPECT_EQ(result.status, "ok");
  ASSERT_EQ(result.events.size(), 1u);
  EXPECT_EQ(result.events[0].kind, "separation");  // the bar leaves the wall
  const Conservation& c = result.conservation;
  // The books close within what the run's certified error bound allows (fan steps).
  const double books = certified_books_tolerance(scene, result, c.energy_initial);
  EXPECT_LT(books, 1e-2 * c.energy_initial) << "a bound too loose to check anything";
  EXPECT_NEAR(c.momentum_final - c.momentum_initial, c.wall_impulse, books);
  EXPECT_NEAR(c.energy_final - c.energy_initial, c.wall_work - c.energy_dissipated, books);
  EXPECT_GT(c.energy_dissipated, 0.0) << "a genuine shock";
}

TEST(Plugins, AMaterialIsCheckedWithTheParametersTheSceneGives) {
  // test_plugin_required is the rigid law with its stiffness scaled by `scale`/4: c_s = c
  // at scale 4, and it cannot be checked when its plugin loads (the factor is required).
  // A scene that makes it acausal is refused at the material, before anything runs.
  const auto scene_with = [](const std::string& scale) {
    return "name: x\nplugins: [" + plugin("required").string() +
           "]\nmaterials:\n  m: {model: test_plugin_required, scale: " + scale +
           "}\nbodies: [{name: b, material: m, position: 0, length: 1}]\ntime: {end: 1}\n";
  };
  try {
    (void)load_scene_string(scene_with("16"), "<test>");
    FAIL() << "an acausal material was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "<test>:4:")) << e.what();
    EXPECT_TRUE(contains(e.what(), "'m'")) << e.what();
    EXPECT_TRUE(contains(e.what(), "acausal")) << e.what();
  }
  EXPECT_NO_THROW((void)load_scene_string(scene_with("2"), "<test>"));
}

TEST(Plugins, RelativePathsStartAtTheSceneFile) {
  const fs::path directory = fs::path(::testing::TempDir()) / "rigidity_plugins_relative";
  fs::create_directories(directory / "lib");
  fs::copy_file(plugin("murnaghan"), directory / "lib" / "libmurnaghan.so", fs::copy_options::overwrite_existing);
  std::ofstream(directory / "scene.yaml") << with_plugin(kMurnaghanScene, "lib/libmurnaghan.so");
  // The copy is another file with the same materials: loaded if it comes first (each test runs
  // in a process of its own under ctest), refused as a second copy if the original came first.
  try {
    const Scene scene = load_scene_file((directory / "scene.yaml").string());
    EXPECT_EQ(scene.materials.at("solid").material->model(), "murnaghan");
    EXPECT_EQ(loaded_plugins().back().path, fs::canonical(directory / "lib" / "libmurnaghan.so").string());
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), (directory / "lib" / "libmurnaghan.so").string()));
    EXPECT_TRUE(contains(e.what(), "registered twice")) << "found, and refused only as a second copy";
  }
  fs::remove_all(directory);
}

TEST(Plugins, ARefusedPluginIsAnErrorAtItsSceneKey) {
  const std::string scene =
      "name: x\nplugins:\n  - " + plugin("murnaghan").string() + "\n  - " + plugin("acausal").string() +
      "\nmaterials: {m: {model: rigid}}\nbodies: [{name: b, material: m, position: 0, length: 1}]\n"
      "time: {end: 1}\n";
  try {
    static_cast<void>(load_scene_string(scene, "scene.yaml"));
    FAIL() << "an acausal plugin was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "plugins.1");
    EXPECT_EQ(e.where().file, "scene.yaml");
    EXPECT_EQ(e.where().line, 4);
    EXPECT_TRUE(contains(e.what(), "scene.yaml:4:5: error: key 'plugins.1': plugin '"));
    EXPECT_TRUE(contains(e.what(), "acausal"));
  }
  try {
    static_cast<void>(load_scene_string("name: x\nplugins: [nowhere/libx.so]\n", "scene.yaml"));
    FAIL() << "a missing plugin was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "plugins.0");
    EXPECT_TRUE(contains(e.what(), "scene.yaml:2:11: error: key 'plugins.0': plugin 'nowhere/libx.so' does not exist"));
  }
}

// ---- the command line ------------------------------------------------------------------------------

class PluginCli : public CliTest {
 protected:
  /// `rigidity ARGS` with RIGIDITY_PLUGIN_PATH set to `path`.
  CliOutcome rigidity_with(const std::string& path, const std::string& args) const {
    ::setenv("RIGIDITY_PLUGIN_PATH", path.c_str(), 1);
    CliOutcome outcome = rigidity(args);
    ::unsetenv("RIGIDITY_PLUGIN_PATH");
    return outcome;
  }
};

TEST_F(PluginCli, MaterialsListsTabulatedAndThePluginsOnThePath) {
  const CliOutcome plain = rigidity("materials");
  EXPECT_EQ(plain.exit_status, 0) << plain.err;
  EXPECT_TRUE(contains(plain.out, "\ntabulated\n"));
  EXPECT_FALSE(contains(plain.out, "murnaghan"));
  const CliOutcome with =
      rigidity_with(plugin("murnaghan").parent_path().string() + ":" + plugin("good").string(), "materials");
  EXPECT_EQ(with.exit_status, 0) << with.err;
  EXPECT_TRUE(contains(with.out, "\nmurnaghan\n"));
  EXPECT_TRUE(contains(with.out, "\ntest_plugin_material\n"));
  EXPECT_TRUE(contains(with.out, "examples/plugin/murnaghan.cpp:"));
}

TEST_F(PluginCli, ABrokenPluginOnThePathIsInvalidInput) {
  const CliOutcome outcome = rigidity_with(plugin("acausal").parent_path().string(), "materials");
  EXPECT_EQ(outcome.exit_status, 2);
  EXPECT_TRUE(contains(outcome.err, "RIGIDITY_PLUGIN_PATH: error: plugin '"));
  EXPECT_TRUE(contains(outcome.err, "acausal"));
  const CliOutcome missing = rigidity_with("/no/such/dir", "materials");
  EXPECT_EQ(missing.exit_status, 2);
  EXPECT_TRUE(contains(missing.err, "'/no/such/dir' is neither a directory nor a file"));
}

TEST_F(PluginCli, RunsASceneWithAPluginAndWritesItAsRun) {
  std::ofstream(dir() / "scene.yaml") << with_plugin(kMurnaghanScene, plugin("murnaghan").string());
  const CliOutcome outcome = rigidity("run scene.yaml --out out");
  ASSERT_EQ(outcome.exit_status, 0) << outcome.err;
  EXPECT_TRUE(contains(read_text(dir() / "out" / "summary.json"), "\"status\": \"ok\""));
  // The scene as run names the plugin, and runs again from where it was written.
  EXPECT_TRUE(contains(read_text(dir() / "out" / "resolved_scene.yaml"), plugin("murnaghan").string()));
  const CliOutcome again = rigidity("validate out/resolved_scene.yaml");
  EXPECT_EQ(again.exit_status, 0) << again.err;
}

}  // namespace
}  // namespace rigidity::testing
