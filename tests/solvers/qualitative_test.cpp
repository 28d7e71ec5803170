// Cracks a smooth wave decides: where a step of a smooth wave brings a body to part, the
// place and instant of the crack follow the steps, so the run says its result is qualitative
// from then on; a crack that true jumps decide is exact and says nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

long cavitations(const RunResult& r) {
  long n = 0;
  for (const RunEvent& e : r.events) n += e.kind == "cavitation" ? 1 : 0;
  return n;
}

TEST(Qualitative, ACrackThatJumpsDecideIsExactAndSaysNothing) {
  // A rigid_fluid bar whose halves fly apart: the two release jumps from the middle meet no
  // smooth wave, and the body parts at t = 0 in the middle, at any tolerance.
  for (const double tolerance : {1e-2, 1e-4}) {
    const RunResult r = solve(load_scene_string(R"(
name: parting
materials: {fluid: {model: rigid_fluid}}
bodies:
  - name: bar
    material: fluid
    segments: [{length: 0.5, velocity: -0.3}, {length: 0.5, velocity: 0.3}]
solver: {tolerance: )" + std::to_string(tolerance) + R"(}
time: {end: 1.0}
)",
                                                "<test>"));
    EXPECT_EQ(cavitations(r), 1);
    EXPECT_TRUE(std::isnan(r.solver_number("qualitative_from")));
    for (const std::string& w : r.warnings) EXPECT_EQ(w.find("qualitative"), std::string::npos) << w;
  }
}

TEST(Qualitative, ACrackASmoothWaveDecidesMakesTheRestQualitative) {
  // A rigid_fluid bar (b0) against a gas bar (b1), both driven towards the left wall: the
  // gas's release fans reach b0 as smooth steps, and b0 parts where they bring tension. How
  // many pieces it ends in follows the steps (the tolerance), so the run says so.
  const auto run = [](double tolerance) {
    return solve(load_scene_string(R"(
name: cracks_in_the_bound
materials:
  m0: {model: rigid_fluid, rest_density: 1.996}
  m1: {model: constant_sound_speed, sound_speed: 0.516, rest_density: 0.538}
bodies:
  - {name: b0, material: m0, position: 0.0000, length: 0.5646, velocity: -0.2134}
  - {name: b1, material: m1, position: 0.8378, length: 0.6812, velocity: -0.3067}
boundaries: {left: {type: wall, position: -0.3}, right: {type: wall, position: 2.0}}
solver: {tolerance: )" + std::to_string(tolerance) +
                                       R"(}
time: {end: 5.0}
)",
                                   "<test>"));
  };
  const RunResult coarse = run(1e-3), fine = run(1e-4);
  for (const RunResult* r : {&coarse, &fine}) {
    const double from = r->solver_number("qualitative_from");
    ASSERT_FALSE(std::isnan(from));
    EXPECT_GT(from, 0.0);
    EXPECT_LT(from, 5.0);
    EXPECT_GE(r->solver_number("cracks_by_smooth_waves"), 1.0);
    bool said = false;
    for (const std::string& w : r->warnings)
      said = said || w.find("body 'b0' cracked where the steps") != std::string::npos;
    EXPECT_TRUE(said);
  }
  // What the warning is about: the cracks follow the steps.
  EXPECT_NE(cavitations(coarse), cavitations(fine));
}

TEST(Qualitative, ACrackAfterAKeptDropletMakesTheRestQualitative) {
  // Two rigid_fluid bars and a rigid one between walls (random scene 20): the rigid_fluid bars
  // ring, crack and rejoin. At t = 2.547 the coarse run keeps a droplet (a crack that near a
  // free end would break off less than the droplet length); the fine run lets it break off and
  // rejoin at 2.701. Until then the two runs crack and rejoin at the same instants; after it
  // they part differently, and the coarse run's error at t = 3 (4.2e-5 against the fine run)
  // is far above what its droplet booked (3.3e-6): the run says its result is qualitative from
  // its first crack after the droplet.
  const auto run = [](double tolerance) {
    return solve(load_scene_string(R"(
name: random_20
materials:
  m0: {model: rigid_fluid, rest_density: 2.12}
  m1: {model: rigid_fluid, rest_density: 1.847}
  m2: {model: rigid, rest_density: 0.579}
bodies:
  - {name: b0, material: m0, position: 0.0000, segments: [{length: 0.2660, velocity: -0.3085, stretch: 0.8639}, {length: 0.2660, velocity: -0.2896, stretch: 0.9762}, {length: 0.2660, velocity: -0.3009, stretch: 0.8810}, {length: 0.2660, velocity: -0.3171, stretch: 0.8803}]}
  - {name: b1, material: m1, position: 1.2236, segments: [{length: 0.1827, velocity: 0.2308, stretch: 0.8677}, {length: 0.1827, velocity: 0.2168, stretch: 0.9559}, {length: 0.1827, velocity: 0.3003, stretch: 0.8829}, {length: 0.1827, velocity: 0.2382, stretch: 0.8519}]}
  - {name: b2, material: m2, position: 2.1612, length: 0.5327, velocity: 0.1469}
boundaries: {left: {type: wall}, right: {type: wall, bonded: true}}
solver: {tolerance: )" + std::to_string(tolerance) +
                                       R"(}
time: {end: 3.0}
)",
                                   "<test>"));
  };
  const RunResult coarse = run(1e-4), fine = run(1e-6);
  ASSERT_GE(coarse.solver_number("droplets"), 1.0);
  EXPECT_EQ(fine.solver_number("droplets"), 0.0);
  const double from = coarse.solver_number("qualitative_from");
  ASSERT_FALSE(std::isnan(from));
  EXPECT_GE(coarse.solver_number("cracks_after_droplets"), 1.0);
  EXPECT_EQ(coarse.solver_number("cracks_by_smooth_waves"), 0.0);
  bool said = false;
  for (const std::string& w : coarse.warnings)
    said = said || w.find("after a droplet was kept in body 'b1'") != std::string::npos;
  EXPECT_TRUE(said);
  // The cracks and rejoins agree before the droplet and not after it.
  std::vector<std::pair<double, std::string>> before[2], after[2];
  for (int k = 0; k < 2; ++k)
    for (const RunEvent& e : (k == 0 ? coarse : fine).events)
      (e.t < from - 0.01 ? before[k] : after[k]).emplace_back(e.t, e.kind);
  ASSERT_EQ(before[0].size(), before[1].size());
  ASSERT_GT(before[0].size(), 100u);
  for (std::size_t i = 0; i < before[0].size(); ++i) {
    EXPECT_NEAR(before[0][i].first, before[1][i].first, 1e-9);
    EXPECT_EQ(before[0][i].second, before[1][i].second);
  }
  EXPECT_NE(after[0], after[1]);
}

}  // namespace
}  // namespace rigidity
