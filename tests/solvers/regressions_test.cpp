// Regressions found by the work-precision driver.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rigidity/registry.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/finite_volume.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

TEST(Regressions, FansAreSplitAtTheDefaultTolerance) {
  // span/tolerance ~ 1e11 once overflowed an int, and the fan collapsed to one step.
  const RunResult r = solve(load_scene_string(R"(
name: tube
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies:
  - name: tube
    material: gas
    segments: [{length: 0.5, stretch: 0.5}, {length: 0.5, stretch: 1.0}]
boundaries: {left: {type: wall}, right: {type: wall}}
solver: {tolerance: 1.0e-12}
time: {end: 0.1}
)",
                                              "<test>"));
  EXPECT_GT(r.stats.fronts, 1000);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("coarser than solver.tolerance"), std::string::npos);
}

TEST(Regressions, FiniteVolumeRecoversSubnormalAndTinyMomenta) {
  ParameterValues values;
  values.set("rest_density", 2.0);
  values.set("wave_speed", 0.5);
  const auto hooke = MaterialRegistry::instance().at("hooke").make(values);
  for (double momentum : {4e-311, 1.2e-308, 1e-100, 1e-20}) {
    const finite_volume::Conserved u{1.0, momentum};
    for (double guess : {0.0, 1e-3, 0.1}) {
      const finite_volume::Recovered r = finite_volume::recover_state(*hooke, u, guess);
      ASSERT_TRUE(r.status == Status::ok) << momentum << " from " << guess;
      // At s = 1 (labels 1, φ ≈ 0) momentum = (e+p) s sinh φ = ρ00 φ to round-off.
      EXPECT_NEAR(r.state.rapidity, momentum / 2.0, 1e-15 * momentum) << momentum;
    }
  }
}

}  // namespace
}  // namespace rigidity
