// The generic numeric path (numeric_material.hpp) against the closed forms it must
// reproduce. Two test-only materials are registered in this binary, and so are also
// covered by the registry-wide contract suite (material_contract_test.cpp).

#include "rigidity/numeric_material.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/registry.hpp"

namespace rigidity::testing {
namespace {

/// The rigid law given only as p(s) = (ρ00/2)(1/s² − 1); c_s = 1, so declared linearly degenerate.
class TestRigidPressureLaw final : public PressureLawMaterial {
 public:
  static constexpr std::string_view kName = "test_rigid_pressure_law";
  static std::string doc() { return "Test only: the rigid law given as p(s) alone."; }
  static std::vector<ParameterSpec> parameters() { return {rest_density_parameter()}; }
  /// s ∈ [1e-6, 10]: beyond, e + p ≪ e and the numeric c_s loses its precision.
  static StretchRange window() { return {std::log(1e-6), std::log(10.0)}; }
  explicit TestRigidPressureLaw(const ParameterValues& values)
      : PressureLawMaterial(values.number("rest_density"), window()) {}
  [[nodiscard]] std::string_view model() const override { return kName; }
  [[nodiscard]] bool linearly_degenerate() const override { return true; }

 private:
  [[nodiscard]] double pressure_law(double s) const override { return 0.5 * rest_density() * (1.0 / (s * s) - 1.0); }
};
RIGIDITY_REGISTER_MATERIAL(TestRigidPressureLaw);

/// constant_sound_speed given only as W(s) = ρ00 (s^{−V²} + V² s)/(1 + V²).
class TestConstantSoundSpeedStrainEnergy final : public StrainEnergyMaterial {
 public:
  static constexpr std::string_view kName = "test_constant_sound_speed_strain_energy";
  static std::string doc() { return "Test only: constant_sound_speed given as W(s) alone."; }
  static std::vector<ParameterSpec> parameters() {
    return {rest_density_parameter(), ParameterSpec::number("sound_speed", "V")
                                          .with_dimension(Dimension::velocity)
                                          .require()
                                          .above(0.0)
                                          .at_most(1.0)};
  }
  /// s ∈ [1e-3, 100]: beyond, W is nearly linear in s and its second differences lose W''.
  static StretchRange window() { return {std::log(1e-3), std::log(1e2)}; }
  explicit TestConstantSoundSpeedStrainEnergy(const ParameterValues& values)
      : StrainEnergyMaterial(values.number("rest_density"), window()), v_(values.number("sound_speed")) {}
  [[nodiscard]] std::string_view model() const override { return kName; }
  [[nodiscard]] bool linearly_degenerate() const override { return v_ == 1.0; }

 private:
  [[nodiscard]] double strain_energy_law(double s) const override {
    return rest_density() * (std::pow(s, -v_ * v_) + v_ * v_ * s) / (1.0 + v_ * v_);
  }
  double v_;
};
RIGIDITY_REGISTER_MATERIAL(TestConstantSoundSpeedStrainEnergy);

/// Accuracy the numeric path honestly reaches on these smooth laws (measured: W ~1e-15,
/// W'' ~2e-10 and c_s ~1e-10 for a pressure law; p ~3e-11 of e, W'' ~4e-7 and c_s ~1e-7 at
/// the far end s = 100 of a strain-energy law, ~1e-10 near s = 1), with a margin.
constexpr double kPressureLawEnergyRelTol = 1e-13;
constexpr double kPressureLawStiffnessRelTol = 1e-9;
constexpr double kPressureLawPsiRelTol = 1e-9;
constexpr double kStrainEnergyPressureTol = 1e-10;  // of e
constexpr double kStrainEnergyStiffnessRelTol = 2e-6;
constexpr double kStrainEnergyPsiRelTol = 1e-7;

void expect_close(double actual, double expected, double tol, const char* what, Stretch s) {
  EXPECT_NEAR(actual, expected, tol) << what << " at s = " << s.value();
}

/// The contract grid of `material` less its window ends, where a round trip from a closed-form
/// target may fall just outside the numeric range.
std::vector<Stretch> interior(const Material& material) {
  std::vector<Stretch> grid = stretch_grid(material);
  const StretchRange range = material.admissible();
  std::erase_if(grid, [&](Stretch s) { return s.log() == range.log_min || s.log() == range.log_max; });
  return grid;
}

TEST(PressureLawMaterial, ReproducesRigidFromItsPressureAlone) {
  for (double rho : {1.0, 2.5}) {
    auto numeric = make_material("test_rigid_pressure_law", {{"rest_density", rho}});
    auto exact = make_material("rigid", {{"rest_density", rho}});
    for (Stretch s : interior(*numeric)) {
      // The law takes s as a double: near s = 1 its 1/s² − 1 rounds at ε ρ00, not ε |p|.
      expect_close(numeric->pressure(s), exact->pressure(s), 4 * kEpsilon * (std::abs(exact->pressure(s)) + rho), "p",
                   s);
      expect_close(numeric->strain_energy(s), exact->strain_energy(s),
                   kPressureLawEnergyRelTol * exact->strain_energy(s), "W", s);
      expect_close(numeric->energy_density(s), exact->energy_density(s),
                   kPressureLawEnergyRelTol * exact->energy_density(s), "e", s);
      expect_close(numeric->stiffness(s), exact->stiffness(s), kPressureLawStiffnessRelTol * exact->stiffness(s), "W''",
                   s);
      expect_close(numeric->sound_speed(s), 1.0, kPressureLawStiffnessRelTol, "c_s", s);
      EXPECT_LE(numeric->sound_speed(s), 1.0) << "causal at s = " << s.value();
      expect_close(numeric->riemann_psi(s), exact->riemann_psi(s),
                   kPressureLawPsiRelTol * std::abs(exact->riemann_psi(s)), "Psi", s);

      const Solved<Stretch> at_p = numeric->stretch_at_pressure(exact->pressure(s));
      ASSERT_TRUE(at_p.ok()) << to_string(at_p.status) << " at s = " << s.value();
      expect_close(at_p.value.log(), s.log(), 1e-14 * (1.0 + std::abs(s.log())), "stretch_at_pressure", s);
      const Solved<Stretch> at_psi = numeric->stretch_at_psi(exact->riemann_psi(s));
      ASSERT_TRUE(at_psi.ok()) << to_string(at_psi.status) << " at s = " << s.value();
      expect_close(at_psi.value.log(), s.log(), kPressureLawPsiRelTol * (1.0 + std::abs(s.log())), "stretch_at_psi", s);
    }
    // The limits are the values at the window ends, [1e-6, 10].
    EXPECT_NEAR(numeric->max_pressure(), 0.5 * rho * (1e12 - 1.0), 1e-14 * 0.5 * rho * 1e12);
    EXPECT_NEAR(numeric->max_tension(), 0.5 * rho * (0.01 - 1.0), 4 * kEpsilon);
    EXPECT_NEAR(numeric->psi_max(), std::log(1e6), kPressureLawPsiRelTol * std::log(1e6));
    EXPECT_NEAR(numeric->psi_min(), -std::log(10.0), kPressureLawPsiRelTol * std::log(10.0));
    EXPECT_EQ(numeric->stretch_at_pressure(numeric->max_pressure() * 1.001).status, Status::out_of_range);
    EXPECT_EQ(numeric->stretch_at_pressure(-0.499 * rho).status, Status::out_of_range) << "s = 22 is beyond the window";
  }
}

TEST(StrainEnergyMaterial, ReproducesConstantSoundSpeedFromItsStrainEnergyAlone) {
  for (double v : {0.3, 0.8, 1.0}) {
    auto numeric = make_material("test_constant_sound_speed_strain_energy", {{"sound_speed", v}});
    auto exact = make_material("constant_sound_speed", {{"sound_speed", v}});
    for (Stretch s : interior(*numeric)) {
      const double e = exact->energy_density(s);
      expect_close(numeric->strain_energy(s), exact->strain_energy(s), 4 * kEpsilon * exact->strain_energy(s), "W", s);
      expect_close(numeric->pressure(s), exact->pressure(s), kStrainEnergyPressureTol * e, "p", s);
      expect_close(numeric->stiffness(s), exact->stiffness(s), kStrainEnergyStiffnessRelTol * exact->stiffness(s),
                   "W''", s);
      expect_close(numeric->sound_speed(s), v, kStrainEnergyStiffnessRelTol * v, "c_s", s);
      expect_close(numeric->riemann_psi(s), exact->riemann_psi(s),
                   kStrainEnergyPsiRelTol * std::abs(exact->riemann_psi(s)), "Psi", s);

      const Solved<Stretch> at_p = numeric->stretch_at_pressure(exact->pressure(s));
      ASSERT_TRUE(at_p.ok()) << to_string(at_p.status) << " at s = " << s.value();
      // ln s moves by δp/(s W'') for an error δp in p.
      expect_close(at_p.value.log(), s.log(), 2 * kStrainEnergyPressureTol * e / (s.value() * exact->stiffness(s)),
                   "stretch_at_pressure", s);
      const Solved<Stretch> at_psi = numeric->stretch_at_psi(exact->riemann_psi(s));
      ASSERT_TRUE(at_psi.ok()) << to_string(at_psi.status) << " at s = " << s.value();
      expect_close(at_psi.value.log(), s.log(), 2 * kStrainEnergyPsiRelTol * std::abs(s.log()), "stretch_at_psi", s);
    }
  }
}

/// A pressure law that gives no number beyond s = 2, inside its window [0.1, 10].
class BrokenBeyondTwo final : public PressureLawMaterial {
 public:
  BrokenBeyondTwo() : PressureLawMaterial(1.0, {std::log(0.1), std::log(10.0)}) {}
  [[nodiscard]] std::string_view model() const override { return "broken_beyond_two"; }

 private:
  [[nodiscard]] double pressure_law(double s) const override {
    return s > 2.0 ? std::numeric_limits<double>::quiet_NaN() : 0.5 * (1.0 / (s * s) - 1.0);
  }
};

TEST(NumericMaterial, FailuresAreAStatusOrAnExceptionNeverANumber) {
  const BrokenBeyondTwo broken;  // GSL would abort the process here if its handler were on
  const Stretch three = Stretch::from_value(3.0);
  EXPECT_EQ(broken.strain_energy_estimate(three).status, Status::not_converged);
  EXPECT_EQ(broken.riemann_psi_estimate(three).status, Status::not_converged);
  EXPECT_EQ(broken.sound_speed_estimate(three).status, Status::not_converged);
  EXPECT_THROW(static_cast<void>(broken.strain_energy(three)), NumericalError);
  EXPECT_THROW(static_cast<void>(broken.riemann_psi(three)), NumericalError);
  EXPECT_THROW(static_cast<void>(broken.max_tension()), NumericalError);
  EXPECT_FALSE(broken.stretch_at_pressure(-0.2).ok());
  EXPECT_FALSE(broken.stretch_at_psi(-0.5).ok());
  // Where the law holds, everything works.
  const Stretch half = Stretch::from_value(0.5);
  EXPECT_NEAR(broken.strain_energy(half), 0.5 * (2.0 + 0.5), 1e-13);
  EXPECT_NEAR(broken.riemann_psi(half), std::log(2.0), 1e-9);
  EXPECT_NEAR(broken.max_pressure(), 0.5 * (100.0 - 1.0), 1e-13);
}

/// The rigid law on a window of the caller's choosing.
class RigidOn final : public PressureLawMaterial {
 public:
  explicit RigidOn(StretchRange window) : PressureLawMaterial(1.0, window) {}
  [[nodiscard]] std::string_view model() const override { return "rigid_on"; }

 private:
  [[nodiscard]] double pressure_law(double s) const override { return 0.5 * (1.0 / (s * s) - 1.0); }
};

TEST(NumericMaterial, NeedsAFiniteWindowAroundTheNaturalState) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(RigidOn({-inf, 1.0}), std::invalid_argument);
  EXPECT_THROW(RigidOn({-1.0, inf}), std::invalid_argument);
  EXPECT_THROW(RigidOn({0.5, 1.0}), std::invalid_argument) << "s = 1 outside";
  EXPECT_NO_THROW(RigidOn({-1.0, 0.0})) << "a fluid's window may end at s = 1";
  const RigidOn fluid({-1.0, 0.0});
  EXPECT_EQ(fluid.max_tension(), 0.0);
  EXPECT_EQ(fluid.psi_min(), 0.0);
  const Solved<Stretch> natural = fluid.stretch_at_pressure(0.0);
  ASSERT_TRUE(natural.ok());
  EXPECT_EQ(natural.value.log(), 0.0);
  EXPECT_EQ(fluid.stretch_at_pressure(-1e-9).status, Status::out_of_range);
  EXPECT_EQ(NumericMaterial::default_window().log_min, std::log(1e-6));
  EXPECT_EQ(NumericMaterial::default_window().log_max, std::log(1e6));
}

}  // namespace
}  // namespace rigidity::testing
