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
#include "rigidity/solvers/riemann.hpp"
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

/// Two uniform states of the bar, either side of X = 0.5.
struct Sides {
  double stretch_left = 1.3, velocity_left = 0.0, stretch_right = 0.7, velocity_right = 0.0;
  double half = 0.5;                        ///< the natural length of either side
  const char* ends = "wall, bonded: true";  ///< both boundaries
};

/// The bar of l0 = 2 × sides.half with the two states of `sides` (by default l0 = 1, stretched,
/// s = 1.3, left of the middle and compressed, s = 0.7, right of it, at rest, between bonded walls),
/// to t = 0.25 (no wave from an end reaches the middle's); s and v sampled at 2001 labels.
std::string composite_scene(const std::string& solver, const Sides& sides = {}) {
  char segments[512];
  std::snprintf(segments, sizeof segments,
                "      - {length: %.17g, velocity: %.17g, stretch: %.17g}\n"
                "      - {length: %.17g, velocity: %.17g, stretch: %.17g}\n"
                "boundaries: {left: {type: %s}, right: {type: %s}}\n",
                sides.half, sides.velocity_left, sides.stretch_left, sides.half, sides.velocity_right,
                sides.stretch_right, sides.ends, sides.ends);
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
)yaml" + segments +
         R"yaml(solver: )yaml" + solver +
         R"yaml(
time: {end: 0.25}
outputs:
  snapshots: [{times: [0.25], quantities: [s, v], samples: 2001}]
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

/// The composite scene with the law as a formula (Chebyshev tables of the expression, within
/// ~1e-12 of it) for the front tracker.
RunResult run_tracker(double tolerance, const Sides& sides = {}, const std::string& formula = {}) {
  std::string scene = composite_scene("{method: characteristics, tolerance: " + std::to_string(tolerance) + "}", sides);
  const std::size_t from = scene.find("  sine:\n"), to = scene.find("bodies:");
  char law[256];
  std::snprintf(law, sizeof law,
                "  sine:\n    model: formula\n    pressure: \"-%.17g*((s - 1) + %.17g*(1 - cos(%.17g*(s - 1))))\"\n"
                "    min_stretch: 0.5\n    max_stretch: 1.6\n",
                kE, kA / kK, kK);
  scene.replace(from, to - from, formula.empty() ? std::string(law) : "  sine:\n" + formula);
  return solve(load_scene_string(scene, "<test>"));
}

/// The largest |Δs| and |Δφ| between a run's samples and the exact solution.
struct Misses {
  double stretch = 0.0, rapidity = 0.0;
};
Misses misses(const RunResult& r, const nc::Solution& exact, double middle) {
  Misses out;
  int n = 0;
  for (const SnapshotSample& sample : r.snapshots) {
    const double xi = (sample.X - middle) / 0.25;
    if (std::abs(xi) > 1.6) continue;  // beyond the waves of the middle (none is faster than 1.3)
    const nc::State e = exact.at(xi);
    if (sample.quantity == Quantity::s) {
      out.stretch = std::max(out.stretch, std::abs(sample.value - e.stretch));
      ++n;
    } else if (sample.quantity == Quantity::v) {
      out.rapidity = std::max(out.rapidity, std::abs(std::atanh(sample.value) - e.rapidity));
    }
  }
  EXPECT_GT(n, 500);
  return out;
}

// The front tracker builds composite waves as Liu's condition does: a fan with a shock attached at
// its sonic point, and sequences of them across several inflections (up to five pieces), their
// pieces at the speeds and states of the independent construction. The law is a formula; samples
// at 2001 labels against the exact solution of the law itself, whose shocks are placed to round-off
// too, so no sample lies between a shock and where the exact one puts it. The same at any
// tolerance: nothing here is approximated (a fan nothing crosses is sampled as the exact centred
// wave). Measured, the same at 1e-3 and 1e-6: max |Δs|, |Δφ| 1.2e-13, 6.5e-14 (S | RS and RS | S),
// 8.7e-12, 1.5e-10 (RSRS | SR), 4.7e-12, 6.3e-12 (SRSRS | R), 4.1e-10, 3.0e-10 (SRS | SRS), 2.5e-11,
// 3.2e-11 (RS | SRS): the formula's Chebyshev table of Ψ, whose differences along a fan of this
// law (c_s bends every 0.1 in stretch) miss the quadrature of c_s/s by up to 1e-8, not the
// construction (its shocks are sonic where attached to round-off: chord and characteristic
// speeds equal to 1e-15).
TEST(FrontTrackerNonconvex, RiemannProblemsGiveTheCompositeWavesOfLiusCondition) {
  const nc::Law law = sine_law();
  // A bar of l0 = 2 with free ends: the end's waves (composite too, where a side is stretched
  // across an inflection) stay 0.4 away from the middle's at t = 0.25.
  const double half = 1.0;
  const char* free = "free";
  for (const Sides& c : {Sides{1.3, 0.0, 0.7, 0.0, half, free}, Sides{0.7, 0.0, 1.3, 0.0, half, free},
                         Sides{1.45, 0.1, 0.65, -0.1, half, free}, Sides{0.6, -0.3, 1.5, 0.1, half, free},
                         Sides{0.55, 0.0, 1.55, 0.0, half, free}, Sides{1.5, -0.1, 0.55, 0.1, half, free}}) {
    const nc::Solution exact = nc::riemann_problem(law, {std::atanh(c.velocity_left), c.stretch_left},
                                                   {std::atanh(c.velocity_right), c.stretch_right});
    ASSERT_TRUE(exact.solved);
    const std::string pattern = exact.left.pattern() + " | " + exact.right.pattern();
    SCOPED_TRACE(pattern);
    for (const double tolerance : {1e-3, 1e-6}) {
      const RunResult r = run_tracker(tolerance, c);
      const Misses m = misses(r, exact, half);
      std::printf("%-12s tolerance %g: max |ds| %.2g, max |dphi| %.2g, bound %.2g\n", pattern.c_str(), tolerance,
                  m.stretch, m.rapidity, r.solver_number("error_bound"));
      EXPECT_LT(m.stretch, 1e-9);
      EXPECT_LT(m.rapidity, 1e-9);
      EXPECT_EQ(r.solver_number("error_bound"), 0.0);
      EXPECT_EQ(r.status, "ok");
    }
  }
}

// Berjamin et al.'s tanh law, σ = E d tanh(ε/d), far from its Newtonian limit (E = 0.2 ρ00 c²,
// d = 0.1: c_s up to 0.45 c): convex in compression and concave in tension, so a compressed side
// against a stretched one makes a shock with a fan attached on one side. Against the independent
// construction at 2001 samples, the same at every tolerance. Measured: max |Δs|, |Δφ| 1.0e-14,
// 2.9e-15 (SR | R) and 6.2e-14, 1.3e-14 (R | SR). The finite-volume baseline converges to the
// same composite waves at first order: L1(s) over the waves 5.6e-3, 2.3e-3 (SR | R) and 5.8e-3,
// 2.6e-3 (R | SR) at 200, 800 cells.
TEST(FrontTrackerNonconvex, TheTanhLawGivesTheCompositeWavesOfLiusCondition) {
  constexpr double E = 0.2, d = 0.1;
  const nc::Law law([](double s) { return -E * d * std::tanh((s - 1.0) / d); },
                    [](double s) { return -E / std::pow(std::cosh((s - 1.0) / d), 2); }, 1.0, 0.75, 1.25,
                    [](double s) { return 1.0 + E * d * d * std::log(std::cosh((s - 1.0) / d)); });
  const std::string formula =
      "    model: formula\n    pressure: \"-0.02*tanh((s - 1)/0.1)\"\n"
      "    min_stretch: 0.75\n    max_stretch: 1.25\n";
  for (const Sides& sides : {Sides{0.85, -0.1, 1.1, 0.0, 1.0, "free"}, Sides{0.9, 0.1, 1.1, 0.0, 1.0, "free"}}) {
    const nc::Solution exact =
        nc::riemann_problem(law, {std::atanh(sides.velocity_left), sides.stretch_left}, {0.0, sides.stretch_right});
    ASSERT_TRUE(exact.solved);
    const std::string pattern = exact.left.pattern() + " | " + exact.right.pattern();
    SCOPED_TRACE(pattern);
    EXPECT_NE(pattern.find("SR"), std::string::npos);  // a shock with a fan attached
    for (const double tolerance : {1e-3, 1e-6}) {
      const RunResult r = run_tracker(tolerance, sides, formula);
      ASSERT_EQ(r.status, "ok");
      const Misses m = misses(r, exact, 1.0);
      std::printf("tanh %s tolerance %g: max |ds| %.2g, max |dphi| %.2g\n", pattern.c_str(), tolerance, m.stretch,
                  m.rapidity);
      EXPECT_LT(m.stretch, 1e-9);
      EXPECT_LT(m.rapidity, 1e-9);
      EXPECT_EQ(r.solver_number("error_bound"), 0.0);
    }
    double l1[2] = {0.0, 0.0};
    for (const int k : {0, 1}) {
      std::string scene = composite_scene(
          "{method: finite_volume, cells: " + std::to_string(k == 0 ? 200 : 800) + ", order: 1, flux: hll}", sides);
      const std::size_t from = scene.find("  sine:\n"), to = scene.find("bodies:");
      scene.replace(from, to - from, "  sine:\n" + formula);
      const RunResult r = solve(load_scene_string(scene, "<test>"));
      ASSERT_EQ(r.status, "ok");
      int n = 0;
      for (const SnapshotSample& sample : r.snapshots) {
        const double xi = (sample.X - 1.0) / 0.25;
        if (sample.quantity != Quantity::s || std::abs(xi) > 1.6) continue;
        l1[k] += std::abs(sample.value - exact.at(xi).stretch);
        ++n;
      }
      l1[k] /= n;
    }
    std::printf("tanh %s finite volume: L1(s) %.3g at 200 cells, %.3g at 800\n", pattern.c_str(), l1[0], l1[1]);
    EXPECT_LT(l1[1], 0.5 * l1[0]);
  }
}

// A tabulated law declares nothing either: the sine law as its table (rows every ln 2/700 in
// ln s, Steffen's interpolation within ~1e-8 of the law in p) runs S | RS by its composite waves,
// to the table's accuracy. Measured: max |Δs| 2.5e-6, |Δφ| 1.5e-6 at 1e-3 and 1e-6 alike.
TEST(FrontTrackerNonconvex, ATabulatedLawFindsItsInflectionsAndRunsTheCompositeWave) {
  const nc::Law law = sine_law();
  const nc::Solution exact = nc::riemann_problem(law, {0.0, 1.3}, {0.0, 0.7});
  ASSERT_TRUE(exact.solved);
  for (const double tolerance : {1e-3, 1e-6}) {
    const RunResult r = solve(load_scene_string(
        composite_scene("{method: characteristics, tolerance: " + std::to_string(tolerance) + "}"), "<test>"));
    ASSERT_EQ(r.status, "ok");
    const Misses m = misses(r, exact, 0.5);
    EXPECT_LT(m.stretch, 1e-5);
    EXPECT_LT(m.rapidity, 1e-5);
    EXPECT_EQ(r.solver_number("error_bound"), 0.0);
  }
}

}  // namespace
}  // namespace rigidity
