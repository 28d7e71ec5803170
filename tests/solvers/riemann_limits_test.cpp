// Riemann problems without a classical solution for a physical reason (docs/cli.md, exit 3): a side
// would leave its material's admissible range, crushed or, bonded, pulled beyond its largest
// tension. The solver says which material, the impact and the limit, with the numbers of closed
// forms; just inside the limit it solves; and the message states those numbers.
#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <string_view>

#include "rigidity/errors.hpp"
#include "rigidity/numeric_material.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace rigidity {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::shared_ptr<const Material> make(const std::string& model, const char* speed_key = nullptr, double speed = 0.0) {
  ParameterValues values;
  values.set("rest_density", 1.0);
  if (speed_key != nullptr) values.set(speed_key, speed);
  return build_material(model, values);
}

/// The shortest decimal that reads back to v, as the messages print it.
std::string shortest(double v) {
  std::array<char, 64> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return ec == std::errc() ? std::string(buffer.data(), end) : std::string("?");
}

/// The message require_solved throws as InadmissibleError (empty if it throws nothing or else).
std::string inadmissible_message(const RiemannSolution& sol, const Material& m, double t, double x) {
  try {
    require_solved(sol, m, t, x);
  } catch (const InadmissibleError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InadmissibleError: " << e.what();
  }
  return {};
}

const State kNatural{0.0, Stretch::natural()};

// hooke with b = V = 1/2, ρ00 = 1: p_max = b²/(1 − b²) = 1/3 and Ψ_max = artanh b. The rigid
// law at p = 1/3: s² = 1/(1 + 2p) = 3/5, so Ψ = −ln s = ln(5/3)/2.
constexpr double kHookeSpeed = 0.5;
const double kRigidPsiAtHookeCrush = 0.5 * std::log(5.0 / 3.0);

TEST(RiemannLimits, AHookeBarCrushedOnARigidBarNeedsMoreThanPsiMax) {
  const auto hooke = make("hooke", "wave_speed", kHookeSpeed);
  const auto rigid = make("rigid");
  // The hooke bar (left) is crushed when, at its maximum pressure, its star still outruns the
  // rigid star: it would need Ψ = J+ − φ*_R(p_max) = artanh v − ln(5/3)/2.
  const double v = 0.8;
  const RiemannSolution sol = solve_riemann(*hooke, State{std::atanh(v), Stretch::natural()}, *rigid, kNatural, 0.0);
  ASSERT_EQ(sol.status, Status::out_of_range);
  EXPECT_EQ(sol.material, hooke.get());
  EXPECT_FALSE(sol.in_tension);
  EXPECT_DOUBLE_EQ(sol.impact_rapidity, std::atanh(v));
  EXPECT_DOUBLE_EQ(sol.limit_psi, std::atanh(kHookeSpeed));
  EXPECT_NEAR(sol.demanded_psi, std::atanh(v) - kRigidPsiAtHookeCrush, 1e-14);
  // Just inside the limit (Ψ needed below artanh V) it has a solution, below p_max.
  const double v_ok = std::tanh(std::atanh(kHookeSpeed) + kRigidPsiAtHookeCrush - 1e-3);
  const RiemannSolution ok = solve_riemann(*hooke, State{std::atanh(v_ok), Stretch::natural()}, *rigid, kNatural, 0.0);
  ASSERT_EQ(ok.status, Status::ok);
  EXPECT_LT(ok.pressure, hooke->max_pressure());
  EXPECT_NEAR(hooke->pressure(ok.left.stretch), rigid->pressure(ok.right.stretch), 1e-13);
}

TEST(RiemannLimits, AHookeBarCrushedByARigidBarNeedsMoreThanPsiMax) {
  // Mirror image, the hooke bar on the right: its range ends at a finite left star stretch (where
  // the rigid left reaches 1/3). It once came back with the impact and the limits left at 0 (and
  // the message "an impact at relative speed 0 c ... limit 0 c").
  const auto hooke = make("hooke", "wave_speed", kHookeSpeed);
  const auto rigid = make("rigid");
  const double v = 0.9;
  const RiemannSolution sol = solve_riemann(*rigid, State{std::atanh(v), Stretch::natural()}, *hooke, kNatural, 0.0);
  ASSERT_EQ(sol.status, Status::out_of_range);
  EXPECT_EQ(sol.material, hooke.get());
  EXPECT_DOUBLE_EQ(sol.impact_rapidity, std::atanh(v));
  EXPECT_DOUBLE_EQ(sol.limit_psi, std::atanh(kHookeSpeed));
  // φ*_L = J+ − Ψ_rigid(p_max), and the hooke bar would need Ψ = φ*_L − J−.
  EXPECT_NEAR(sol.demanded_psi, std::atanh(v) - kRigidPsiAtHookeCrush, 1e-14);
  const std::string message = inadmissible_message(sol, *rigid, 2.5, 1.0);
  EXPECT_NE(message.find("'hooke'"), std::string::npos) << message;  // not the rigid bar the caller named
  EXPECT_NE(message.find("relative speed " + shortest(std::tanh(sol.impact_rapidity)) + " c"), std::string::npos)
      << message;
  EXPECT_NE(message.find("Psi = " + shortest(sol.demanded_psi)), std::string::npos) << message;
  EXPECT_NE(message.find("tanh Psi_max = " + shortest(std::tanh(sol.limit_psi)) + " c"), std::string::npos) << message;
  EXPECT_EQ(message.find(" 0 c"), std::string::npos) << message;
}

TEST(RiemannLimits, AShockingFluidCrushingAHookeBarIsNoSolution) {
  // The fluid's star pressure would exceed the hooke bar's maximum: the bar is crushed. (This
  // once came back as a solution, with the hooke star at p_max, that is at zero length.)
  const auto fluid = make("constant_sound_speed", "sound_speed", 0.766);
  const auto hooke = make("hooke", "wave_speed", kHookeSpeed);
  const State left{std::atanh(0.9), Stretch::natural()};
  const RiemannSolution sol = solve_riemann(*fluid, left, *hooke, kNatural, 0.0);
  ASSERT_EQ(sol.status, Status::out_of_range);
  EXPECT_EQ(sol.material, hooke.get());
  EXPECT_DOUBLE_EQ(sol.impact_rapidity, left.rapidity);
  EXPECT_DOUBLE_EQ(sol.limit_psi, std::atanh(kHookeSpeed));
  // The fluid's shock star at the hooke bar's maximum pressure, and the Ψ the bar would need there.
  const WaveCurvePoint fluid_star = WaveCurve(*fluid, left, Side::left).at_pressure(hooke->max_pressure());
  ASSERT_TRUE(fluid_star.ok());
  EXPECT_NEAR(sol.demanded_psi, fluid_star.rapidity, 1e-14);
  EXPECT_GT(sol.demanded_psi, sol.limit_psi);
}

TEST(RiemannLimits, AWallImpactMessageStatesTheNumbersInShortestForm) {
  const auto hooke = make("hooke", "wave_speed", 0.3);
  const double v = 0.45;
  const RiemannSolution sol = solve_wall(*hooke, State{std::atanh(v), Stretch::natural()}, Side::left, 0.0, 0.0);
  ASSERT_EQ(sol.status, Status::out_of_range);
  EXPECT_NEAR(std::tanh(sol.demanded_psi), v, 1e-15);
  const std::string message = inadmissible_message(sol, *hooke, 1.0 / 3.0, 2.0 / 3.0);
  EXPECT_NE(message.find("t = " + shortest(1.0 / 3.0) + " L/c, x = " + shortest(2.0 / 3.0) + " L"), std::string::npos)
      << message;
  EXPECT_NE(message.find("relative speed " + shortest(std::tanh(std::atanh(v))) + " c"), std::string::npos) << message;
  EXPECT_NE(message.find("to zero length"), std::string::npos) << message;
  EXPECT_NE(message.find("tanh Psi_max = " + shortest(std::tanh(sol.limit_psi)) + " c"), std::string::npos) << message;
  EXPECT_NEAR(std::tanh(sol.limit_psi), 0.3, 1e-16);
}

/// The constant-sound-speed law p = V²/k (s^−k − 1) (k = 1 + V², ρ00 = 1) given as a pressure law
/// on the window s ∈ [0.5, 2]: a genuinely nonlinear material whose range ends at finite stretches.
class WindowedFluid final : public PressureLawMaterial {
 public:
  explicit WindowedFluid(double sound_speed)
      : PressureLawMaterial(1.0, StretchRange{std::log(0.5), std::log(2.0)}),
        v_(sound_speed),
        k_(1.0 + sound_speed * sound_speed) {}
  [[nodiscard]] std::string_view model() const override { return "windowed_fluid"; }

 private:
  [[nodiscard]] double pressure_law(double s) const override { return v_ * v_ / k_ * (std::pow(s, -k_) - 1.0); }
  double v_;
  double k_;
};

TEST(RiemannLimits, AMaterialWithAFiniteRangeLeavesItAtItsEnds) {
  const WindowedFluid m(0.5);
  // Inside the window: solved.
  ASSERT_EQ(solve_wall(m, State{std::atanh(0.1), Stretch::natural()}, Side::left, 0.0, 0.0).status, Status::ok);
  // A hard wall impact compresses it below s = 0.5 (a shock: the Ψ it would need is not defined).
  const double v = 0.9;
  const RiemannSolution crushed = solve_wall(m, State{std::atanh(v), Stretch::natural()}, Side::left, 0.0, 0.0);
  ASSERT_EQ(crushed.status, Status::out_of_range);
  EXPECT_EQ(crushed.material, &m);
  EXPECT_FALSE(crushed.in_tension);
  EXPECT_DOUBLE_EQ(crushed.impact_rapidity, std::atanh(v));
  EXPECT_EQ(crushed.limit_psi, m.psi_max());
  EXPECT_TRUE(std::isnan(crushed.demanded_psi));
  std::string message = inadmissible_message(crushed, m, 0.0, 0.0);
  EXPECT_NE(message.find("below its smallest admissible stretch s = 0.5"), std::string::npos) << message;
  // Not crushed: it left the range its law was declared on, and the message gives that range.
  EXPECT_EQ(message.find("crush"), std::string::npos) << message;
  EXPECT_NE(message.find("out of the range its law is declared on, s in [0.5, 2]"), std::string::npos) << message;
  // A bonded wall receding fast stretches it beyond s = 2, and so do two bonded halves flying apart.
  const RiemannSolution pulled = solve_wall(m, kNatural, Side::left, 1.0, -kInf);
  ASSERT_EQ(pulled.status, Status::out_of_range);
  EXPECT_TRUE(pulled.in_tension);
  EXPECT_EQ(pulled.limit_psi, m.psi_min());
  message = inadmissible_message(pulled, m, 0.0, 0.0);
  EXPECT_NE(message.find("beyond its largest admissible stretch s = 2"), std::string::npos) << message;
  const RiemannSolution torn =
      solve_riemann(m, State{-1.0, Stretch::natural()}, m, State{1.0, Stretch::natural()}, -kInf);
  ASSERT_EQ(torn.status, Status::out_of_range);
  EXPECT_TRUE(torn.in_tension);
  EXPECT_EQ(torn.material, &m);
  EXPECT_DOUBLE_EQ(torn.impact_rapidity, -2.0);
  // A wall that cannot pull lets go instead: a free end, no verdict.
  const RiemannSolution released = solve_wall(m, kNatural, Side::left, 1.0, 0.0);
  ASSERT_EQ(released.status, Status::ok);
  EXPECT_TRUE(released.parted);
}

}  // namespace
}  // namespace rigidity
