// Cracks a smooth wave decides: where a step of a smooth wave brings a body to part, the
// place and instant of the crack follow the steps, so the run says its result is qualitative
// from then on; a crack that true jumps decide is exact and says nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

}  // namespace
}  // namespace rigidity
