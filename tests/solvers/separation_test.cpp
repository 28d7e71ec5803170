// Contacts that push but do not pull (docs/physics.md): bodies separate exactly when the contact
// pressure would become negative. The paper's rebound after 2·t1 = 2·l0·s between two bars,
// and the exact Riemann solver's parting rule for every material of the registry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "exact/registry_samples.hpp"
#include "exact/riemann.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

std::vector<const RunEvent*> events_of(const RunResult& r, const std::string& kind) {
  std::vector<const RunEvent*> out;
  for (const RunEvent& e : r.events)
    if (e.kind == kind) out.push_back(&e);
  return out;
}

std::string two_bars(const std::string& material, double v, double gap) {
  // Two equal bars of natural length 1 at ±v, their facing ends `gap` apart.
  const double lab_length = std::sqrt((1.0 - v) * (1.0 + v));
  char buf[1024];
  std::snprintf(buf, sizeof buf, R"(
name: two_bars
materials: {m: %s}
bodies:
  - {name: left, material: m, position: 0.0, length: 1.0, velocity: %.17g}
  - {name: right, material: m, position: %.17g, length: 1.0, velocity: %.17g}
time: {end: 4.0}
)",
                material.c_str(), v, lab_length + gap, -v);
  return buf;
}

TEST(Separation, EqualBarsPartAfterTwiceTheTransitTimeOfThePaper) {
  // A symmetric collision is a wall impact for each bar: the front crosses the stopped,
  // compressed bar, the release from the free rear crosses it back, and when it reaches the
  // contact the pressure there would turn negative: the bars part, each unstrained at ∓v.
  // For `rigid` the contact lasts 2 t1 = 2 l0 s with s = sqrt((1 − v)/(1 + v)) (paper,
  // footnote 2); for any material, l0/|m_front| + l0/|m_release| of the exact waves.
  struct Case {
    std::string yaml;
    exact::ClosedFormLaw<double> law;
  };
  const std::vector<Case> cases = {{"{model: rigid}", exact::rigid(1.0)},
                                   {"{model: hooke, wave_speed: 0.7, rest_density: 2.0}", exact::hooke(2.0, 0.7)}};
  const double v = 0.6, gap = 0.12;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.yaml);
    const RunResult r = solve(load_scene_string(two_bars(c.yaml, v, gap), "<test>"));
    const exact::Solution<double> hit =
        exact::wall_problem<double>(c.law, {std::atanh(v), 1.0}, exact::Side::left, 0.0, 0.0);
    const exact::Solution<double> release = exact::free_end_problem<double>(c.law, hit.left.star, exact::Side::right);
    const double t_contact = gap / (2.0 * v);
    const double duration = -1.0 / hit.left.front_speed() + 1.0 / release.right.front_speed();
    if (c.law.model() == exact::Model::rigid) {
      EXPECT_NEAR(duration, 2.0 * std::sqrt((1.0 - v) / (1.0 + v)), 1e-14);
    }
    const auto contacts = events_of(r, "contact"), separations = events_of(r, "separation");
    ASSERT_EQ(contacts.size(), 1u);
    ASSERT_EQ(separations.size(), 1u);
    EXPECT_NEAR(contacts[0]->t, t_contact, 1e-12);
    EXPECT_NEAR(separations[0]->t, t_contact + duration, 1e-12);
    EXPECT_EQ(separations[0]->bodies, (std::vector<std::string>{"left", "right"}));
    ASSERT_EQ(r.bodies.size(), 2u);
    EXPECT_NEAR(r.bodies[0].velocity_mean, -v, 1e-12);
    EXPECT_NEAR(r.bodies[1].velocity_mean, v, 1e-12);
  }
}

TEST(Separation, AReleaseToThePartingPressureWithinRoundOffHoldsTheContactWhicheverWayItRounds) {
  // A compressed side moving away from a push-only wall (or a body at rest) just fast enough that
  // the release leaves the contact at p = 0 and moving with the wall: Ψ* = J − φ_wall vanishes in
  // exact arithmetic and is a few ulps either way in floating point (J = φ + Ψ(s) with φ = −Ψ(s)
  // rounded). The contact carries no force and the side does not move away from it: it holds,
  // at p = 0 exactly, until a wave brings tension (as the cascade reference of
  // spray_reference_test.cpp has it), whichever way Ψ* rounds. (A nonlinear bar leaving a wall
  // meets this when a step of its release fan brings the wall to p = 0: a law as a formula and
  // as a plugin, the same to 1e-14, left the wall one step apart.)
  int cases = 0;
  for (const exact::MaterialSample& sample : exact::registry_samples()) {
    const Material& m = *sample.material;
    if (m.cavitation_pressure() > 0.0) continue;
    const Stretch s = Stretch::from_value(0.99);
    if (!m.admissible().contains(s)) continue;
    for (const double ulps : {-2.0, 0.0, 2.0}) {
      SCOPED_TRACE(sample.model + ", " + std::to_string(ulps) + " ulps");
      const double psi = m.riemann_psi(s);
      const State away{-psi * (1.0 + ulps * std::numeric_limits<double>::epsilon()), s};
      // (A law whose expansions are shocks releases through a shock, not along the invariant.)
      if (wave_is_shock(m, away, Stretch::natural(), -1)) continue;
      const RiemannSolution wall = solve_wall(m, away, Side::left, 0.0, 0.0);
      ASSERT_EQ(wall.status, Status::ok);
      EXPECT_FALSE(wall.parted);
      EXPECT_EQ(wall.pressure, 0.0);
      // Two bodies: the right one at rest, unstrained.
      const RiemannSolution bodies = solve_riemann(m, away, m, State{0.0, Stretch::natural()}, 0.0);
      ASSERT_EQ(bodies.status, Status::ok);
      EXPECT_FALSE(bodies.parted);
      EXPECT_NEAR(bodies.pressure, 0.0, 1e-15);
      ++cases;
    }
  }
  EXPECT_GT(cases, 6);
}

TEST(Separation, PushOnlyContactPartsExactlyWhenItsPressureWouldTurnNegativeForEveryMaterial) {
  // Two states meeting at a contact that cannot pull: bonded, the star pressure of the exact
  // reference is p*; pushing only, the sides part if and only if p* < 0, each relaxing to
  // p = 0 (a fluid's cavitation pressure if higher), and otherwise meet at p*.
  int parted = 0, held = 0;
  for (const exact::MaterialSample& sample : exact::registry_samples()) {
    const Material& m = *sample.material;
    const exact::MaterialLaw law(m);
    const double min_pressure = std::max(0.0, m.cavitation_pressure());
    for (double closing : {-0.02, -1e-4, 1e-4, 0.02}) {
      for (double stretch : {0.99, 1.0}) {
        if (!m.admissible().contains(Stretch::from_value(stretch))) continue;
        SCOPED_TRACE(sample.model + " closing at " + std::to_string(closing) + ", s = " + std::to_string(stretch));
        const State left{std::atanh(closing), Stretch::from_value(stretch)}, right{0.0, Stretch::from_value(stretch)};
        const exact::Solution<double> bonded =
            exact::riemann_problem<double>(law, {left.rapidity, stretch}, law, {0.0, stretch});
        const RiemannSolution sol = solve_riemann(m, left, m, right, min_pressure);
        ASSERT_EQ(sol.status, Status::ok);
        const bool should_part = !bonded.solved || bonded.parted || bonded.pressure < min_pressure;
        EXPECT_EQ(sol.parted, should_part) << "bonded p* = " << bonded.pressure;
        if (should_part) {
          ++parted;
          EXPECT_EQ(sol.pressure, min_pressure);
          EXPECT_NEAR(m.pressure(sol.left.stretch), min_pressure, 1e-12 * m.rest_density());
          EXPECT_NEAR(m.pressure(sol.right.stretch), min_pressure, 1e-12 * m.rest_density());
        } else {
          ++held;
          EXPECT_NEAR(sol.pressure, bonded.pressure, 1e-10 * (std::abs(bonded.pressure) + m.rest_density()));
        }
      }
    }
  }
  EXPECT_GT(parted, 10);
  EXPECT_GT(held, 10);
}

TEST(Separation, BodiesAtRestInContactStayInContactWhateverTheirMaterials) {
  // Unstrained and at rest, touching: the contact holds at p = 0 and nothing happens, for
  // one material on both sides and for two (the parting test then compares the sides'
  // velocities at the parting pressure, equal here, not only the star state's pressure).
  const std::vector<std::string> materials = {"{model: rigid}", "{model: hooke, wave_speed: 0.5, rest_density: 2.0}",
                                              "{model: rigid_fluid, rest_density: 3.0}"};
  for (const std::string& left : materials)
    for (const std::string& right : materials)
      for (const std::string method : {"characteristics", "finite_volume"}) {
        SCOPED_TRACE(left + " | " + right + " | " + method);
        const std::string yaml = "name: at_rest\nmaterials: {a: " + left + ", b: " + right +
                                 "}\nbodies:\n  - {name: plate1, material: a, position: 0.0, length: 1.0}\n"
                                 "  - {name: plate2, material: b, position: 1.0, length: 0.5}\n"
                                 "boundaries: {right: {type: wall}}\nsolver: {method: " +
                                 method + "}\ntime: {end: 3.0}\n";
        const RunResult r = solve(load_scene_string(yaml, "<test>"));
        EXPECT_TRUE(r.events.empty()) << r.events.front().kind << " at t = " << r.events.front().t;
        ASSERT_EQ(r.bodies.size(), 2u);
        EXPECT_EQ(r.bodies[0].velocity_mean, 0.0);
        EXPECT_EQ(r.bodies[1].velocity_mean, 0.0);
      }
}

}  // namespace
}  // namespace rigidity
