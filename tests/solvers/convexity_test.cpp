// A material of reversed convexity: the linear law p = ρ00 V² (1 − s) extended to
// relativity has a Lagrangian wave speed that grows under tension, so its expansions
// are shocks and its compressions fans — the opposite of the built-ins. The tracker
// must pick the admissible wave by the characteristics (Lax), not by the sign of the
// pressure jump, or the fans it emits would converge and recreate themselves forever.
#include <gtest/gtest.h>

#include <cmath>

#include "rigidity/numeric_material.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

class LinearLaw final : public PressureLawMaterial {
 public:
  static constexpr std::string_view kName = "test_linear_law";
  static std::string doc() { return "test only: p = rho00 V^2 (1 - s), V = 0.3"; }
  static std::vector<ParameterSpec> parameters() { return {rest_density_parameter()}; }
  explicit LinearLaw(const ParameterValues& values)
      : PressureLawMaterial(values.number("rest_density"), StretchRange{std::log(0.5), std::log(2.0)}) {}
  [[nodiscard]] std::string_view model() const override { return kName; }
  [[nodiscard]] double pressure_law(double s) const override { return rest_density() * 0.09 * (1.0 - s); }
};
RIGIDITY_REGISTER_MATERIAL(LinearLaw);

TEST(ReversedConvexity, ExpansionsAreShocksAndCompressionsFans) {
  ParameterValues values;
  values.set("rest_density", 1.0);
  const auto m = build_material("test_linear_law", values);
  const State compressed{0.0, Stretch::from_value(0.8)};
  // Released at a free end (p → 0, s → 1): an expansion, a shock for this material.
  EXPECT_TRUE(wave_is_shock(*m, compressed, Stretch::natural(), -1));
  // Compressed further: a fan.
  EXPECT_FALSE(wave_is_shock(*m, compressed, Stretch::from_value(0.7), -1));
}

TEST(ReversedConvexity, ACompressedBarReleasedAtFreeEndsRunsToTheEnd) {
  const RunResult r = solve(load_scene_string(R"(
name: reversed_convexity
materials: {m: {model: test_linear_law}}
bodies:
  - name: bar
    material: m
    segments:
      - {length: 0.5, velocity: 0.0, stretch: 0.8}
      - {length: 0.5, velocity: 0.0, stretch: 0.9}
solver: {tolerance: 0.01, max_interactions: 1000000}
time: {end: 3.0}
)",
                                              "<test>"));
  const Conservation& c = r.conservation;
  EXPECT_NEAR(c.momentum_final, c.momentum_initial, 1e-6);
  EXPECT_GE(c.energy_dissipated, 0.0);
  EXPECT_LE(c.energy_final, c.energy_initial + 1e-6);
  EXPECT_GT(r.stats.interactions, 2);
}

}  // namespace
}  // namespace rigidity
