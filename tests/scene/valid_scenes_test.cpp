// Valid scenes load with the right values: natural and SI units, velocity / rapidity /
// gamma, segments, defaults, pistons, outputs; resolved_yaml reloads to the same Scene.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "rigidity/registry.hpp"
#include "rigidity/scene_loader.hpp"
#include "scene_test_util.hpp"
#include "test_material.hpp"

RIGIDITY_REGISTER_MATERIAL(rigidity::test::SceneTestMaterial);

namespace rigidity::test {
namespace {

constexpr double c = kSpeedOfLightSI;

const SceneTestMaterial& test_material(const Scene& scene, const std::string& name) {
  return dynamic_cast<const SceneTestMaterial&>(*scene.materials.at(name).material);
}

// ---- the embedded default scene --------------------------------------------------------------

TEST(DefaultScene, IsThePapersWallImpact) {
  const Scene scene = load_scene_string(default_scene_text(), "<default>");
  EXPECT_EQ(scene.name, "paper_wall_impact");
  EXPECT_EQ(scene.source, "<default>");
  EXPECT_EQ(scene.units, UnitSystem::natural);
  ASSERT_EQ(scene.materials.count("rigid_steel"), 1u);
  EXPECT_EQ(scene.materials.at("rigid_steel").model, "rigid");
  EXPECT_EQ(scene.materials.at("rigid_steel").material->rest_density(), 1.0);
  ASSERT_EQ(scene.bodies.size(), 1u);
  const BodyDecl& bar = scene.bodies[0];
  EXPECT_EQ(bar.name, "bar");
  EXPECT_EQ(bar.position, 0.0);
  ASSERT_EQ(bar.segments.size(), 1u);
  EXPECT_EQ(bar.segments[0].length, 1.0);
  EXPECT_TRUE(close_relative(bar.segments[0].rapidity, std::atanh(0.6)));
  EXPECT_EQ(bar.segments[0].stretch, Stretch::natural());
  EXPECT_EQ(bar.segments[0].material, "rigid_steel");
  EXPECT_EQ(bar.natural_length(), 1.0);
  EXPECT_EQ(scene.left.type, BoundaryType::free);
  EXPECT_EQ(scene.right.type, BoundaryType::wall);
  EXPECT_FALSE(scene.right.bonded);
  EXPECT_TRUE(close_relative(scene.right.position, 0.8));  // the bar's right end: l0 s / gamma
  EXPECT_EQ(scene.solver.method, SolverMethod::characteristics);
  EXPECT_EQ(scene.solver.tolerance, 1.0e-12);
  EXPECT_EQ(scene.t_end, 1.5);
  ASSERT_EQ(scene.outputs.probes.size(), 2u);
  EXPECT_EQ(scene.outputs.probes[0].name, "wall");
  EXPECT_EQ(scene.outputs.probes[0].X, 1.0);
  EXPECT_EQ(scene.outputs.probes[0].quantities, (std::vector<Quantity>{Quantity::p, Quantity::v, Quantity::s}));
  EXPECT_EQ(scene.outputs.probes[0].every, 0.05);
  EXPECT_EQ(scene.outputs.probes[1].X, 0.0);
  ASSERT_EQ(scene.outputs.snapshots.size(), 1u);
  EXPECT_EQ(scene.outputs.snapshots[0].times, (std::vector<double>{0.25, 0.5, 0.75}));
  EXPECT_EQ(scene.outputs.snapshots[0].samples, 11);
  EXPECT_TRUE(scene.outputs.snapshots[0].bodies.empty());
  EXPECT_TRUE(scene.outputs.fronts);
}

TEST(DefaultScene, IsTheConfigFile) {
  std::ifstream in(std::string(RIGIDITY_SOURCE_DIR) + "/configs/paper_wall_impact.yaml");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(default_scene_text(), text);
}

TEST(Configs, EveryShippedSceneLoads) {
  namespace fs = std::filesystem;
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(RIGIDITY_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW({
      try {
        (void)load_scene_file(entry.path().string());
      } catch (const InputError& e) {
        ADD_FAILURE() << e.what();
      }
    });
    ++count;
  }
  EXPECT_GE(count, 1);
}

// ---- defaults -----------------------------------------------------------------------------------

constexpr const char* kMinimal = R"(
name: minimal
materials:
  m: {model: rigid}
bodies:
  - {name: bar, material: m, length: 2.5}
time: {end: 3}
)";

TEST(Defaults, AreFilledIn) {
  const Scene scene = load_ok(kMinimal);
  EXPECT_EQ(scene.units, UnitSystem::natural);
  EXPECT_TRUE(scene.plugins.empty());
  EXPECT_EQ(scene.materials.at("m").material->rest_density(), 1.0);
  const BodyDecl& bar = scene.bodies.at(0);
  EXPECT_EQ(bar.position, 0.0);
  EXPECT_EQ(bar.segments.at(0).rapidity, 0.0);
  EXPECT_EQ(bar.segments.at(0).stretch, Stretch::natural());
  EXPECT_EQ(bar.natural_length(), 2.5);
  EXPECT_EQ(scene.left.type, BoundaryType::free);
  EXPECT_EQ(scene.right.type, BoundaryType::free);
  EXPECT_EQ(scene.solver.method, SolverMethod::characteristics);
  EXPECT_EQ(scene.solver.tolerance, 1.0e-12);
  EXPECT_EQ(scene.solver.max_fronts, 1000000);
  EXPECT_EQ(scene.solver.cells, 400);
  EXPECT_EQ(scene.solver.order, 2);
  EXPECT_EQ(scene.solver.cfl, 0.5);
  EXPECT_EQ(scene.solver.flux, FluxType::hll);
  EXPECT_EQ(scene.t_end, 3.0);
  EXPECT_TRUE(scene.outputs.probes.empty());
  EXPECT_TRUE(scene.outputs.snapshots.empty());
  EXPECT_FALSE(scene.outputs.fronts);
}

TEST(Defaults, AreWrittenToTheResolvedScene) {
  const Scene scene = load_ok(kMinimal);
  const std::string r = scene.resolved_yaml();
  for (const char* expected :
       {"units: natural", "plugins: []", "rest_density: 1", "position: 0", "velocity: 0", "stretch: 1",
        "left: {type: free}", "method: characteristics", "tolerance: 1e-12", "max_fronts: 1000000", "cells: 400",
        "order: 2", "cfl: 0.5", "flux: hll", "probes: []", "snapshots: []", "fronts: false"})
    EXPECT_NE(r.find(expected), std::string::npos) << expected << " not in\n" << r;
}

TEST(Defaults, SolverKeysOfTheOtherMethodAreCheckedAndKept) {
  const Scene scene = load_ok(std::string(kMinimal) + "solver: {method: characteristics, cells: 50, flux: exact}\n");
  EXPECT_EQ(scene.solver.method, SolverMethod::characteristics);
  EXPECT_EQ(scene.solver.cells, 50);
  EXPECT_EQ(scene.solver.flux, FluxType::exact);
  EXPECT_NE(scene.resolved_yaml().find("cells: 50"), std::string::npos);
}

// ---- numbers --------------------------------------------------------------------------------------

TEST(Numbers, AcceptYamlDecimalForms) {
  for (const auto& [text, value] : std::vector<std::pair<std::string, double>>{
           {"2", 2.0}, {"+1.5", 1.5}, {".5", 0.5}, {"3.", 3.0}, {"1e3", 1000.0}, {"2.5E-3", 2.5e-3}, {"1e-400", 0.0}}) {
    SCOPED_TRACE(text);
    const Scene scene =
        load_ok("name: n\nmaterials: {m: {model: rigid}}\nbodies: [{name: b, material: m, position: " + text +
                ", length: 1}]\ntime: {end: 1}\n");
    EXPECT_EQ(scene.bodies[0].position, value);
  }
}

TEST(Numbers, IntegersAcceptExponentForm) {
  const Scene scene = load_ok(std::string(kMinimal) + "solver: {max_fronts: 2e6, cells: 1.0e3}\n");
  EXPECT_EQ(scene.solver.max_fronts, 2000000);
  EXPECT_EQ(scene.solver.cells, 1000);
  EXPECT_NE(scene.resolved_yaml().find("max_fronts: 2000000"), std::string::npos);
}

// ---- velocity, rapidity, gamma ----------------------------------------------------------------------

Scene body_with(const std::string& state) {
  return load_ok("name: n\nmaterials: {m: {model: rigid}}\nbodies:\n  - {name: b, material: m, length: 1, " + state +
                 "}\ntime: {end: 1}\n");
}

TEST(InitialState, VelocityIsStoredAsRapidity) {
  EXPECT_TRUE(close_relative(body_with("velocity: 0.6").bodies[0].segments[0].rapidity, std::atanh(0.6)));
  EXPECT_TRUE(close_relative(body_with("velocity: -0.3").bodies[0].segments[0].rapidity, std::atanh(-0.3)));
  EXPECT_TRUE(
      close_relative(body_with("velocity: 0.999999999999").bodies[0].segments[0].rapidity, std::atanh(0.999999999999)));
}

TEST(InitialState, RapidityIsKeptExactly) {
  EXPECT_EQ(body_with("rapidity: 2.0").bodies[0].segments[0].rapidity, 2.0);
  EXPECT_EQ(body_with("rapidity: -30").bodies[0].segments[0].rapidity, -30.0);
}

TEST(InitialState, GammaKeepsFullPrecisionUpTo1e12) {
  for (double gamma : {1.0, 1.25, 1.0e3, 1.0e12}) {
    const double phi = body_with("gamma: " + std::to_string(gamma)).bodies[0].segments[0].rapidity;
    EXPECT_TRUE(close_relative(phi, std::acosh(gamma)));
    if (gamma > 1.0) {
      EXPECT_TRUE(close_relative(std::cosh(phi), gamma, 1.0e-14));
    }
  }
  const Scene scene = body_with("gamma: 1.0e12, direction: -1");
  EXPECT_TRUE(close_relative(scene.bodies[0].segments[0].rapidity, -std::acosh(1.0e12)));
}

TEST(InitialState, LabLengthContractsAndStretches) {
  // l = l0 s / gamma: a bar of l0 = 1, s = 0.5, v = 0.6 (gamma = 1.25) is 0.4 long; a wall
  // at its right end defaults to x = 0.4.
  const Scene scene = load_ok(
      "name: n\nmaterials: {m: {model: rigid}}\nbodies: [{name: b, material: m, length: 1, velocity: 0.6, stretch: "
      "0.5}]\nboundaries: {right: {type: wall}}\ntime: {end: 1}\n");
  EXPECT_TRUE(close_relative(scene.bodies[0].segments[0].stretch.log(), std::log(0.5)));
  EXPECT_TRUE(close_relative(scene.right.position, 0.4));
}

// ---- segments ---------------------------------------------------------------------------------------

TEST(Segments, PiecewiseDataWithMaterialOverride) {
  const Scene scene = load_ok(R"(
name: layered
materials:
  steel: {model: rigid}
  rubber: {model: hooke, wave_speed: 0.1, rest_density: 0.5}
bodies:
  - name: bar
    material: steel
    position: -1
    segments:
      - {length: 0.5, velocity: 0.2, stretch: 0.8}
      - {length: 0.25, rapidity: 0.1, material: rubber}
      - {length: 0.25, gamma: 2, direction: -1, stretch: 1.1}
boundaries: {left: {type: wall}}
time: {end: 1}
)");
  const BodyDecl& bar = scene.bodies.at(0);
  ASSERT_EQ(bar.segments.size(), 3u);
  EXPECT_EQ(bar.position, -1.0);
  EXPECT_EQ(bar.natural_length(), 1.0);
  EXPECT_EQ(bar.segments[0].material, "steel");
  EXPECT_TRUE(close_relative(bar.segments[0].rapidity, std::atanh(0.2)));
  EXPECT_TRUE(close_relative(bar.segments[0].stretch.log(), std::log(0.8)));
  EXPECT_EQ(bar.segments[1].material, "rubber");
  EXPECT_EQ(bar.segments[1].rapidity, 0.1);
  EXPECT_EQ(bar.segments[1].stretch, Stretch::natural());
  EXPECT_TRUE(close_relative(bar.segments[2].rapidity, -std::acosh(2.0)));
  EXPECT_EQ(scene.left.position, -1.0);  // the wall defaults to the body's left end
  EXPECT_EQ(scene.material_of(bar.segments[1]).model(), "hooke");
  // Each segment's material is written out in full.
  EXPECT_NE(scene.resolved_yaml().find("material: steel}"), std::string::npos) << scene.resolved_yaml();
}

// ---- several bodies -----------------------------------------------------------------------------------

TEST(Bodies, MayTouchWithinRounding) {
  // b starts where a ends, computed by hand: 0.8 = 1 / 1.25 up to rounding.
  const Scene scene = load_ok(R"(
name: two
materials: {m: {model: rigid}}
bodies:
  - {name: a, material: m, length: 1, velocity: 0.6}
  - {name: b, material: m, position: 0.8, length: 1, velocity: -0.6}
  - {name: c, material: m, position: 5, length: 1}
time: {end: 1}
)");
  ASSERT_EQ(scene.bodies.size(), 3u);
  const double a_end = scene.bodies[0].position + 1.0 / std::cosh(std::atanh(0.6));
  EXPECT_TRUE(close_relative(scene.bodies[1].position, 0.8));
  EXPECT_GE(scene.bodies[1].position, a_end);  // never overlapping, not even by an ulp
  EXPECT_EQ(scene.bodies[2].position, 5.0);
}

// ---- boundaries ------------------------------------------------------------------------------------------

TEST(Boundaries, WallsAndPistons) {
  const Scene scene = load_ok(R"(
name: pistons
materials: {m: {model: rigid}}
bodies: [{name: bar, material: m, position: 1, length: 2}]
boundaries:
  left: {type: piston, bonded: true, table: [[0, 0.5], [0.25, 0], [1, -0.5]]}
  right: {type: wall, position: 4}
time: {end: 2}
)");
  EXPECT_EQ(scene.left.type, BoundaryType::piston);
  EXPECT_TRUE(scene.left.bonded);
  EXPECT_EQ(scene.left.position, 1.0);
  EXPECT_EQ(scene.left.piston.times, (std::vector<double>{0.0, 0.25, 1.0}));
  ASSERT_EQ(scene.left.piston.rapidities.size(), 3u);
  EXPECT_TRUE(close_relative(scene.left.piston.rapidities[0], std::atanh(0.5)));
  EXPECT_EQ(scene.left.piston.rapidities[1], 0.0);
  EXPECT_TRUE(close_relative(scene.left.piston.rapidities[2], std::atanh(-0.5)));
  EXPECT_EQ(scene.right.type, BoundaryType::wall);
  EXPECT_EQ(scene.right.position, 4.0);
  EXPECT_NE(scene.resolved_yaml().find("position: 1"), std::string::npos);  // the derived default is written out
}

TEST(Boundaries, ConstantPiston) {
  const Scene scene = load_ok(std::string(kMinimal) + "boundaries: {right: {type: piston, velocity: -0.25}}\n");
  EXPECT_EQ(scene.right.piston.times, (std::vector<double>{0.0}));
  ASSERT_EQ(scene.right.piston.rapidities.size(), 1u);
  EXPECT_TRUE(close_relative(scene.right.piston.rapidities[0], std::atanh(-0.25)));
  EXPECT_EQ(scene.right.position, 2.5);
  EXPECT_FALSE(scene.right.bonded);
}

TEST(Bodies, AProfileIsTheStaircaseOfItsValuesAtTheSegmentsMiddles) {
  const Scene scene = load_ok(R"yaml(
name: profile
materials: {m: {model: hooke, wave_speed: 0.5}}
bodies:
  - {name: bar, material: m, length: 2, velocity_profile: "0.2*sin(_pi*X/l0)", stretch_profile: "1 + 0.1*X",
     profile_segments: 8}
  - {name: other, material: m, position: 3, length: 1, gamma: 1.25, stretch_profile: "1 - 0.1*X", profile_segments: 2}
time: {end: 1}
)yaml");
  const std::vector<Segment>& segments = scene.bodies.at(0).segments;
  ASSERT_EQ(segments.size(), 8u);
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double X = 2.0 * (static_cast<double>(k) + 0.5) / 8.0;
    EXPECT_DOUBLE_EQ(segments[k].length, 0.25);
    EXPECT_NEAR(std::tanh(segments[k].rapidity), 0.2 * std::sin(M_PI * X / 2.0), 1e-12) << k;  // muparser's _pi
    EXPECT_NEAR(segments[k].stretch.value(), 1.0 + 0.1 * X, 1e-15) << k;
    EXPECT_EQ(segments[k].material, "m");
  }
  // What is not a profile stays uniform: gamma 1.25 (v = 0.6) along a stretch profile.
  const std::vector<Segment>& other = scene.bodies.at(1).segments;
  ASSERT_EQ(other.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(std::tanh(other[k].rapidity), 0.6, 1e-15);
    EXPECT_NEAR(other[k].stretch.value(), 1.0 - 0.1 * (static_cast<double>(k) + 0.5) / 2.0, 1e-15);
  }
  // The scene as run reloads to the same bodies.
  const Scene again = load_ok(scene.resolved_yaml());
  ASSERT_EQ(again.bodies.at(0).segments.size(), 8u);
  EXPECT_EQ(again.bodies.at(0).segments[3].rapidity, segments[3].rapidity);
}

TEST(Bodies, AProfileOfAnSiSceneIsWrittenInItsUnits) {
  const Scene scene = load_ok(R"(
name: profile_si
units: si
materials: {steel: {model: hooke, rest_density: 7850, wave_speed: 5100}}
bodies:
  - {name: bar, material: steel, length: 2, velocity_profile: "100*X", profile_segments: 2}
time: {end: 1e-4}
)");
  const std::vector<Segment>& segments = scene.bodies.at(0).segments;
  ASSERT_EQ(segments.size(), 2u);
  // X in metres (0.5 and 1.5 m at the middles), v in m/s: 50 and 150 m/s, in units of c.
  EXPECT_NEAR(std::tanh(segments[0].rapidity), 50.0 / 299792458.0, 1e-20);
  EXPECT_NEAR(std::tanh(segments[1].rapidity), 150.0 / 299792458.0, 1e-20);
}

// ---- outputs -----------------------------------------------------------------------------------------------

TEST(Outputs, ProbesAndSnapshots) {
  const Scene scene = load_ok(R"(
name: outs
materials: {m: {model: rigid}}
bodies:
  - {name: a, material: m, length: 2}
  - {name: b, material: m, position: 3, segments: [{length: 0.5}, {length: 1}]}
time: {end: 2}
outputs:
  probes:
    - {name: mid, body: a, at: 0.5, quantities: [X, x, v, s, p, e, rho, gamma, cs], every: 0.1}
    - {name: tail, body: b, at: right, quantities: [p], every: 2}
  snapshots:
    - {times: [0, 2], quantities: [p], samples: 3, bodies: [b]}
  fronts: true
)");
  ASSERT_EQ(scene.outputs.probes.size(), 2u);
  EXPECT_EQ(scene.outputs.probes[0].X, 0.5);
  EXPECT_EQ(scene.outputs.probes[0].quantities.size(), 9u);
  EXPECT_EQ(scene.outputs.probes[1].X, 1.5);  // l0 of b
  EXPECT_EQ(scene.outputs.snapshots.at(0).times, (std::vector<double>{0.0, 2.0}));
  EXPECT_EQ(scene.outputs.snapshots.at(0).samples, 3);
  EXPECT_EQ(scene.outputs.snapshots.at(0).bodies, (std::vector<std::string>{"b"}));
  EXPECT_TRUE(scene.outputs.fronts);
}

TEST(Outputs, SnapshotsEveryFromZeroToTheEndAsDecimals) {
  const Scene scene = load_ok(std::string(kMinimal) + "outputs: {snapshots: [{every: 0.1, quantities: [p]}]}\n");
  std::vector<double> expected;
  for (int k = 0; k <= static_cast<int>(std::lround(scene.t_end / 0.1)); ++k)
    expected.push_back(std::stod(std::to_string(k) + "e-1"));  // 0.3, not 3 × 0.1
  EXPECT_EQ(scene.outputs.snapshots.at(0).times, expected);
  EXPECT_EQ(scene.outputs.snapshots.at(0).times.back(), scene.t_end);
}

TEST(Boundaries, TractionTakesAPressureOrAHistory) {
  const Scene constant = load_ok(std::string(kMinimal) + "boundaries: {left: {type: traction, pressure: 0.25}}\n");
  EXPECT_EQ(constant.left.type, BoundaryType::traction);
  EXPECT_EQ(constant.left.traction_times, (std::vector<double>{0.0}));
  EXPECT_EQ(constant.left.traction_pressures, (std::vector<double>{0.25}));
  const Scene pulse = load_ok(std::string(kMinimal) +
                              "boundaries: {right: {type: traction, pressure_table: [[0, 0.3], [0.5, -0.05]]}}\n");
  EXPECT_EQ(pulse.right.traction_times, (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(pulse.right.traction_pressures, (std::vector<double>{0.3, -0.05}));
  EXPECT_EQ(pulse.left.type, BoundaryType::free);
}

// ---- SI units -------------------------------------------------------------------------------------------------

constexpr const char* kSI = R"(
name: si_bar
units: si
materials:
  steel: {model: hooke, rest_density: 7850, wave_speed: 5000}
  probe_material: {model: scene_test_material, yield_pressure: 2.5e8, signal_speed: 1.0e8, label: x}
bodies:
  - {name: bar, material: steel, position: -3, length: 2, velocity: 1000}
  - {name: rod, material: probe_material, position: 1, length: 0.5, velocity: -2.0e7}
boundaries:
  left: {type: piston, table: [[0, 10], [1.0e-4, -10]]}
  right: {type: wall, position: 1.6}
time: {end: 1.0e-3}
outputs:
  probes: [{name: p1, body: bar, at: 0.5, quantities: [p], every: 1.0e-5}]
  snapshots: [{times: [0, 5.0e-4], quantities: [x]}]
)";

TEST(SIUnits, AreConvertedToNaturalUnits) {
  const Scene scene = load_ok(kSI);
  EXPECT_EQ(scene.units, UnitSystem::si);
  // densities [kg/m^3] are natural already (c = 1 leaves mass densities alone)
  EXPECT_EQ(scene.materials.at("steel").material->rest_density(), 7850.0);
  // velocities [m/s] → fractions of c: hooke's sound speed at s = 1 is V
  EXPECT_TRUE(close_relative(scene.materials.at("steel").material->sound_speed(Stretch::natural()), 5000.0 / c));
  // pressures [Pa] → mass densities p/c²
  EXPECT_TRUE(close_relative(test_material(scene, "probe_material").yield_pressure(), 2.5e8 / (c * c)));
  EXPECT_TRUE(close_relative(test_material(scene, "probe_material").signal_speed(), 1.0e8 / c));
  EXPECT_EQ(test_material(scene, "probe_material").label(), "x");
  // lengths [m] are natural lengths
  EXPECT_EQ(scene.bodies[0].position, -3.0);
  EXPECT_EQ(scene.bodies[0].segments[0].length, 2.0);
  EXPECT_TRUE(close_relative(scene.bodies[0].segments[0].rapidity, std::atanh(1000.0 / c)));
  EXPECT_TRUE(close_relative(scene.bodies[1].segments[0].rapidity, std::atanh(-2.0e7 / c)));
  // times [s] → lengths c·t
  EXPECT_TRUE(close_relative(scene.t_end, 1.0e-3 * c));
  EXPECT_TRUE(close_relative(scene.outputs.probes[0].every, 1.0e-5 * c));
  EXPECT_EQ(scene.outputs.snapshots[0].times[0], 0.0);
  EXPECT_TRUE(close_relative(scene.outputs.snapshots[0].times[1], 5.0e-4 * c));
  EXPECT_TRUE(close_relative(scene.left.piston.times[1], 1.0e-4 * c));
  EXPECT_TRUE(close_relative(scene.left.piston.rapidities[0], std::atanh(10.0 / c)));
  EXPECT_EQ(scene.right.position, 1.6);
  // resolved_yaml stays in SI
  EXPECT_NE(scene.resolved_yaml().find("units: si"), std::string::npos);
  EXPECT_NE(scene.resolved_yaml().find("wave_speed: 5000"), std::string::npos) << scene.resolved_yaml();
  EXPECT_NE(scene.resolved_yaml().find("end: 0.001"), std::string::npos) << scene.resolved_yaml();
}

TEST(SIUnits, DefaultsAreWrittenInSI) {
  // yield_pressure defaults to 0.3 (natural): written as 0.3 c² Pa, read back exactly.
  const Scene scene = load_ok(R"(
name: si_defaults
units: si
materials: {m: {model: scene_test_material}}
bodies: [{name: b, material: m, length: 1}]
time: {end: 1}
)");
  EXPECT_EQ(test_material(scene, "m").yield_pressure(), 0.3);
  EXPECT_EQ(test_material(scene, "m").signal_speed(), 0.7);
  EXPECT_EQ(test_material(scene, "m").label(), "plain");
  const Scene again = load_ok(scene.resolved_yaml());
  EXPECT_EQ(test_material(again, "m").yield_pressure(), 0.3);
  EXPECT_EQ(test_material(again, "m").signal_speed(), 0.7);
}

// ---- materials -------------------------------------------------------------------------------------------

TEST(Materials, ConstructorRefusalIsAnInputErrorAtTheMaterial) {
  try {
    (void)load_scene_string(
        "name: n\nmaterials:\n  m: {model: scene_test_material, label: explode}\nbodies: [{name: b, material: m, "
        "length: 1}]\ntime: {end: 1}\n",
        "boom.yaml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "materials.m");
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(e.message().find("refused by the constructor"), std::string::npos) << e.what();
  }
}

TEST(Materials, EveryBuiltInLoads) {
  const Scene scene = load_ok(R"(
name: all
materials:
  a: {model: rigid, rest_density: 2}
  b: {model: hooke, wave_speed: 0.5}
  c: {model: rigid_fluid}
  d: {model: constant_sound_speed, sound_speed: 0.3}
bodies:
  - {name: a, material: a, length: 1}
  - {name: b, material: b, position: 1, length: 1}
  - {name: c, material: c, position: 2, length: 1, stretch: 0.5}
  - {name: d, material: d, position: 3, length: 1}
time: {end: 1}
)");
  EXPECT_EQ(scene.materials.size(), 4u);
  EXPECT_EQ(scene.materials.at("a").material->rest_density(), 2.0);
  EXPECT_EQ(scene.materials.at("d").material->model(), "constant_sound_speed");
}

// ---- resolved_yaml ------------------------------------------------------------------------------------------

TEST(Resolved, ReloadsToTheSameScene) {
  expect_round_trip(std::string(default_scene_text()));
  expect_round_trip(kMinimal);
  expect_round_trip(kSI);
  expect_round_trip(R"(
name: everything
plugins: []  # a listed plugin is loaded with the scene: tests/plugins/ round-trips real ones
materials:
  steel: {model: rigid}
  "123": {model: hooke, wave_speed: 0.1}
bodies:
  - name: a
    material: steel
    position: -0.1
    segments:
      - {length: 0.3333333333333333, velocity: 0.1, stretch: 0.7}
      - {length: 0.1, gamma: 1.0e12, direction: -1, material: "123"}
      - {length: 0.2, rapidity: 3}
  - {name: b, material: steel, position: 10, length: 1, gamma: 7}
boundaries:
  left: {type: wall, bonded: true}
  right: {type: piston, table: [[0, 0.1], [0.3, 0.2]]}
solver: {method: finite_volume, cells: 1000, order: 1, cfl: 0.9, flux: exact}
time: {end: 3}
outputs:
  probes: [{name: w, body: b, at: 0.25, quantities: [p, v], every: 0.001}]
  snapshots: [{times: [0, 1, 3], quantities: [x, s], samples: 5, bodies: [a, b]}]
  fronts: true
)");
}

TEST(Resolved, IsAFixedPoint) {
  const Scene first = load_ok(kSI);
  const Scene second = load_ok(first.resolved_yaml());
  EXPECT_EQ(first.resolved_yaml(), second.resolved_yaml());
}

// ---- files -------------------------------------------------------------------------------------------------------

TEST(Files, SourceIsThePath) {
  const std::string path = std::string(RIGIDITY_SOURCE_DIR) + "/configs/paper_wall_impact.yaml";
  EXPECT_EQ(load_scene_file(path).source, path);
}

TEST(Files, MissingFileIsAnInputError) {
  EXPECT_THROW((void)load_scene_file("/nonexistent/scene.yaml"), InputError);
  EXPECT_THROW((void)load_scene_file(RIGIDITY_TEST_DATA_DIR), InputError);  // a directory
}

}  // namespace
}  // namespace rigidity::test
