// The exact Riemann solver against the jump conditions and the Riemann invariants (docs/physics.md).
#include "rigidity/solvers/riemann.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "rigidity/registry.hpp"

namespace rigidity {
namespace {

std::shared_ptr<const Material> make(const std::string& model, double rest_density = 1.0,
                                     const char* speed_key = nullptr, double speed = 0.0) {
  ParameterValues values;
  values.set("rest_density", rest_density);
  if (speed_key != nullptr) values.set(speed_key, speed);
  return build_material(model, values);
}

// Conserved densities and fluxes per unit label (docs/physics.md).
double labels(const State& st) { return st.stretch.value() / std::cosh(st.rapidity); }
double momentum(const Material& m, const State& st) {
  return m.enthalpy_density(st.stretch) * st.stretch.value() * std::sinh(st.rapidity);
}
double energy(const Material& m, const State& st) {
  const double s = st.stretch.value(), ch = std::cosh(st.rapidity);
  return m.enthalpy_density(st.stretch) * s * ch - m.pressure(st.stretch) * s / ch;
}

/// Checks the label and momentum jump conditions m[U] = [F] across a front of
/// Lagrangian speed `speed` between states a (left) and b (right).
void expect_jump_conditions(const Material& m, const State& a, const State& b, double speed, double tol) {
  const double labels_residual = speed * (labels(b) - labels(a)) + (std::tanh(b.rapidity) - std::tanh(a.rapidity));
  const double momentum_residual =
      speed * (momentum(m, b) - momentum(m, a)) - (m.pressure(b.stretch) - m.pressure(a.stretch));
  const double scale = std::abs(m.pressure(b.stretch) - m.pressure(a.stretch)) + 1e-300;
  EXPECT_LE(std::abs(labels_residual), tol * std::abs(std::tanh(b.rapidity) - std::tanh(a.rapidity)) + 1e-300);
  EXPECT_LE(std::abs(momentum_residual), tol * scale);
}

TEST(Riemann, RigidCollisionIsSymmetricAndClosedForm) {
  // Two equal rigid bars at ±v: both stop, compressed as against a wall.
  const auto rigid = make("rigid");
  const double v = 0.6;
  const State left{std::atanh(v), Stretch::natural()}, right{-std::atanh(v), Stretch::natural()};
  const RiemannSolution sol = solve_riemann(*rigid, left, *rigid, right, 0.0);
  ASSERT_TRUE(sol.status == Status::ok);
  EXPECT_FALSE(sol.parted);
  EXPECT_NEAR(sol.left.rapidity, 0.0, 1e-15);
  EXPECT_NEAR(sol.left.stretch.value(), 0.5, 1e-15);
  EXPECT_NEAR(sol.pressure, 1.5, 1.5e-15 * 4);
}

TEST(Riemann, LinearlyDegenerateJumpsSatisfyTheJumpConditionsAndConserveEnergy) {
  for (const auto& m : {make("rigid"), make("hooke", 2.0, "wave_speed", 0.3), make("hooke", 1.0, "wave_speed", 0.9)}) {
    const State left{0.4, Stretch::from_value(0.9)}, right{-0.2, Stretch::from_value(1.3)};
    const RiemannSolution sol = solve_riemann(*m, left, *m, right, -1e300);
    ASSERT_TRUE(sol.status == Status::ok) << m->model();
    // C− jump between left and star moves at the characteristic speed of either side.
    const double speed_left = characteristic_speed(*m, sol.left, -1);
    EXPECT_NEAR(speed_left, characteristic_speed(*m, left, -1), 1e-13 * std::abs(speed_left)) << m->model();
    expect_jump_conditions(*m, left, sol.left, speed_left, 1e-12);
    const double speed_right = characteristic_speed(*m, sol.right, +1);
    EXPECT_NEAR(speed_right, characteristic_speed(*m, right, +1), 1e-13 * std::abs(speed_right)) << m->model();
    expect_jump_conditions(*m, sol.right, right, speed_right, 1e-12);
    // No dissipation: the energy law holds across the jump too.
    const double energy_residual = speed_left * (energy(*m, sol.left) - energy(*m, left)) -
                                   (m->pressure(sol.left.stretch) * std::tanh(sol.left.rapidity) -
                                    m->pressure(left.stretch) * std::tanh(left.rapidity));
    EXPECT_LE(std::abs(energy_residual), 1e-12 * std::abs(energy(*m, left))) << m->model();
  }
}

TEST(Riemann, ShocksOfTheConstantSoundSpeedFluidSatisfyTheJumpConditionsAndDissipate) {
  const auto m = make("constant_sound_speed", 1.0, "sound_speed", 0.5);
  const State left{0.8, Stretch::natural()}, right{-0.8, Stretch::natural()};
  const RiemannSolution sol = solve_riemann(*m, left, *m, right, -1e300);
  ASSERT_TRUE(sol.status == Status::ok);
  ASSERT_GT(sol.pressure, 0.0);
  EXPECT_NEAR(sol.left.rapidity, 0.0, 1e-14);
  const FrontSpeeds sl = shock_speeds(*m, left, sol.left, -1);
  EXPECT_LT(sl.lagrangian, 0.0);
  expect_jump_conditions(*m, left, sol.left, sl.lagrangian, 1e-12);
  const FrontSpeeds sr = shock_speeds(*m, right, sol.right, +1);
  expect_jump_conditions(*m, sol.right, right, sr.lagrangian, 1e-12);
  // Lax: the shock is faster than the characteristics ahead, slower than behind.
  EXPECT_LT(sl.lagrangian, characteristic_speed(*m, left, -1));
  EXPECT_GT(sl.lagrangian, characteristic_speed(*m, sol.left, -1));
  // A genuine shock removes energy: m[E] − [F] > 0 across it.
  const double dissipation = sl.lagrangian * (energy(*m, sol.left) - energy(*m, left)) -
                             (m->pressure(sol.left.stretch) * std::tanh(sol.left.rapidity) -
                              m->pressure(left.stretch) * std::tanh(left.rapidity));
  EXPECT_GT(dissipation, 0.0);
}

TEST(Riemann, TwoMaterialsShareStarPressureAndVelocity) {
  const auto a = make("rigid", 1.0);
  const auto b = make("hooke", 2.0, "wave_speed", 0.5);
  const State left{std::atanh(0.3), Stretch::natural()}, right{0.0, Stretch::natural()};
  const RiemannSolution sol = solve_riemann(*a, left, *b, right, 0.0);
  ASSERT_TRUE(sol.status == Status::ok);
  EXPECT_NEAR(a->pressure(sol.left.stretch), b->pressure(sol.right.stretch), 1e-14);
  // Each side's star state lies on its own wave curve: J+ of the left, J− of the right.
  EXPECT_NEAR(sol.left.rapidity + a->riemann_psi(sol.left.stretch), left.rapidity, 1e-14);
  EXPECT_NEAR(sol.right.rapidity - b->riemann_psi(sol.right.stretch), 0.0, 1e-14);
}

TEST(Riemann, PushOnlyContactsPart) {
  const auto rigid = make("rigid");
  const State left{-0.1, Stretch::natural()}, right{0.1, Stretch::natural()};
  const RiemannSolution sol = solve_riemann(*rigid, left, *rigid, right, 0.0);
  ASSERT_TRUE(sol.status == Status::ok);
  EXPECT_TRUE(sol.parted);
  EXPECT_EQ(sol.pressure, 0.0);
  EXPECT_EQ(sol.left.rapidity, -0.1);
  EXPECT_EQ(sol.right.rapidity, 0.1);
}

TEST(Riemann, HookeCannotBeCrushedAtTheWaveSpeed) {
  const auto hooke = make("hooke", 1.0, "wave_speed", 0.5);
  const State bar{std::atanh(0.6), Stretch::natural()};
  const RiemannSolution sol = solve_wall(*hooke, bar, Side::left, 0.0, 0.0);
  EXPECT_TRUE(sol.status == Status::out_of_range);
  EXPECT_NEAR(std::tanh(sol.demanded_psi), 0.6, 1e-15);
  EXPECT_NEAR(std::tanh(sol.limit_psi), 0.5, 1e-15);
}

TEST(Riemann, UltraRelativisticWallImpactKeepsFullPrecision) {
  // v = 1 − 1e-12 (γ ≈ 7e5) given by its rapidity: s = e^−φ exactly.
  const auto rigid = make("rigid");
  const double phi = std::atanh(1.0 - 1e-12);
  const RiemannSolution sol = solve_wall(*rigid, State{phi, Stretch::natural()}, Side::left, 0.0, 0.0);
  ASSERT_TRUE(sol.status == Status::ok);
  EXPECT_NEAR(sol.left.stretch.log(), -phi, 1e-15 * phi);
  EXPECT_NEAR(sol.pressure / (0.5 * std::expm1(2.0 * phi)), 1.0, 1e-13);
  // A tiny impact, v = 1e-9: p ≈ v to leading order, with no cancellation.
  const double v = 1e-9;
  const RiemannSolution slow = solve_wall(*rigid, State{std::atanh(v), Stretch::natural()}, Side::left, 0.0, 0.0);
  // (1/s² − 1)/2 with s² = (1 − v)/(1 + v) is exactly v/(1 − v).
  EXPECT_NEAR(slow.pressure / (v / (1.0 - v)), 1.0, 1e-12);
}

TEST(CharacteristicSpeeds, BothFamiliesAtOnceAreTheClosedFormOfEach) {
  // dX/dt = ± c_s / (s γ (1 ± v c_s)) and dx/dt = (v ± c_s)/(1 ± v c_s), written here
  // directly; both families at once (the tracker's regions) must give what each family alone
  // gives, to the bit, and both the closed form.
  const std::shared_ptr<const Material> materials[] = {make("rigid"), make("hooke", 1.0, "wave_speed", 0.5),
                                                       make("constant_sound_speed", 2.0, "sound_speed", 0.3),
                                                       make("rigid_fluid")};
  for (const auto& m : materials) {
    for (double log_s : {-1.5, -0.2, 0.0}) {
      for (double phi : {-4.0, -0.3, 0.0, 0.7, 6.0}) {
        const State st{phi, Stretch::from_log(log_s)};
        FrontSpeeds both[2];
        characteristic_speeds_both(*m, st, both);
        const double c = m->sound_speed(st.stretch), v = std::tanh(phi), s = st.stretch.value(), g = std::cosh(phi);
        for (int k = 0; k < 2; ++k) {
          const int family = k == 0 ? -1 : +1;
          const FrontSpeeds alone = characteristic_speeds(*m, st, family);
          EXPECT_EQ(both[k].lagrangian, alone.lagrangian) << m->model() << " " << phi << " " << log_s;
          EXPECT_EQ(both[k].lab, alone.lab) << m->model() << " " << phi << " " << log_s;
          const double lagrangian = family * c / (s * g * (1.0 + family * v * c));
          const double lab = (v + family * c) / (1.0 + family * v * c);
          // The reference loses digits as 1 − |v| c_s → 0; the code's form does not.
          const double conditioning = 1.0 / (1.0 - std::abs(v) * c);
          EXPECT_NEAR(both[k].lagrangian, lagrangian, 1e-14 * conditioning * std::abs(lagrangian))
              << m->model() << " " << phi;
          EXPECT_NEAR(both[k].lab, lab, 1e-12) << m->model() << " " << phi;
        }
      }
    }
  }
}

}  // namespace
}  // namespace rigidity
