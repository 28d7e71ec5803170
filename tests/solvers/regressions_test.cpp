// Regressions found by the work-precision driver.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "rigidity/registry.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/finite_volume.hpp"
#include "rigidity/solvers/riemann.hpp"
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
  const auto hooke = build_material("hooke", values);
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

TEST(Regressions, AShockAsWeakAsRoundOffIsSolved) {
  // From mixed_115 (below) at t = 3.689: two states of one constant_sound_speed bar 1e-14 apart.
  // A trial star stretch an ulp from the right state made a shock whose change of Ψ rounded to
  // 0: its bracket started at 1e-300, gave up after 200 doublings ("no bracket"), and the failure
  // was read as the rapidity 0.
  ParameterValues values;
  values.set("rest_density", 1.306);
  values.set("sound_speed", 0.766);
  const auto m = build_material("constant_sound_speed", values);
  const State left{0.084683510613710489, Stretch::from_log(-0.38742040442452447)};
  const State right{0.084683510613702648, Stretch::from_log(-0.38742040442453474)};
  const RiemannSolution sol = solve_riemann(*m, left, *m, right, -std::numeric_limits<double>::infinity());
  ASSERT_EQ(sol.status, Status::ok) << sol.failure;
  EXPECT_NEAR(sol.left.rapidity, left.rapidity, 1e-14);
  EXPECT_NEAR(sol.left.stretch.log(), right.stretch.log(), 1e-14);
  EXPECT_NEAR(sol.pressure, m->pressure(right.stretch), 1e-14);
  // The wave curve a few ulps of pressure from the state itself: shocks of round-off strength.
  const WaveCurve curve(*m, right, Side::right);
  double p = curve.pressure();
  for (int k = 0; k < 8; ++k) {
    p = std::nextafter(p, 1.0);
    const WaveCurvePoint pt = curve.at_pressure(p);
    ASSERT_TRUE(pt.ok()) << k;
    EXPECT_NEAR(pt.rapidity, right.rapidity, 1e-15) << k;
  }
}

TEST(Regressions, AFluidBouncingIntoThreeHookeBarsRunsPastTheProblemThatStoppedIt) {
  // The scene stopped at t = 3.68922026255 with "the Riemann problem ... could not be solved (no
  // bracket)" (the test above). Run a little past it; to t = 20 it takes minutes.
  const RunResult r = solve(load_scene_string(R"(
name: mixed_115
materials:
  m0: {model: constant_sound_speed, sound_speed: 0.766, rest_density: 1.306}
  m1: {model: hooke, wave_speed: 0.864, rest_density: 1.787}
  m2: {model: hooke, wave_speed: 0.837, rest_density: 1.460}
  m3: {model: hooke, wave_speed: 0.769, rest_density: 1.320}
bodies:
  - {name: b0, material: m0, position: 0.0000, length: 0.6436, velocity: -0.3666}
  - {name: b1, material: m1, position: 1.1921, length: 1.2402, velocity: -0.1340}
  - {name: b2, material: m2, position: 2.9968, length: 1.2809, velocity: 0.0528}
  - {name: b3, material: m3, position: 4.7769, length: 1.0251, velocity: 0.1895}
boundaries: {left: {type: wall, position: -0.3}, right: {type: free}}
solver: {method: characteristics, tolerance: 0.001}
time: {end: 3.7}
)",
                                              "<test>"));
  EXPECT_EQ(r.status, "ok");
  const Conservation& c = r.conservation;
  // Fan steps of ΔΨ = 2e-3 meet the jump conditions to O(ΔΨ²) = 4e-6 (measured: 1.5e-6).
  EXPECT_NEAR(c.momentum_final - c.momentum_initial, c.wall_impulse, 4e-6);
  EXPECT_GE(c.energy_dissipated, 0.0);
}

}  // namespace
}  // namespace rigidity
