// A run that meets a state with no classical solution mid-way (a bar crushed to zero length)
// stops there: solve() throws InadmissibleStop with the run up to that instant, its books
// closed there and its verdict judged against its error bound.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

/// The run up to where `yaml` stops as inadmissible (a failure if it does not).
RunResult stopped_run(const std::string& yaml) {
  try {
    (void)solve(load_scene_string(yaml, "<test>"));
  } catch (const InadmissibleStop& stop) {
    return stop.result();
  }
  ADD_FAILURE() << "no InadmissibleStop";
  return {};
}

/// Rigid hammers and a Hooke bar: every interaction is exact, so the books close to round-off
/// at the stop if the state the stop left is the run's state at that instant.
void expect_books_closed(const RunResult& r) {
  const Conservation& c = r.conservation;
  EXPECT_NEAR(c.energy_final + c.energy_dissipated - c.energy_initial - c.wall_work, 0.0, 1e-12 * c.energy_initial);
  EXPECT_NEAR(c.momentum_final - c.momentum_initial - c.wall_impulse, 0.0, 1e-12 * c.energy_initial);
}

const std::string kMaterials =
    "materials:\n"
    "  heavy: {model: rigid, rest_density: 20.0}\n"
    "  soft: {model: hooke, wave_speed: 0.6, rest_density: 1.0}\n";

TEST(InadmissibleStop, ABarCrushedAtALeftWallStopsThereWithItsBooksClosed) {
  // The hammer reaches the bar at t = 0.3/0.45 = 2/3; the compression crosses the bar's unit
  // natural length at 0.6 in the labels and, doubled at the wall, crushes it there at 2/3 + 5/3.
  // The interaction that finds it took in the front and leaves the wall's end with the state
  // behind it.
  const RunResult r = stopped_run("name: left\n" + kMaterials +
                                  "bodies:\n"
                                  "  - {name: bar, material: soft, position: 0.0, length: 1.0}\n"
                                  "  - {name: hammer, material: heavy, position: 1.3, length: 0.5, velocity: -0.45}\n"
                                  "boundaries: {left: {type: wall, position: 0.0}}\n"
                                  "time: {end: 5.0}\n");
  EXPECT_EQ(r.status, "inadmissible");
  EXPECT_NEAR(r.t_reached, 7.0 / 3.0, 1e-12);
  ASSERT_TRUE(r.inadmissible.has_value());
  EXPECT_EQ(r.inadmissible->x, 0.0);
  EXPECT_NEAR(r.inadmissible->psi_limit, std::atanh(0.6), 1e-12);
  EXPECT_GT(r.inadmissible->margin(), 0.2);
  EXPECT_EQ(r.solver_number("error_bound"), 0.0);
  EXPECT_FALSE(r.verdict_uncertain);
  EXPECT_NE(r.verdict.find("is small against the margin"), std::string::npos) << r.verdict;
  EXPECT_NE(r.stop_reason.find("would crush the material 'hooke' to zero length"), std::string::npos);
  expect_books_closed(r);
}

TEST(InadmissibleStop, ABarCrushedWhereTwoCompressionsMeetInsideItStopsThereWithItsBooksClosed) {
  // Hammers at both ends: their compressions meet inside the bar, where the interaction that
  // finds the crush took in both fronts; the state right of the meeting is kept all the same.
  const RunResult r = stopped_run("name: mid\n" + kMaterials +
                                  "bodies:\n"
                                  "  - {name: left, material: heavy, position: 0.0, length: 0.5, velocity: 0.45}\n"
                                  "  - {name: bar, material: soft, position: 0.8, length: 1.0}\n"
                                  "  - {name: right, material: heavy, position: 2.1, length: 0.5, velocity: -0.45}\n"
                                  "time: {end: 5.0}\n");
  EXPECT_EQ(r.status, "inadmissible");
  ASSERT_TRUE(r.inadmissible.has_value());
  EXPECT_GT(r.inadmissible->x, r.bodies.at(1).x_left);  // inside the bar
  EXPECT_LT(r.inadmissible->x, r.bodies.at(1).x_right);
  EXPECT_EQ(r.t_reached, r.inadmissible->t);
  expect_books_closed(r);
}

TEST(InadmissibleStop, FiniteVolumeStopsThereTooAndHasNoBoundToVouchForTheStop) {
  const RunResult r = stopped_run("name: left\n" + kMaterials +
                                  "bodies:\n"
                                  "  - {name: bar, material: soft, position: 0.0, length: 1.0}\n"
                                  "  - {name: hammer, material: heavy, position: 1.3, length: 0.5, velocity: -0.45}\n"
                                  "boundaries: {left: {type: wall, position: 0.0}}\n"
                                  "solver: {method: finite_volume, cells: 100}\n"
                                  "time: {end: 5.0}\n");
  EXPECT_EQ(r.status, "inadmissible");
  EXPECT_GT(r.t_reached, 2.0 / 3.0);
  EXPECT_LT(r.t_reached, 5.0);
  EXPECT_TRUE(r.verdict_uncertain);
  EXPECT_NE(r.verdict.find("reports no error bound"), std::string::npos) << r.verdict;
}

TEST(InadmissibleStop, TheVerdictIsFirmOnlyWhereTheMarginIsOverAHundredTimesTheBound) {
  RunResult r;
  r.t_reached = 1.0;
  r.solver = "characteristics";
  Inadmissibility crushed = Inadmissibility::at(1.0);
  crushed.psi_needed = 0.8;
  crushed.psi_limit = 0.7;  // a margin of 0.1
  r.inadmissible = crushed;
  r.solver_numbers = {{"error_bound", 9.9e-4}};
  (void)judge_inadmissible_stop(r, UnitSystem::natural);
  EXPECT_FALSE(r.verdict_uncertain);
  r.solver_numbers = {{"error_bound", 1.01e-3}};
  EXPECT_NE(judge_inadmissible_stop(r, UnitSystem::natural).find("may move or remove this stop"), std::string::npos);
  EXPECT_TRUE(r.verdict_uncertain);
  // Pulled apart: the margin is how far below its limit (Psi_min) the material would go.
  Inadmissibility pulled = Inadmissibility::at(1.0);
  pulled.psi_needed = -0.8;
  pulled.psi_limit = -0.7;
  pulled.in_tension = true;
  r.inadmissible = pulled;
  r.solver_numbers = {{"error_bound", 1e-4}};
  (void)judge_inadmissible_stop(r, UnitSystem::natural);
  EXPECT_FALSE(r.verdict_uncertain);
  // Not known how far beyond: never firm.
  r.inadmissible = Inadmissibility::at(1.0);
  r.solver_numbers = {{"error_bound", 0.0}};
  (void)judge_inadmissible_stop(r, UnitSystem::natural);
  EXPECT_TRUE(r.verdict_uncertain);
}

}  // namespace
}  // namespace rigidity
