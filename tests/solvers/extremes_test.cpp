// Extreme Lorentz factors, tiny impacts and long runs, against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

RunResult run_yaml(const std::string& yaml) { return solve(load_scene_string(yaml, "<test>")); }

/// A rigid bar of natural length 1 given by its rapidity, against a wall at its right end.
std::string rigid_wall_impact(double rapidity, double t_end, double every) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, R"(
name: extreme
materials: {m: {model: rigid}}
bodies: [{name: bar, material: m, length: 1.0, rapidity: %.17g}]
boundaries: {left: {type: free}, right: {type: wall}}
time: {end: %.17g}
outputs:
  probes: [{name: wall, body: bar, at: right, quantities: [p, s], every: %.17g}]
)",
                rapidity, t_end, every);
  return buf;
}

TEST(Extremes, UltraRelativisticImpactKeepsPressureAndContactTime) {
  // v = 1 − 1e-12, γ ≈ 7.07e5: s = e^−φ, p = (e^{2φ} − 1)/2, contact 2 s. Carried as
  // rapidity throughout, never as 1 − v.
  const double phi = std::atanh(1.0 - 1e-12);
  const double s = std::exp(-phi), p = 0.5 * std::expm1(2.0 * phi), contact = 2.0 * s;
  const RunResult r = run_yaml(rigid_wall_impact(phi, 1.5 * contact, contact / 8.0));
  double p_max = 0.0;
  for (const ProbeSample& sample : r.probes)
    if (sample.quantity == Quantity::p) p_max = std::max(p_max, sample.value);
  EXPECT_NEAR(p_max / p, 1.0, 1e-9);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].kind, "separation");
  EXPECT_NEAR(r.events[0].t / contact, 1.0, 1e-9);
  EXPECT_NEAR(r.bodies[0].velocity_mean, -(1.0 - 1e-12), 1e-15);
  EXPECT_NEAR(r.conservation.energy_final / r.conservation.energy_initial, 1.0, 1e-12);
}

TEST(Extremes, TinyImpactHasNoCancellation) {
  // v = 1e-9: p = (1/s² − 1)/2 = v/(1 − v) exactly, s − 1 ≈ −v.
  const double v = 1e-9;
  const RunResult r = run_yaml(rigid_wall_impact(std::atanh(v), 3.0, 0.25));
  double p_max = 0.0;
  for (const ProbeSample& sample : r.probes)
    if (sample.quantity == Quantity::p) p_max = std::max(p_max, sample.value);
  EXPECT_NEAR(p_max / (v / (1.0 - v)), 1.0, 1e-12);
  EXPECT_NEAR(r.bodies[0].velocity_mean / -v, 1.0, 1e-12);
}

// A gas bar (constant_sound_speed, V = 0.3, ρ00 = 1) into a wall at γ = 22360.68 (1 − v = 1e-9):
// the shock stands almost still in the lab while the bar runs into it at nearly c. Its lab
// speed U from the conservation of particles and momentum across it, in the wall's frame,
// written here: n γ (U − v) = U/s* and −U γ² v = p* − γ² v² (the bar: e = 1, p = 0; behind:
// at rest, p* = V²/(1 + V²)(s*^−(1+V²) − 1)), so U = γ v/(γ − 1/s*), and s* by bisection in
// ln s*. The shock meets the free rear end (x = v t, from 0) at t1 = x0/(v − U). Its speed is
// a small difference of nearly opposite terms on the bar's side; from the star's side it is not.
TEST(Extremes, AShockIntoABarNearLightSpeedRunsAtItsSpeedToFullPrecision) {
  const double gamma = 22360.68, v = std::sqrt((1.0 - 1.0 / gamma) * (1.0 + 1.0 / gamma));
  const double V2 = 0.09;
  const auto lab_speed = [&](double log_s) { return gamma * v / (gamma - std::exp(-log_s)); };
  const auto excess = [&](double log_s) {  // p(s*) less what the momentum condition asks: falls as s* grows
    return V2 / (1.0 + V2) * std::expm1(-(1.0 + V2) * log_s) - gamma * gamma * v * (v - lab_speed(log_s));
  };
  double lo = -40.0, hi = -5.0;
  for (int it = 0; it < 200; ++it) (excess(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double U = lab_speed(0.5 * (lo + hi));
  ASSERT_NEAR(U, -2.3715519624e-5, 1e-14);
  const RunResult r = run_yaml(R"(
name: extreme_gas
materials: {gas: {model: constant_sound_speed, sound_speed: 0.3}}
bodies: [{name: bar, material: gas, position: 0.0, length: 1.0, gamma: 22360.68}]
boundaries: {right: {type: wall}}
solver: {tolerance: 1e-4}
time: {end: 5e-5}
outputs: {fronts: true}
)");
  ASSERT_EQ(r.status, "ok");
  const FrontSegment* shock = nullptr;
  for (const FrontSegment& f : r.fronts)
    if (f.t0 == 0.0 && f.family == -1) shock = &f;
  ASSERT_NE(shock, nullptr);
  const double x0 = shock->x0;  // the bar's lab length
  EXPECT_NEAR(x0, 1.0 / gamma, 1e-15 / gamma);
  EXPECT_NEAR(shock->t1 / (x0 / (v - U)), 1.0, 1e-13);
  EXPECT_NEAR((shock->x1 - shock->x0) / shock->t1 / U, 1.0, 1e-9);
  // The books close, of 22360 and 22366 in the balance (the shock dissipates all but 5.9 of the
  // energy, its dissipation to about 1e-11 of it).
  EXPECT_NEAR(r.conservation.momentum_residual(), 0.0, 1e-8);
  EXPECT_NEAR(r.conservation.energy_residual() / r.conservation.energy_initial, 0.0, 1e-10);
}

// The same bar (V = 0.1) at γ = 1e20: compressed to about 1e-40 of its natural length while the
// impact happens at t ≈ 1e-20, so its two ends meet to the last digit of time and position. The
// run stops, naming the body and why, rather than going on with books that do not close.
TEST(Extremes, ACompressionBeyondDoublePrecisionStopsNamingTheBody) {
  try {
    (void)run_yaml(R"(
name: beyond
materials: {gas: {model: constant_sound_speed, sound_speed: 0.1}}
bodies: [{name: slug, material: gas, position: 0.0, length: 1.0, gamma: 1e20}]
boundaries: {right: {type: wall}}
time: {end: 1e-3}
)");
    ADD_FAILURE() << "no error";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("body 'slug'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("double precision"), std::string::npos) << e.what();
  }
}

TEST(LongRuns, BarBouncingBetweenWallsForAHundredThousandTimeUnits) {
  const RunResult r = run_yaml(R"(
name: bouncing
materials: {m: {model: hooke, wave_speed: 0.7}}
bodies: [{name: bar, material: m, position: 0.0, length: 1.0, velocity: 0.6}]
boundaries:
  left: {type: wall, position: -1.0}
  right: {type: wall, position: 2.0}
time: {end: 1.0e5}
)");
  const Conservation& c = r.conservation;
  EXPECT_NEAR(c.energy_final / c.energy_initial, 1.0, 1e-10);
  EXPECT_NEAR(c.momentum_final - c.momentum_initial, c.wall_impulse, 1e-10 * std::abs(c.wall_impulse));
  // The motion is periodic: flights of 2.2/0.6 across the gap (walls 3 apart, the
  // bar 0.8 long in the lab) and contacts of τ = 2 sqrt(V² s² + 1 − V²)/V, with s
  // behind the front from Ψ(s) = artanh(0.6). Contact k starts at 2 + k (τ + flight).
  const double b = 0.7, a = std::sqrt(1.0 - b * b);
  const double s = a / b * std::sinh(std::asinh(b / a) - std::atanh(0.6));
  const double tau = 2.0 * std::sqrt(b * b * s * s + a * a) / b, flight = 2.2 / 0.6;
  ASSERT_GT(r.events.size(), 10000u);  // a contact and a separation per bounce
  long k = 0;
  for (const RunEvent& e : r.events) {
    if (e.kind != "contact") continue;
    EXPECT_NEAR(e.t, 2.0 + static_cast<double>(k) * (tau + flight), 1e-9 * e.t) << "contact " << k;
    if (std::abs(e.t - (2.0 + static_cast<double>(k) * (tau + flight))) > 1e-9 * e.t) break;
    ++k;
  }
  EXPECT_GT(k, 5000);
  EXPECT_LT(r.stats.fronts, 20 * static_cast<long>(r.events.size()));
}

TEST(LongRuns, ManySegmentsRingingBetweenBondedWallsConserveEnergy) {
  std::string yaml =
      "name: ringing\nmaterials: {m: {model: rigid}}\nbodies:\n  - name: bar\n    material: m\n    segments:\n";
  for (int i = 0; i < 300; ++i) {
    char line[128];
    std::snprintf(line, sizeof line, "      - {length: 0.01, velocity: %g, stretch: %g}\n", 0.3 * std::sin(0.1 * i),
                  1.0 + 0.2 * std::cos(0.37 * i));
    yaml += line;
  }
  yaml += "boundaries: {left: {type: wall, bonded: true}, right: {type: wall, bonded: true}}\ntime: {end: 20.0}\n";
  const RunResult r = run_yaml(yaml);
  const Conservation& c = r.conservation;
  // A rigid bar is a light piece: its 600 fronts run from end to end (the bar is 3 long: about
  // 7 times each by t = 20) without visiting their 10⁶ crossings.
  EXPECT_GT(r.stats.interactions, 3000);
  EXPECT_LT(r.stats.interactions, 10000);
  EXPECT_NEAR(c.energy_final / c.energy_initial, 1.0, 1e-10);
  EXPECT_NEAR(c.momentum_final - c.momentum_initial, c.wall_impulse, 1e-10 * c.energy_initial);
  EXPECT_EQ(c.energy_dissipated, 0.0);
}

}  // namespace
}  // namespace rigidity
