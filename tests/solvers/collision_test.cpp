// Bodies meeting bodies: a two-material collision against its exact Riemann
// solution, spall of the rigid fluid against the rigid solid, and the shock tube
// of the constant-sound-speed fluid converging as solver.tolerance shrinks. The
// exact solutions are the independent references of tests/exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "error_bound.hpp"
#include "exact/flyer_plate.hpp"
#include "exact/profile.hpp"
#include "exact/riemann.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

RunResult run_yaml(const std::string& yaml, Scene* scene_out = nullptr) {
  Scene scene = load_scene_string(yaml, "<test>");
  RunResult r = solve(scene);
  if (scene_out != nullptr) *scene_out = std::move(scene);
  return r;
}

std::size_t count_events(const RunResult& r, const std::string& kind) {
  return static_cast<std::size_t>(
      std::count_if(r.events.begin(), r.events.end(), [&](const RunEvent& e) { return e.kind == kind; }));
}

TEST(Collision, RigidBarOnHookeBarMatchesTheExactRiemannSolution) {
  // Rigid (ρ00 = 1) at v = 0.5 across a gap of 0.1 onto hooke (ρ00 = 2, V = 0.5) at rest.
  const std::string yaml = R"(
name: two_materials
materials:
  solid: {model: rigid, rest_density: 1.0}
  soft: {model: hooke, rest_density: 2.0, wave_speed: 0.5}
bodies:
  - {name: flyer, material: solid, position: 0.0, length: 1.0, velocity: 0.5}
  - {name: target, material: soft, position: 0.966025403784438, length: 1.0, velocity: 0.0}
time: {end: 0.8}
outputs:
  probes:
    - {name: face, body: target, at: left, quantities: [p, v], every: 0.01}
)";
  const RunResult r = run_yaml(yaml);
  // Contact when the flyer's front (lab length sqrt(1 − 0.25) = 0.8660...) has crossed the gap 0.1.
  ASSERT_GE(count_events(r, "contact"), 1u);
  EXPECT_NEAR(r.events.front().t, 0.1 / 0.5, 1e-12);

  const auto flyer = exact::rigid(1.0);
  const auto target = exact::hooke(2.0, 0.5);
  const exact::Solution<double> exact =
      exact::riemann_problem<double>(flyer, {std::atanh(0.5), 1.0}, target, {0.0, 1.0}, 0.0);
  const double p_star = exact.pressure, v_star = exact::velocity(exact.right.star);

  double p_face = 0.0, v_face = 0.0;
  for (const ProbeSample& s : r.probes) {
    if (std::abs(s.t - 0.3) > 1e-9) continue;
    (s.quantity == Quantity::p ? p_face : v_face) = s.value;
  }
  EXPECT_NEAR(p_face, p_star, 1e-12 * p_star);
  EXPECT_NEAR(v_face, v_star, 1e-12 * v_star);
  // Free bodies: momentum and energy are conserved exactly.
  const Conservation& c = r.conservation;
  EXPECT_NEAR(c.momentum_final, c.momentum_initial, 1e-12 * c.momentum_initial);
  EXPECT_NEAR(c.energy_final, c.energy_initial, 1e-12 * c.energy_initial);
  EXPECT_EQ(c.wall_impulse, 0.0);
}

std::string flyer_plate(const std::string& model) {
  return R"(
name: flyer_plate
materials:
  m: {model: )" +
         model + R"(}
bodies:
  - {name: flyer, material: m, position: 0.0, length: 0.5, velocity: 0.3}
  - {name: target, material: m, position: 0.5, length: 1.0, velocity: -0.3}
time: {end: 3.0}
)";
}

TEST(Collision, FlyerPlateSpallsInTheRigidFluidButNotInTheRigidSolid) {
  // Two plates collide head on. The release waves from the free rear faces meet
  // inside the thick plate and put it in tension: the solid carries it, the
  // rigid fluid cavitates there and parts.
  const RunResult solid = run_yaml(flyer_plate("rigid"));
  const RunResult fluid = run_yaml(flyer_plate("rigid_fluid"));
  EXPECT_EQ(count_events(solid, "cavitation"), 0u);
  EXPECT_GE(count_events(fluid, "cavitation"), 1u);
  // The fluid parts where and when the two release waves meet (closed form: every front at ±c).
  const exact::FlyerPlateMeeting meeting = exact::symmetric_flyer_plate(0.0, 0.5, 0.5, 1.0, 0.3);
  ASSERT_TRUE(meeting.valid);
  const auto spall = std::find_if(fluid.events.begin(), fluid.events.end(), [](const RunEvent& e) {
    return e.kind == "cavitation" && e.bodies == std::vector<std::string>{"target"};
  });
  ASSERT_NE(spall, fluid.events.end());
  EXPECT_NEAR(spall->t, meeting.t_meet, 1e-12);
  EXPECT_NEAR(spall->x, meeting.x_meet, 1e-12);
  EXPECT_NEAR(fluid.events.front().t, meeting.t_contact, 1e-12);
  bool parted = false;
  for (const BodyResult& b : fluid.bodies) parted = parted || b.name == "target.2";
  EXPECT_TRUE(parted);
  for (const RunResult* r : {&solid, &fluid}) {
    const Conservation& c = r->conservation;
    EXPECT_NEAR(c.momentum_final, c.momentum_initial, 1e-12 * std::abs(c.energy_initial));
    EXPECT_NEAR(c.energy_final, c.energy_initial, 1e-12 * c.energy_initial);
    EXPECT_EQ(c.energy_dissipated, 0.0);
  }
}

TEST(Collision, ASnapshotOfAPartedBodyFindsWhatAProbeAtEachLabelFinds) {
  // Snapshots are filled by one walk along a body's pieces and nodes; probes look each
  // label up alone. After the rigid-fluid target has parted, every probe label on the
  // snapshot's grid (its ends, either side of the crack) must read the same p, v and x.
  const std::string labels[] = {"0.0", "0.25", "0.5", "0.745", "1.0"};
  std::string outputs =
      "outputs:\n  snapshots: [{times: [1.5, 3.0], samples: 201, quantities: [p, v, x]}]\n  probes:\n";
  for (const std::string& X : labels)
    outputs += "    - {name: p" + std::to_string(outputs.size()) + ", body: target, at: " + X +
               ", quantities: [p, v, x], every: 1.5}\n";
  Scene scene;
  const RunResult r = run_yaml(flyer_plate("rigid_fluid") + outputs, &scene);
  ASSERT_GE(count_events(r, "cavitation"), 1u);
  int target = -1;
  for (std::size_t b = 0; b < r.body_names.size(); ++b)
    target = r.body_names[b] == "target" ? static_cast<int>(b) : target;
  ASSERT_GE(target, 0);
  int compared = 0;
  for (const ProbeSample& probe : r.probes) {
    if (probe.t == 0.0) continue;
    const double X = scene.outputs.probes[static_cast<std::size_t>(probe.probe)].X;
    const auto same = std::find_if(r.snapshots.begin(), r.snapshots.end(), [&](const SnapshotSample& s) {
      return s.t == probe.t && s.body == target && std::abs(s.X - X) < 1e-12 && s.quantity == probe.quantity;
    });
    ASSERT_NE(same, r.snapshots.end()) << "X = " << X << " t = " << probe.t;
    EXPECT_EQ(same->value, probe.value) << "X = " << X << " t = " << probe.t;
    ++compared;
  }
  EXPECT_EQ(compared, 2 * 5 * 3);
}

std::string cradle(double tolerance) {
  // A flyer of length 1e-4 knocks a piece as long as itself off the target's free rear
  // face (Newton's cradle: the release waves from both rear faces meet 1e-4 inside it, and
  // the rigid fluid parts there: the sliver flies off at +v, the rest goes on at −v).
  char yaml[512];
  std::snprintf(yaml, sizeof yaml, R"(
name: cradle
materials:
  m: {model: rigid_fluid}
bodies:
  - {name: flyer, material: m, position: 0.0, length: 1.0e-4, velocity: 0.3}
  - {name: target, material: m, position: 0.001, length: 0.5, velocity: -0.3}
solver: {tolerance: %.17g}
time: {end: 3.0}
)",
                tolerance);
  return yaml;
}

TEST(Collision, ASliverLongerThanTheToleranceBreaksOffExactly) {
  // ℓ_min = tolerance × 0.5 = 5e-6 < 1e-4: the crack opens where the closed form puts it.
  const RunResult r = run_yaml(cradle(1e-5));
  const exact::FlyerPlateMeeting meeting = exact::symmetric_flyer_plate(0.0, 1e-4, 0.001, 0.5, 0.3);
  ASSERT_TRUE(meeting.valid);
  ASSERT_EQ(count_events(r, "cavitation"), 1u);
  const auto spall =
      std::find_if(r.events.begin(), r.events.end(), [](const RunEvent& e) { return e.kind == "cavitation"; });
  EXPECT_NEAR(spall->t, meeting.t_meet, 1e-12);
  EXPECT_NEAR(spall->x, meeting.x_meet, 1e-12);
  ASSERT_EQ(r.bodies.size(), 3u);
  EXPECT_NEAR(r.bodies[1].velocity_mean, -0.3, 1e-12);  // target.1
  EXPECT_NEAR(r.bodies[2].velocity_mean, 0.3, 1e-12);   // target.2, the sliver
  EXPECT_EQ(solver_number(r, "droplets"), 0.0);
  EXPECT_EQ(solver_number(r, "error_bound"), 0.0);
  const Conservation& c = r.conservation;
  EXPECT_NEAR(c.momentum_final, c.momentum_initial, 1e-12);
}

TEST(Collision, ASliverShorterThanTheToleranceStaysWithItsPieceAndIsBooked) {
  // ℓ_min = 1e-3 × 0.5 > 1e-4: no crack; the sliver takes the state the rest is released
  // to (unstrained, −v instead of +v). Its length times the rapidity it lost is the error
  // booked (mean over the bodies' length 0.5001, times the stability factor 2), and the
  // momentum it lost, 2 ρ00 γ v × 1e-4, is booked as the droplets' share of the balance.
  const RunResult r = run_yaml(cradle(1e-3));
  EXPECT_EQ(count_events(r, "cavitation"), 0u);
  ASSERT_EQ(r.bodies.size(), 2u);
  EXPECT_EQ(r.bodies[1].name, "target");
  EXPECT_NEAR(r.bodies[1].velocity_mean, -0.3, 1e-12);
  EXPECT_NEAR(r.bodies[0].velocity_mean, -0.3, 1e-12);
  EXPECT_EQ(solver_number(r, "droplets"), 1.0);
  const double sliver = 1e-4, lost = 2.0 * std::atanh(0.3);
  EXPECT_NEAR(solver_number(r, "error_droplets"), sliver * lost / 0.5001, 1e-9 * sliver);
  EXPECT_NEAR(solver_number(r, "error_bound"), 2.0 * sliver * lost / 0.5001, 1e-9 * sliver);
  const Conservation& c = r.conservation;
  const double lost_momentum = 2.0 * 0.3 / std::sqrt(1.0 - 0.09) * sliver;
  EXPECT_NEAR(c.momentum_initial - c.momentum_final, lost_momentum, 1e-9 * lost_momentum);
  EXPECT_NEAR(c.momentum_droplets, -lost_momentum, 1e-9 * lost_momentum);
  EXPECT_NEAR(c.momentum_final - c.momentum_initial - c.momentum_droplets, 0.0, 1e-15);
  EXPECT_NEAR(c.energy_final, c.energy_initial, 1e-12);
  EXPECT_NEAR(c.energy_droplets, 0.0, 1e-15);  // unstrained at −v instead of +v: the same energy
}

TEST(Collision, ASprayAtAFineToleranceKeepsNoMorePiecesThanAtACoarseOne) {
  // Three rigid-fluid bodies knocked apart between a wall and a rigid rod, a gas bar and a
  // rod in segments (random scene 35 to t = 8) at tolerance 1e-6: the spray's error does not
  // fall with the tolerance, and a body is held to at most 100 pieces (what a tolerance of
  // 2e-4 gives) by letting its droplets grow; at 0.02/tolerance it would keep 20 000, and here
  // holds 148 by t = 8.
  const RunResult r = run_yaml(R"(
name: random_35
materials:
  m0: {model: rigid_fluid, rest_density: 2.326}
  m1: {model: rigid_fluid, rest_density: 1.466}
  m2: {model: rigid_fluid, rest_density: 2.063}
  m3: {model: rigid, rest_density: 1.284}
  m4: {model: constant_sound_speed, rest_density: 1.311, sound_speed: 0.706}
  m5: {model: rigid, rest_density: 0.363}
bodies:
  - {name: b0, material: m0, position: 0.0000, length: 0.8793, velocity: 0.0652}
  - {name: b1, material: m1, position: 1.0112, length: 0.7997, velocity: 0.0765}
  - {name: b2, material: m2, position: 1.9309, length: 1.5429, velocity: -0.0595}
  - {name: b3, material: m3, position: 3.7053, length: 1.3521, velocity: -0.4644}
  - {name: b4, material: m4, position: 5.4025, length: 1.2431, velocity: -0.4550}
  - {name: b5, material: m5, position: 6.8320, segments: [{length: 0.1745, velocity: 0.0096, stretch: 0.9827}, {length: 0.1745, velocity: -0.0076, stretch: 0.9279}, {length: 0.1745, velocity: -0.0174, stretch: 0.9158}, {length: 0.1745, velocity: 0.0029, stretch: 1.0940}, {length: 0.1745, velocity: -0.0739, stretch: 1.0496}]}
boundaries:
  left: {type: wall}
  right: {type: free}
solver: {method: characteristics, tolerance: 1e-06}
time: {end: 8}
)");
  ASSERT_EQ(r.status, "ok");
  std::map<std::string, int> pieces;
  for (const BodyResult& b : r.bodies) ++pieces[b.name.substr(0, b.name.find('.'))];
  ASSERT_EQ(pieces.size(), 6u);
  EXPECT_GT(pieces["b2"], 1);  // a spray
  for (const auto& [body, count] : pieces) EXPECT_LE(count, 100) << body;
  EXPECT_GT(solver_number(r, "droplets"), 0.0);
  EXPECT_GT(solver_number(r, "error_droplets"), 0.0);
}

// ---- the shock tube of the constant-sound-speed fluid --------------------------------

std::string shock_tube(double tolerance, double t_end) {
  char yaml[1024];
  std::snprintf(yaml, sizeof yaml, R"(
name: shock_tube
materials:
  gas: {model: constant_sound_speed, sound_speed: 0.5}
bodies:
  - name: tube
    material: gas
    segments:
      - {length: 0.5, velocity: 0.0, stretch: 0.5}
      - {length: 0.5, velocity: 0.0, stretch: 1.0}
boundaries:
  left: {type: wall}
  right: {type: wall}
solver: {tolerance: %.17g, resolution: tolerance}
time: {end: %.17g}
outputs:
  snapshots:
    - {times: [%.17g], quantities: [s], samples: 4001}
)",
                tolerance, t_end, t_end);
  return yaml;
}

double shock_tube_error(double tolerance) {
  const RunResult r = run_yaml(shock_tube(tolerance, 0.3));
  // The exact solution: a C− fan and a C+ shock from the jump at X = 0.5, before either
  // reaches a wall.
  const auto gas = exact::constant_sound_speed(1.0, 0.5);
  const exact::Solution<double> sol = exact::riemann_problem<double>(gas, {0.0, 0.5}, gas, {0.0, 1.0});
  const exact::Profile profile = exact::solution_profile(sol, 0.5, 0.3, 0.0, 1.0);
  double error = 0.0;
  int n = 0;
  for (const SnapshotSample& s : r.snapshots) {
    error += std::abs(s.value - exact::stretch_at(profile, s.X));
    ++n;
  }
  EXPECT_EQ(n, 4001);
  EXPECT_EQ(solver_number(r, "error_bound"), 0.0) << "tolerance " << tolerance;
  return error / n;  // L1 over X in [0, 1]
}

TEST(ShockTube, IsExactWhileItsFanIsUncrossed) {
  // The fan's steps stand for the exact centred fan until one of them interacts: at any
  // tolerance the samples are the exact solution's (tests/exact) to round-off.
  for (double tolerance : {0.04, 0.02, 0.01}) EXPECT_LT(shock_tube_error(tolerance), 1e-13) << tolerance;
}

TEST(ShockTube, ConvergesWithTheToleranceOnceItsFanIsCrossed) {
  // By t = 2 the fan has reflected off the left wall and crossed the shock's reflection:
  // from then on its steps carry the solution, reconstructed between them, whose error falls
  // with the step, 0.7 √tolerance. Against a run at a much smaller tolerance (itself within
  // its bound of the truth).
  const RunResult fine = run_yaml(shock_tube(1e-8, 2.0));
  std::vector<double> errors;
  for (double tolerance : {4e-4, 1e-4, 2.5e-5}) {
    const RunResult r = run_yaml(shock_tube(tolerance, 2.0));
    ASSERT_EQ(r.snapshots.size(), fine.snapshots.size());
    double error = 0.0;
    for (std::size_t k = 0; k < r.snapshots.size(); ++k)
      error += std::abs(r.snapshots[k].value - fine.snapshots[k].value);
    errors.push_back(error / static_cast<double>(r.snapshots.size()));
    EXPECT_LT(errors.back(), solver_number(r, "error_bound")) << "tolerance " << tolerance;
    EXPECT_GT(solver_number(r, "error_fans"), 0.0) << "the fan was crossed: its steps book their error";
  }
  // Quartered, the tolerance halves the step: the error falls at least twice (measured 2.2
  // and 2.8: as the step's square where the fan crossed only itself, more slowly where it
  // crossed the reflected shock, whose path meets it step by step).
  EXPECT_GT(std::log2(errors[0] / errors[1]), 1.0) << errors[0] << " " << errors[1];
  EXPECT_GT(std::log2(errors[1] / errors[2]), 1.0) << errors[1] << " " << errors[2];
}

}  // namespace
}  // namespace rigidity
