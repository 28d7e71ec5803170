// Rarefaction fans: behind a withdrawing piston the front tracker's fan, split into steps of
// ΔΨ = solver.tolerance moving at the mean of their sides' characteristic speeds, against
// the exact centred fan of tests/exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "exact/riemann.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

TEST(Fan, WithdrawingPistonLeavesTheExactCentredFanToHalfAStep) {
  // A constant_sound_speed bar (V = 0.5), compressed (s = 0.6) and at rest against a wall on
  // its right, its left piston withdrawing at 0.2 c: a centred C+ fan from (X, t) = (0, 0),
  // carrying J− = φ − Ψ. With the steps of equal ΔΨ = span/floor(span/tolerance) (between one
  // and two tolerances) each moving at the speed of the label jump condition (the mean of
  // its sides' speeds to second order), a step front sits where the exact fan is half-way
  // between its two states: Ψ is off by at most ΔΨ/2, and by ΔΨ/4 on average over the fan.
  const double tolerance = 0.02, t = 1.0;
  char yaml[1024];
  std::snprintf(yaml, sizeof yaml, R"(
name: withdrawing_piston
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies: [{name: bar, material: gas, length: 1.0, velocity: 0.0, stretch: 0.6}]
boundaries: {left: {type: piston, velocity: -0.2}, right: {type: wall}}
solver: {tolerance: %.17g}
time: {end: %.17g}
outputs:
  snapshots: [{times: [%.17g], quantities: [s], samples: 20001}]
)",
                tolerance, t, t);
  const RunResult r = solve(load_scene_string(yaml, "<test>"));
  const auto gas = exact::constant_sound_speed(1.0, 0.5);
  const exact::Solution<double> ref =
      exact::wall_problem<double>(gas, {0.0, 0.6}, exact::Side::right, std::atanh(-0.2), 0.0);
  ASSERT_TRUE(ref.solved);
  ASSERT_EQ(ref.right.kind, exact::WaveKind::fan);
  const exact::Wave<double>& fan = ref.right;
  const double span = std::abs(gas.psi(fan.star.stretch) - gas.psi(fan.outer.stretch));
  // Steps of two tolerances (kFanStepPerTolerance): a centred step misses its part by a quarter.
  const double steps = std::max(1.0, std::floor(span / (2.0 * tolerance))), step = span / steps;
  const double tail = t * fan.left_edge_speed(), head = t * fan.right_edge_speed();
  ASSERT_LT(head, 1.0);  // the fan has not reached the wall

  double worst = 0.0, l1 = 0.0;
  std::set<double> levels;
  int inside = 0;
  const double dX = 1.0 / 20000.0;
  for (const SnapshotSample& s : r.snapshots) {
    const double psi = gas.psi(s.value), exact_psi = gas.psi(fan.at(s.X / t).stretch);
    const double error = std::abs(psi - exact_psi);
    worst = std::max(worst, error);
    if (s.X > tail && s.X < head) {
      l1 += error * dX;
      levels.insert(s.value);
      ++inside;
    }
  }
  const double width = head - tail;
  std::printf("fan: %g steps of dPsi = %.4g over X in [%.4f, %.4f]: max |dPsi| = %.4g step, L1 = %.4g step*width\n",
              steps, step, tail, head, worst / step, l1 / (step * width));
  EXPECT_GT(inside, 4000);
  // The states in the fan: the outer state, the star and the steps between.
  EXPECT_EQ(static_cast<double>(levels.size()), steps + 1.0);
  EXPECT_LE(worst, 0.55 * step);
  EXPECT_GT(l1, 0.2 * step * width);
  EXPECT_LT(l1, 0.3 * step * width);
}

}  // namespace
}  // namespace rigidity
