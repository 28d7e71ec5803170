// Shocks: the exact Riemann solver's star states against the independent jump conditions
// of tests/exact for every genuinely nonlinear material of the registry, and the front
// tracker's shocks (a shock tube, a wall impact) against the independent reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "exact/registry_samples.hpp"
#include "exact/riemann.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Star states of two root finds to round-off, each converged to machine precision.
constexpr double kStar = 1e-10;
/// What front tracking holds exactly: the star state and the shock's speed.
constexpr double kTracked = 1e-12;

/// The label and momentum jump conditions m [τ] = −[v], m [M] = [p] (docs/physics.md) across a front
/// of Lagrangian speed m between left state a and right state b, relative to the jumps.
void expect_jump_conditions(const Material& m, const State& a, const State& b, double speed, double tolerance) {
  const double dv = std::tanh(b.rapidity) - std::tanh(a.rapidity);
  const double dp = m.pressure(b.stretch) - m.pressure(a.stretch);
  EXPECT_LE(std::abs(speed * (label_density(b) - label_density(a)) + dv), tolerance * std::abs(dv)) << "labels";
  EXPECT_LE(std::abs(speed * (momentum_density(m, b) - momentum_density(m, a)) - dp), tolerance * std::abs(dp))
      << "momentum";
}

exact::State<double> to_exact(const State& s) { return {s.rapidity, s.stretch.value()}; }

TEST(ShockJump, LabelAndMomentumConditionsHoldForEveryGenuinelyNonlinearMaterial) {
  // Colliding and separating pairs: whichever is the shock for a material's convexity (a
  // compression for the usual one, an expansion for a reversed one) is checked.
  int shocks = 0;
  for (const exact::MaterialSample& sample : exact::registry_samples()) {
    const Material& m = *sample.material;
    if (m.linearly_degenerate() || m.cavitation_pressure() > -kInf) continue;
    const exact::MaterialLaw law(m);
    for (double v : {0.1, -0.1, 0.03}) {
      SCOPED_TRACE(sample.model + " closing speed " + std::to_string(v));
      const State left{std::atanh(v), Stretch::natural()}, right{-std::atanh(v), Stretch::from_value(0.95)};
      const RiemannSolution sol = solve_riemann(m, left, m, right, -kInf);
      ASSERT_EQ(sol.status, Status::ok);
      const exact::Solution<double> ref = exact::riemann_problem<double>(law, to_exact(left), law, to_exact(right));
      ASSERT_TRUE(ref.solved);
      EXPECT_NEAR(sol.pressure, ref.pressure, kStar * (std::abs(ref.pressure) + m.rest_density()));
      EXPECT_NEAR(sol.left.rapidity, ref.left.star.rapidity, kStar);
      EXPECT_NEAR(sol.right.rapidity, ref.right.star.rapidity, kStar);
      EXPECT_NEAR(sol.left.stretch.value(), ref.left.star.stretch, kStar);
      EXPECT_NEAR(sol.right.stretch.value(), ref.right.star.stretch, kStar);
      // The shocks the solver would emit: its own speed and states meet the jump conditions.
      if (ref.left.kind == exact::WaveKind::shock) {
        ++shocks;
        expect_jump_conditions(m, left, sol.left, shock_speeds(m, left, sol.left, -1).lagrangian, kStar);
        EXPECT_NEAR(shock_speeds(m, left, sol.left, -1).lagrangian, ref.left.front_speed(), kStar);
      }
      if (ref.right.kind == exact::WaveKind::shock) {
        ++shocks;
        expect_jump_conditions(m, sol.right, right, shock_speeds(m, right, sol.right, +1).lagrangian, kStar);
        EXPECT_NEAR(shock_speeds(m, right, sol.right, +1).lagrangian, ref.right.front_speed(), kStar);
      }
    }
  }
  EXPECT_GE(shocks, 6);
}

// ---- the front tracker's shocks ------------------------------------------------------------------

TEST(ShockJump, ShockTubeOfTheFrontTrackerHasTheExactStarStateAndShockSpeed) {
  // configs/shock_tube.yaml: the star state between the fan's tail and the shock, and the
  // shock itself, are resolved exactly whatever the fan step.
  const Scene scene = load_scene_string(R"(
name: shock_tube
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies:
  - name: tube
    material: gas
    segments: [{length: 0.5, stretch: 0.5}, {length: 0.5, stretch: 1.0}]
boundaries: {left: {type: wall}, right: {type: wall}}
solver: {tolerance: 0.05}
time: {end: 0.3}
outputs:
  snapshots: [{times: [0.3], quantities: [s, v], samples: 1001}]
  fronts: true
)",
                                        "<test>");
  const RunResult r = solve(scene);
  const auto gas = exact::constant_sound_speed(1.0, 0.5);
  const exact::Solution<double> ref = exact::riemann_problem<double>(gas, {0.0, 0.5}, gas, {0.0, 1.0});
  ASSERT_EQ(ref.right.kind, exact::WaveKind::shock);
  const double tail = 0.5 + 0.3 * ref.left.right_edge_speed(), shock = 0.5 + 0.3 * ref.right.front_speed();
  int plateau = 0;
  for (const SnapshotSample& s : r.snapshots) {
    // Off the fan's last step (which lies behind the tail by up to a step) and the shock.
    if (s.X < tail + 0.02 || s.X > shock - 1e-3) continue;
    const double expected = s.quantity == Quantity::s ? ref.right.star.stretch : exact::velocity(ref.right.star);
    EXPECT_NEAR(s.value, expected, kTracked) << "X = " << s.X;
    ++plateau;
  }
  EXPECT_GT(plateau, 100);
  // The shock: a straight world line from the initial jump (lab x = 0.25) at the exact speed.
  int segments = 0;
  for (const FrontSegment& f : r.fronts) {
    if (f.kind != SegmentKind::shock) continue;
    ++segments;
    EXPECT_EQ(f.family, +1);
    EXPECT_NEAR((f.x1 - f.x0) / (f.t1 - f.t0), ref.right.front_lab_speed(), kTracked);
    EXPECT_NEAR(f.x0 - f.t0 * ref.right.front_lab_speed(), 0.25, kTracked);
  }
  EXPECT_GE(segments, 1);
}

TEST(ShockJump, TwoShocksCrossingInPlaceLeaveTheExactStarState) {
  // Three segments of one gas at +u, 0, −u: each junction sends a shock into the middle one,
  // and the two meet at its centre, where the tracker crosses them in place (its closed-form
  // Hugoniot and secant star, not the Riemann solver). Behind them the gas must be in the
  // exact state between the two star states the first collisions made: the independent
  // reference solves the three problems by bisection on the jump conditions.
  const double u = 0.05;
  const Scene scene = load_scene_string(R"(
name: crossing_shocks
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies:
  - name: gas
    material: gas
    segments: [{length: 1.0, velocity: 0.05}, {length: 1.0, velocity: 0.0}, {length: 1.0, velocity: -0.05}]
solver: {method: characteristics, tolerance: 1.0e-9}
time: {end: 1.4}
outputs:
  probes: [{name: centre, body: gas, at: 1.5, quantities: [s, v], every: 0.1}]
)",
                                        "<test>");
  const RunResult r = solve(scene);
  const auto gas = exact::constant_sound_speed(1.0, 0.5);
  const exact::State<double> left{std::atanh(u), 1.0}, middle{0.0, 1.0}, right{-std::atanh(u), 1.0};
  const exact::Solution<double> first = exact::riemann_problem<double>(gas, left, gas, middle);
  const exact::Solution<double> second = exact::riemann_problem<double>(gas, middle, gas, right);
  ASSERT_EQ(first.right.kind, exact::WaveKind::shock);
  ASSERT_EQ(second.left.kind, exact::WaveKind::shock);
  const exact::Solution<double> crossed = exact::riemann_problem<double>(gas, first.right.star, gas, second.left.star);
  // The shocks reach the centre at 0.5/|m|; sample well after that, before anything else comes.
  const double meet = 0.5 / std::abs(first.right.front_speed());
  int after = 0;
  for (const ProbeSample& s : r.probes) {
    if (s.t < meet + 0.1) continue;
    const double expected = s.quantity == Quantity::s ? crossed.left.star.stretch : exact::velocity(crossed.left.star);
    EXPECT_NEAR(s.value, expected, 1e-11) << to_string(s.quantity) << " at t = " << s.t;
    ++after;
  }
  EXPECT_GE(after, 2);
  // The crossing compressed the gas further than either shock alone.
  EXPECT_LT(crossed.left.star.stretch, first.right.star.stretch - 1e-3);
}

TEST(ShockJump, WallImpactOfAConstantSoundSpeedBarMatchesTheIndependentReference) {
  // A bar at 0.4 c hits a wall: a shock runs back, behind it the bar rests against the wall.
  const Scene scene = load_scene_string(R"(
name: css_wall_impact
materials: {gas: {model: constant_sound_speed, sound_speed: 0.6, rest_density: 1.3}}
bodies: [{name: bar, material: gas, length: 1.0, velocity: 0.4}]
boundaries: {left: {type: free}, right: {type: wall}}
time: {end: 1.0}
outputs:
  probes: [{name: wall, body: bar, at: right, quantities: [p, s, v], every: 0.125}]
  fronts: true
)",
                                        "<test>");
  const RunResult r = solve(scene);
  const auto gas = exact::constant_sound_speed(1.3, 0.6);
  const exact::Solution<double> ref =
      exact::wall_problem<double>(gas, {std::atanh(0.4), 1.0}, exact::Side::left, 0.0, 0.0);
  ASSERT_EQ(ref.left.kind, exact::WaveKind::shock);
  const double transit = -1.0 / ref.left.front_speed();  // the shock reaches the free rear
  ASSERT_GT(transit, 1.0);
  int checked = 0;
  for (const ProbeSample& s : r.probes) {
    if (s.t <= 0.0) continue;
    const double expected = s.quantity == Quantity::p   ? ref.pressure
                            : s.quantity == Quantity::s ? ref.left.star.stretch
                                                        : 0.0;
    EXPECT_NEAR(s.value, expected, kTracked * (1.0 + std::abs(expected))) << "t = " << s.t;
    ++checked;
  }
  EXPECT_EQ(checked, 24);
  int segments = 0;
  for (const FrontSegment& f : r.fronts)
    if (f.kind == SegmentKind::shock) {
      ++segments;
      EXPECT_NEAR((f.x1 - f.x0) / (f.t1 - f.t0), ref.left.front_lab_speed(), kTracked);
    }
  EXPECT_GE(segments, 1);
}

}  // namespace
}  // namespace rigidity
