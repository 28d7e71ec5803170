// The paper's experiment as a library call (rigidity/solvers/wall_impact.hpp), what
// `rigidity compare` tabulates: against the closed forms of docs/materials.md and the independent
// exact wall problem of tests/exact/, which shares no code with the Riemann solver.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "exact/registry_samples.hpp"
#include "exact/riemann.hpp"
#include "rigidity/solvers/wall_impact.hpp"

namespace rigidity {
namespace {

TEST(WallImpactAnalysis, RigidBarMatchesThePaper) {
  // s = sqrt((1 − v)/(1 + v)) (paper eq. 15), p = (ρ00/2)(1/s² − 1) = ρ00 v/(1 − v), front at c.
  const auto rigid = testing::make_material("rigid", {{"rest_density", 2.0}});
  for (const double v : {1e-6, 0.1, 0.6, 0.8, 0.99}) {
    const ImpactOutcome r = wall_impact(*rigid, v);
    ASSERT_EQ(r.status, Status::ok) << v;
    EXPECT_NEAR(r.impact.s, std::sqrt((1.0 - v) / (1.0 + v)), 1e-14) << v;
    EXPECT_NEAR(r.impact.p, 2.0 * v / (1.0 - v), 1e-13 * (1.0 + 2.0 * v / (1.0 - v))) << v;
    EXPECT_NEAR(r.impact.front_speed, 1.0, 1e-15) << v;
  }
  EXPECT_FALSE(crush_speed(*rigid).has_value()) << "the rigid law stiffens without end";
}

TEST(WallImpactAnalysis, HookeFrontRunsAtItsWaveSpeedAndCrushesAtIt) {
  // Linearly degenerate: the front runs at c_s(1) = V in the bar's frame, and J+ = φ carried
  // to the wall gives Ψ* = artanh v, reachable while v < tanh Ψ_max = V (docs/materials.md).
  for (const double V : {0.3, 0.5, 0.9}) {
    const auto hooke = testing::make_material("hooke", {{"wave_speed", V}});
    const ImpactOutcome r = wall_impact(*hooke, 0.5 * V);
    ASSERT_EQ(r.status, Status::ok);
    EXPECT_NEAR(r.impact.front_speed, V, 1e-14);
    EXPECT_EQ(wall_impact(*hooke, V + 0.01 * (1.0 - V)).status, Status::out_of_range) << "crushed beyond V";
    const std::optional<double> crush = crush_speed(*hooke);
    ASSERT_TRUE(crush.has_value());
    EXPECT_NEAR(*crush, V, 1e-14);
  }
}

TEST(WallImpactAnalysis, EveryRegisteredMaterialMatchesTheIndependentWallProblem) {
  int checked = 0;
  for (const exact::MaterialSample& sample : exact::registry_samples()) {
    const Material& m = *sample.material;
    const exact::MaterialLaw law(m);
    for (const double v : {0.01, 0.2, 0.45}) {  // a sample of hooke crushes at V = 0.5 exactly
      const exact::Solution<double> ref =
          exact::wall_problem<double>(law, {std::atanh(v), 1.0}, exact::Side::left, 0.0, 0.0);
      const ImpactOutcome r = wall_impact(m, v);
      if (!ref.solved) {
        EXPECT_EQ(r.status, Status::out_of_range) << sample.model << " v = " << v;
        continue;
      }
      ASSERT_EQ(r.status, Status::ok) << sample.model << " v = " << v;
      EXPECT_NEAR(r.impact.s, ref.left.star.stretch, 1e-10 * ref.left.star.stretch) << sample.model << " v = " << v;
      EXPECT_NEAR(r.impact.p, ref.pressure, 1e-9 * std::abs(ref.pressure)) << sample.model << " v = " << v;
      EXPECT_GT(r.impact.front_speed, 0.0);
      EXPECT_LE(r.impact.front_speed, 1.0);
      ++checked;
    }
  }
  EXPECT_GE(checked, 12);
}

}  // namespace
}  // namespace rigidity
