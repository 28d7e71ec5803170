// Walls and pistons: the material next to a wall moves with it. The exact Riemann solver's
// wall problem against the independent reference for every material of the registry, on
// both sides of pistons that push and withdraw, and the front tracker's piston faces
// against it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "exact/registry_samples.hpp"
#include "exact/riemann.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

/// Star states of two root finds to round-off, each converged to machine precision.
constexpr double kStar = 1e-10;
/// A piston face in front tracking holds the star state exactly.
constexpr double kTracked = 1e-12;

TEST(WallReflection, MovingPistonSetsTheClosedFormStarStateOfEveryMaterial) {
  int checked = 0;
  for (const exact::MaterialSample& sample : exact::registry_samples()) {
    const Material& m = *sample.material;
    const exact::MaterialLaw law(m);
    for (Side side : {Side::left, Side::right}) {
      for (double u : {-0.05, 0.05, -0.2, 0.2}) {
        // The piston moves at u; the material rests, slightly compressed (p > 0).
        SCOPED_TRACE(sample.model + (side == Side::left ? " wall on the right" : " wall on the left") +
                     " at u = " + std::to_string(u));
        const State state{0.0, Stretch::from_value(0.97)};
        const exact::Side exact_side = side == Side::left ? exact::Side::left : exact::Side::right;
        const exact::Solution<double> ref =
            exact::wall_problem<double>(law, {0.0, 0.97}, exact_side, std::atanh(u), 0.0);
        if (!ref.solved) continue;  // crushed: beyond this material's reach
        const RiemannSolution sol = solve_wall(m, state, side, std::atanh(u), 0.0);
        ASSERT_EQ(sol.status, Status::ok);
        EXPECT_EQ(sol.parted, ref.parted);
        const exact::Wave<double>& wave = side == Side::left ? ref.left : ref.right;
        const State& star = side == Side::left ? sol.left : sol.right;
        EXPECT_NEAR(sol.pressure, ref.pressure, kStar * (std::abs(ref.pressure) + m.rest_density()));
        EXPECT_NEAR(star.rapidity, wave.star.rapidity, kStar);
        EXPECT_NEAR(star.stretch.value(), wave.star.stretch, kStar);
        // Unless it let go, the material next to the wall moves with it.
        if (!ref.parted) {
          EXPECT_NEAR(std::tanh(star.rapidity), u, kStar);
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 40);
}

std::string piston_scene(const std::string& material, double piston_velocity, double stretch) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, R"(
name: piston
materials: {m: %s}
bodies: [{name: bar, material: m, length: 1.0, velocity: 0.0, stretch: %.17g}]
boundaries:
  left: {type: piston, velocity: %.17g}
  right: {type: wall}
time: {end: 0.6}
outputs:
  probes: [{name: face, body: bar, at: left, quantities: [p, v, s], every: 0.1}]
)",
                material.c_str(), stretch, piston_velocity);
  return buf;
}

TEST(WallReflection, PistonFaceHoldsTheExactStarStateOfEachBuiltinMaterial) {
  // A piston pushes into, or withdraws from, a compressed bar at rest; until the wave from
  // the piston returns, the face holds the star of the wall problem (a jump, a shock or the
  // tail of a fan).
  struct Case {
    std::string yaml;
    exact::ClosedFormLaw<double> law;
  };
  const std::vector<Case> cases = {
      {"{model: rigid, rest_density: 1.3}", exact::rigid(1.3)},
      {"{model: hooke, wave_speed: 0.6}", exact::hooke(1.0, 0.6)},
      {"{model: rigid_fluid}", exact::rigid_fluid(1.0)},
      {"{model: constant_sound_speed, sound_speed: 0.5}", exact::constant_sound_speed(1.0, 0.5)}};
  for (const Case& c : cases) {
    for (double u : {0.3, -0.1}) {
      SCOPED_TRACE(c.yaml + " piston at " + std::to_string(u));
      const RunResult r = solve(load_scene_string(piston_scene(c.yaml, u, 0.8), "<test>"));
      const exact::Solution<double> ref =
          exact::wall_problem<double>(c.law, {0.0, 0.8}, exact::Side::right, std::atanh(u), 0.0);
      ASSERT_TRUE(ref.solved);
      ASSERT_FALSE(ref.parted);
      int checked = 0;
      for (const ProbeSample& s : r.probes) {
        if (s.t <= 0.0) continue;
        const double expected = s.quantity == Quantity::p   ? ref.pressure
                                : s.quantity == Quantity::v ? u
                                                            : ref.right.star.stretch;
        EXPECT_NEAR(s.value, expected, kTracked * (1.0 + std::abs(expected))) << "t = " << s.t;
        ++checked;
      }
      EXPECT_EQ(checked, 18);
    }
  }
}

}  // namespace
}  // namespace rigidity
