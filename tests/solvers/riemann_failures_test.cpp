// The exact Riemann solver never hands back a failed computation as a number (STYLE: a failed
// root find is reported, never returned as if converged). A test material fails on purpose in
// one function at a time (an inverse, or the law itself under strong compression), and every
// path of the solver that calls it must come back with the failed status, naming what failed,
// and require_solved must turn that into a NumericalError, never an answer or an exit-3 verdict.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <string_view>

#include "rigidity/errors.hpp"
#include "rigidity/material.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace rigidity {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Which function of FaultyFluid fails on purpose.
enum class Fault {
  pressure_inverse,               ///< stretch_at_pressure: not converged
  pressure_inverse_out_of_range,  ///< stretch_at_pressure: out of range, for a p inside the range
  psi_inverse,                    ///< stretch_at_psi: not converged
  law_under_compression,          ///< e + p is NaN for s < 0.2 (so the shock jump conditions fail)
};

/// The constant-sound-speed law of docs/materials.md written out (ρ00 = 1, k = 1 + V²):
/// p = V²/k (s^−k − 1), e + p = s^−k, c_s = V, Ψ = −V ln s; V = 1 is the rigid law, linearly
/// degenerate. One function fails on purpose (Fault); everything else is exact.
class FaultyFluid final : public Material {
 public:
  FaultyFluid(double sound_speed, Fault fault)
      : Material(1.0), v_(sound_speed), k_(1.0 + sound_speed * sound_speed), fault_(fault) {}

  [[nodiscard]] std::string_view model() const override { return "faulty_fluid"; }
  [[nodiscard]] double pressure(Stretch s) const override { return v_ * v_ / k_ * std::expm1(-k_ * s.log()); }
  [[nodiscard]] double energy_density(Stretch s) const override { return (std::exp(-k_ * s.log()) + v_ * v_) / k_; }
  [[nodiscard]] double enthalpy_density(Stretch s) const override {
    if (fault_ == Fault::law_under_compression && s.value() < 0.2) return std::numeric_limits<double>::quiet_NaN();
    return std::exp(-k_ * s.log());
  }
  [[nodiscard]] double sound_speed(Stretch) const override { return v_; }
  [[nodiscard]] double riemann_psi(Stretch s) const override { return -v_ * s.log(); }
  [[nodiscard]] Solved<Stretch> stretch_at_pressure(double p) const override {
    if (!(p > max_tension() && p < max_pressure())) return Solved<Stretch>::failure(Status::out_of_range);
    if (fault_ == Fault::pressure_inverse) return Solved<Stretch>::failure(Status::not_converged);
    if (fault_ == Fault::pressure_inverse_out_of_range) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(-std::log1p(k_ * p / (v_ * v_)) / k_)};
  }
  [[nodiscard]] Solved<Stretch> stretch_at_psi(double psi) const override {
    if (fault_ == Fault::psi_inverse) return Solved<Stretch>::failure(Status::not_converged);
    return {Stretch::from_log(-psi / v_)};
  }
  [[nodiscard]] double max_pressure() const override { return kInf; }
  [[nodiscard]] double max_tension() const override { return -v_ * v_ / k_; }
  [[nodiscard]] double psi_max() const override { return kInf; }
  [[nodiscard]] double psi_min() const override { return -kInf; }
  [[nodiscard]] bool linearly_degenerate() const override { return v_ == 1.0; }

 private:
  double v_;
  double k_;
  Fault fault_;
};

std::shared_ptr<const Material> make(const std::string& model, const char* speed_key, double speed) {
  ParameterValues values;
  values.set("rest_density", 1.0);
  values.set(speed_key, speed);
  return build_material(model, values);
}

/// The solution failed numerically (not out_of_range: that is a physical verdict), names the
/// computation and the material, carries no number, and require_solved throws NumericalError
/// saying so with the place of the interaction.
void expect_reported(const RiemannSolution& sol, const Material& faulty, std::string_view what) {
  EXPECT_NE(sol.status, Status::ok);
  EXPECT_NE(sol.status, Status::out_of_range);
  EXPECT_EQ(sol.material, &faulty);
  EXPECT_NE(std::string(sol.failure).find(what), std::string::npos) << sol.failure;
  EXPECT_EQ(sol.pressure, 0.0);
  EXPECT_EQ(sol.left.rapidity, 0.0);
  EXPECT_EQ(sol.right.rapidity, 0.0);
  try {
    require_solved(sol, faulty, 1.5, -0.25);
    ADD_FAILURE() << "a failed Riemann problem passed require_solved";
  } catch (const NumericalError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("t = 1.5 L/c, x = -0.25 L"), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_NE(message.find("faulty_fluid"), std::string::npos) << message;
  }
}

TEST(RiemannFailures, AFailedPressureInverseIsReportedOnEveryPathThatInvertsThePressure) {
  const FaultyFluid faulty(0.5, Fault::pressure_inverse);
  const FaultyFluid faulty_rigid(1.0, Fault::pressure_inverse);
  const auto fluid = make("constant_sound_speed", "sound_speed", 0.5);
  const auto hooke = make("hooke", "wave_speed", 0.5);
  const State compressed{0.1, Stretch::from_value(0.8)}, natural{0.0, Stretch::natural()};

  // The wave curve itself.
  EXPECT_EQ(WaveCurve(faulty, compressed, Side::left).at_pressure(0.1).status, Status::not_converged);
  // A free end relaxes to p = 0 through the inverse.
  expect_reported(solve_free_end(faulty, compressed, Side::left), faulty, "stretch_at_pressure");
  // Two materials: the right star at each trial pressure, inside Brent's method (it once gave
  // a stand-in number there, on which Brent went on).
  expect_reported(solve_riemann(*fluid, State{0.3, Stretch::natural()}, faulty, natural, -kInf), faulty,
                  "stretch_at_pressure");
  expect_reported(solve_riemann(*fluid, State{0.3, Stretch::natural()}, faulty_rigid, natural, 0.0), faulty_rigid,
                  "stretch_at_pressure");
  // The left star stretch at which the right side (hooke, bounded pressure) is crushed.
  expect_reported(solve_riemann(faulty, natural, *hooke, natural, -kInf), faulty, "stretch_at_pressure");
  // A push-only contact parting: each side relaxes to p = 0 (here the parting stretch is asked first).
  expect_reported(solve_riemann(faulty, State{-0.2, Stretch::natural()}, *fluid, State{0.2, Stretch::natural()}, 0.0),
                  faulty, "stretch_at_pressure");
  expect_reported(
      solve_riemann(faulty_rigid, State{-0.2, Stretch::natural()}, faulty_rigid, State{0.2, Stretch::natural()}, 0.0),
      faulty_rigid, "stretch_at_pressure");
  // A wall that cannot pull, receding (on the material's right, moving right): the pressure at
  // which the end lets go.
  expect_reported(solve_wall(faulty, natural, Side::left, 0.3, 0.0), faulty, "stretch_at_pressure");
  expect_reported(solve_wall(faulty_rigid, natural, Side::left, 0.3, 0.0), faulty_rigid, "stretch_at_pressure");
}

TEST(RiemannFailures, AnInverseClaimingOutOfRangeInsideTheRangeIsNumericalNotPhysical) {
  // out_of_range from the material for a p inside the range it declares is not a crushed body:
  // no exit-3 verdict with made-up limits, a numerical failure.
  const FaultyFluid faulty(0.5, Fault::pressure_inverse_out_of_range);
  const auto fluid = make("constant_sound_speed", "sound_speed", 0.5);
  const State natural{0.0, Stretch::natural()};
  expect_reported(solve_riemann(*fluid, State{0.3, Stretch::natural()}, faulty, natural, -kInf), faulty,
                  "stretch_at_pressure");
  expect_reported(solve_free_end(faulty, State{0.1, Stretch::from_value(0.8)}, Side::right), faulty,
                  "stretch_at_pressure");
}

TEST(RiemannFailures, AFailedPsiInverseIsReportedOnEveryPathThatInvertsPsi) {
  const FaultyFluid faulty(0.5, Fault::psi_inverse);
  const FaultyFluid faulty_rigid(1.0, Fault::psi_inverse);
  const State natural{0.0, Stretch::natural()};
  // Linearly degenerate, one material: the star stretch is Ψ* inverted.
  expect_reported(solve_riemann(faulty_rigid, State{0.3, Stretch::natural()}, faulty_rigid, natural, -kInf),
                  faulty_rigid, "stretch_at_psi");
  // A wall: the star on the invariant's curve, for a jump, for a fan (a bonded wall receding),
  // and as the first guess that tells a shock from a fan.
  expect_reported(solve_wall(faulty_rigid, State{0.3, Stretch::natural()}, Side::left, 0.0, 0.0), faulty_rigid,
                  "stretch_at_psi");
  expect_reported(solve_wall(faulty, natural, Side::left, 0.3, -kInf), faulty, "stretch_at_psi");
  expect_reported(solve_wall(faulty, State{0.3, Stretch::natural()}, Side::left, 0.0, 0.0), faulty, "stretch_at_psi");
}

TEST(RiemannFailures, ShockJumpConditionsThatCannotBeEvaluatedAreReported) {
  // e + p is NaN below s = 0.2: a mild impact never asks for it, a hard one does, inside the
  // bracket search or Brent's method on the star stretch.
  const FaultyFluid faulty(0.5, Fault::law_under_compression);
  const State mild{std::atanh(0.1), Stretch::natural()}, hard{std::atanh(0.95), Stretch::natural()};
  ASSERT_EQ(solve_wall(faulty, mild, Side::left, 0.0, 0.0).status, Status::ok);
  expect_reported(solve_wall(faulty, hard, Side::left, 0.0, 0.0), faulty, "shock jump conditions");
  const State hard_right{-hard.rapidity, Stretch::natural()};
  expect_reported(solve_riemann(faulty, hard, faulty, hard_right, -kInf), faulty, "shock jump conditions");
  const auto fluid = make("constant_sound_speed", "sound_speed", 0.5);
  expect_reported(solve_riemann(*fluid, hard, faulty, hard_right, -kInf), faulty, "shock jump conditions");
}

TEST(RiemannFailures, AStarStateNoDoubleRepresentsIsANumericalFailureNotAVerdict) {
  // A fluid takes any compression, but against a wall at rapidity 400 (γ ≈ e^400, a state a scene
  // can give as `rapidity:`) its shock star stretch is about e^−800: no double. The bracket search
  // stops at |ln s| = 700 and says so: not a physical limit (exit 3), and no number comes back.
  const auto slow = make("constant_sound_speed", "sound_speed", 0.01);
  const RiemannSolution sol = solve_wall(*slow, State{400.0, Stretch::natural()}, Side::left, 0.0, 0.0);
  EXPECT_EQ(sol.status, Status::not_converged);
  EXPECT_NE(std::string(sol.failure).find("double precision"), std::string::npos) << sol.failure;
  EXPECT_THROW(require_solved(sol, *slow, 0.0, 0.0), NumericalError);
}

}  // namespace
}  // namespace rigidity
