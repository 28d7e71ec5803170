// The front tracker's closed forms (solvers/src/characteristics/front_math.hpp) against the
// independent laws and Riemann solutions of tests/exact: a wave's strength, a front's speed
// from the label jump condition, and the star state of two states of one material.
#include "front_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <tuple>

#include "core/material_test_support.hpp"
#include "exact/riemann.hpp"

namespace rigidity {
namespace {

using characteristics::CrossingEnds;
using characteristics::CurveEnd;
using characteristics::label_jump_speeds;
using characteristics::same_material_star;
using characteristics::wave_strength;

State state(double v, double s) { return State{std::atanh(v), Stretch::from_value(s)}; }

TEST(FrontMath, WaveStrengthIsTheJumpOfTheFamilysOwnInvariant) {
  const auto gas = testing::make_material("constant_sound_speed", {{"rest_density", 1.3}, {"sound_speed", 0.5}});
  const auto law = exact::constant_sound_speed(1.3, 0.5);
  const State a = state(0.2, 0.8), b = state(-0.1, 1.1);
  for (int family : {-1, +1}) {
    const double expected = (b.rapidity - a.rapidity) + family * (law.psi(1.1) - law.psi(0.8));
    EXPECT_NEAR(wave_strength(*gas, a, b, family), expected, 1e-14) << family;
    EXPECT_NEAR(wave_strength(*gas, b, a, family), -expected, 1e-14) << "signed, from a to b";
  }
}

TEST(FrontMath, LabelJumpSpeedsKeepLabPositionsContinuous) {
  // m [s/γ] = −[v]: the front's lab speed, v + m s/γ, is the same seen from either side. Jumps
  // of both families, 0.1 and 0.3 in Ψ along the other family's invariant (a fan step's).
  const auto hooke = testing::make_material("hooke", {{"rest_density", 1.0}, {"wave_speed", 0.6}});
  const auto law = exact::hooke(1.0, 0.6);
  for (int family : {-1, +1}) {
    for (double step : {0.1, 0.3}) {
      const double psi_a = law.psi(0.95), phi_a = 0.2;
      const double psi_b = psi_a + step, phi_b = phi_a + family * step;
      const State a{phi_a, Stretch::from_value(law.stretch_at_psi(psi_a))};
      const State b{phi_b, Stretch::from_value(law.stretch_at_psi(psi_b))};
      const FrontSpeeds sp = label_jump_speeds(*hooke, a, b, family);
      const double va = std::tanh(phi_a), vb = std::tanh(phi_b);
      const double la = a.stretch.value() / std::cosh(phi_a), lb = b.stretch.value() / std::cosh(phi_b);
      EXPECT_NEAR(sp.lagrangian * (lb - la), -(vb - va), 1e-13) << family << " " << step;
      EXPECT_GT(family * sp.lagrangian, 0.0) << "it runs the family's way";
      // In the lab a label moves at v; the front passes labels at m, each s/γ long in the lab.
      EXPECT_NEAR(va + sp.lagrangian * la, vb + sp.lagrangian * lb, 1e-13);
      EXPECT_NEAR(sp.lab, va + sp.lagrangian * la, 1e-13);
    }
  }
}

TEST(FrontMath, AWeakFrontMovesAtTheCharacteristicSpeedOfItsMeanToSecondOrder) {
  const auto gas = testing::make_material("constant_sound_speed", {{"rest_density", 1.0}, {"sound_speed", 0.5}});
  const auto law = exact::constant_sound_speed(1.0, 0.5);
  for (int family : {-1, +1}) {
    double previous = 0.0;
    for (double step : {1e-2, 5e-3}) {
      // A simple wave of this family: the other invariant the same on both sides.
      const double psi_a = law.psi(0.9), psi_b = psi_a + step;
      const double phi_a = 0.1, phi_b = phi_a + family * step;
      const exact::State<double> ea{phi_a, law.stretch_at_psi(psi_a)}, eb{phi_b, law.stretch_at_psi(psi_b)};
      const exact::State<double> mean{0.5 * (phi_a + phi_b), law.stretch_at_psi(0.5 * (psi_a + psi_b))};
      const State a{phi_a, Stretch::from_value(ea.stretch)}, b{phi_b, Stretch::from_value(eb.stretch)};
      const double miss =
          std::abs(label_jump_speeds(*gas, a, b, family).lagrangian - exact::characteristic_speed(law, mean, family));
      EXPECT_LT(miss, 2.0 * step * step) << family;
      if (previous > 0.0) {
        EXPECT_GT(previous / miss, 3.0) << "halving the step quarters the miss";
      }
      previous = miss;
    }
  }
}

TEST(FrontMath, TheSameMaterialStarIsTheExactRiemannSolutions) {
  const auto gas = testing::make_material("constant_sound_speed", {{"rest_density", 1.0}, {"sound_speed", 0.5}});
  const auto law = exact::constant_sound_speed(1.0, 0.5);
  // A shock and a fan; two fans; two shocks.
  for (const auto& [vl, sl, vr, sr] :
       {std::tuple{0.3, 0.8, 0.0, 1.0}, std::tuple{-0.2, 1.0, 0.2, 1.0}, std::tuple{0.25, 1.0, -0.25, 1.0}}) {
    const State left = state(vl, sl), right = state(vr, sr);
    const exact::Solution<double> ref = exact::riemann_problem(law, exact::State<double>{left.rapidity, sl}, law,
                                                               exact::State<double>{right.rapidity, sr});
    ASSERT_TRUE(ref.solved);
    CrossingEnds ends{
        CurveEnd{left, gas->riemann_psi(left.stretch), characteristic_speeds(*gas, left, -1).lagrangian, {}},
        CurveEnd{right, gas->riemann_psi(right.stretch), characteristic_speeds(*gas, right, +1).lagrangian, {}}};
    const double j_plus = left.rapidity + ends.left.psi, j_minus = right.rapidity - ends.right.psi;
    const State guess{0.5 * (j_plus + j_minus), gas->stretch_at_psi(0.5 * (j_plus - j_minus)).value};
    const Solved<characteristics::SameMaterialStar> star = same_material_star(*gas, ends, guess);
    ASSERT_TRUE(star.ok());
    EXPECT_NEAR(star.value.state.rapidity, ref.left.star.rapidity, 1e-11) << vl << " " << vr;
    EXPECT_NEAR(star.value.state.stretch.value(), ref.left.star.stretch, 1e-11) << vl << " " << vr;
    EXPECT_TRUE(star.value.converged);
  }
}

}  // namespace
}  // namespace rigidity
