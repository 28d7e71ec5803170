// The finite-volume baseline on a law that is not convex, against the exact solution of
// exact/nonconvex_riemann.hpp. The scene loader refuses such a law for the front tracker; the
// finite-volume scheme runs it: HLL's wave speeds are the characteristic speeds of the two face
// states, which is all it asks of a law.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "exact/nonconvex_riemann.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

namespace nc = exact::nonconvex;

/// σ(ε) = E (ε + (A/k)(1 − cos kε)), ε = s − 1, p = −σ: σ' = E (1 + A sin kε) > 0, an inflection
/// wherever cos kε = 0 (every 0.21 in stretch for k = 15); E = 0.2 ρ00 c² puts c_s between 0.1 and 0.9 c
/// on s in [0.5, 1.6].
constexpr double kE = 0.2, kA = 0.8, kK = 15.0;
double sine_pressure(double s) {
  const double e = s - 1.0;
  return -kE * (e + kA / kK * (1.0 - std::cos(kK * e)));
}

nc::Law sine_law() {
  return nc::Law(
      sine_pressure, [](double s) { return -kE * (1.0 + kA * std::sin(kK * (s - 1.0))); }, 1.0, 0.5, 1.6,
      [](double s) {
        const double e = s - 1.0;  // W = ρ00 + ∫_0^ε σ
        return 1.0 + kE * (e * e / 2.0 + kA / kK * (e - std::sin(kK * e) / kK));
      });
}

/// The law as a table of p(s): rows every ln 2/700 in ln s (s = 1 among them) from s = 0.5 to 1.6,
/// as a YAML block scalar indented by `indent`; Steffen's interpolation of it is within ~1e-8 of the law.
std::string sine_table(const std::string& indent) {
  std::string out = indent + "s,p\n";
  const double h = std::log(2.0) / 700.0;
  char row[96];
  for (int k = -700; std::exp(k * h) <= 1.6; ++k) {
    const double s = std::exp(k * h);
    std::snprintf(row, sizeof row, "%.17g,%.17g\n", s, k == 0 ? 0.0 : sine_pressure(s));
    out += indent + row;
  }
  return out;
}

/// The bar of l0 = 1, stretched (s = 1.3) left of X = 0.5 and compressed (s = 0.7) right of it, at
/// rest between bonded walls, to t = 0.25 (no wave reaches a wall); s sampled at 2001 labels.
std::string composite_scene(const std::string& solver) {
  return R"yaml(
name: nonconvex_fv
materials:
  sine:
    model: tabulated
    table: |
)yaml" + sine_table("      ") +
         R"yaml(
bodies:
  - name: bar
    material: sine
    segments:
      - {length: 0.5, velocity: 0.0, stretch: 1.3}
      - {length: 0.5, velocity: 0.0, stretch: 0.7}
boundaries: {left: {type: wall, bonded: true}, right: {type: wall, bonded: true}}
solver: )yaml" +
         solver +
         R"yaml(
time: {end: 0.25}
outputs:
  snapshots: [{times: [0.25], quantities: [s], samples: 2001}]
)yaml";
}
RunResult run_composite(int cells, int order) {
  char solver[128];
  std::snprintf(solver, sizeof solver, "{method: finite_volume, cells: %d, order: %d, flux: hll}", cells, order);
  return solve(load_scene_string(composite_scene(solver), "<test>"));
}

struct Errors {
  double all = 0.0;        ///< L1(s) over X in [0, 1]
  double composite = 0.0;  ///< the part of it from the composite wave, X in [0.575, 0.65]
};

Errors errors(const RunResult& r, const nc::Solution& exact) {
  Errors out;
  int n = 0;
  for (const SnapshotSample& sample : r.snapshots) {
    if (sample.quantity != Quantity::s) continue;
    const double error = std::abs(sample.value - exact.at((sample.X - 0.5) / 0.25).stretch);
    out.all += error;
    if (sample.X > 0.575 && sample.X < 0.65) out.composite += error;
    ++n;
  }
  EXPECT_EQ(n, 2001);
  out.all /= n;
  out.composite /= n;
  return out;
}

TEST(FiniteVolumeNonconvex, FirstOrderConvergesToTheCompositeWave) {
  // The exact solution: a shock into the stretched side, and into the compressed side a fan with
  // a shock attached at its sonic point (S | RS). First order, HLL: L1(s) 5.4e-3, 3.2e-3, 1.8e-3 at
  // 200, 400, 800 cells (orders 0.76, 0.81; about 0.8 on to 3200 cells), the composite wave's part
  // (X in [0.575, 0.65]) 2.0e-3, 1.4e-3, 8.4e-4 (orders 0.57, 0.71). Second order stalls at the
  // sonic point (docs/limits.md), so it is not asked here.
  const nc::Law law = sine_law();
  const nc::Solution exact = nc::riemann_problem(law, {0.0, 1.3}, {0.0, 0.7});
  ASSERT_TRUE(exact.solved);
  ASSERT_EQ(exact.left.pattern(), "S");
  ASSERT_EQ(exact.right.pattern(), "RS");
  const Errors e1 = errors(run_composite(200, 1), exact);
  const Errors e2 = errors(run_composite(400, 1), exact);
  const Errors e3 = errors(run_composite(800, 1), exact);
  std::printf("nonconvex S|RS, order 1: L1(s) = %.4g %.4g %.4g (composite wave %.4g %.4g %.4g), orders %.3f %.3f\n",
              e1.all, e2.all, e3.all, e1.composite, e2.composite, e3.composite, std::log2(e1.all / e2.all),
              std::log2(e2.all / e3.all));
  EXPECT_GT(std::log2(e1.all / e2.all), 0.6);
  EXPECT_GT(std::log2(e2.all / e3.all), 0.6);
  EXPECT_GT(std::log2(e1.composite / e2.composite), 0.5);
  EXPECT_GT(std::log2(e2.composite / e3.composite), 0.5);
  EXPECT_LT(e3.all, 4e-3);
}

// The front tracker's Riemann solver takes each family's waves to be shocks on one side and fans
// on the other: it would put one shock where this law makes a fan with a shock attached, with
// no error booked. The scene is refused for it when loaded, at the table, naming the inflection
// nearest to s = 1 (σ'' = 0 at ε = π/(2k), s = 1.105, where c_s also bends: g changes sign
// between s = 1.0 and 1.2) and what runs the law.
TEST(FiniteVolumeNonconvex, TheFrontTrackerRefusesTheLawWhenTheSceneLoads) {
  try {
    (void)load_scene_string(composite_scene("{method: characteristics, tolerance: 1e-4}"), "<test>");
    FAIL() << "a law with inflections was loaded for the front tracker";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "materials.sine.table") << e.what();
    const std::string message = e.message();
    EXPECT_NE(message.find(": not convex: the genuine nonlinearity"), std::string::npos) << message;
    EXPECT_NE(message.find("solver.method: finite_volume"), std::string::npos) << message;
    const std::size_t at = message.find("at s = ");
    ASSERT_NE(at, std::string::npos) << message;
    const double s = std::stod(message.substr(at + 7));
    EXPECT_GT(s, 1.0) << message;
    EXPECT_LT(s, 1.2) << message;
  }
  // The finite-volume solver takes the same scene.
  EXPECT_NO_THROW((void)load_scene_string(composite_scene("{method: finite_volume, cells: 100}"), "<test>"));
}

}  // namespace
}  // namespace rigidity
