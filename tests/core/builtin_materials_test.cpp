// The four built-in materials against the physics they stand for: the reference values of
// docs/materials.md, the jump conditions of docs/physics.md, the limits V → 1 and V → 0 of `hooke`, the
// identities that define `rigid_fluid` and `constant_sound_speed`, and full precision at
// tiny strains.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "rigidity/material.hpp"

namespace rigidity::testing {
namespace {

/// Closed-form identities and reference values hold to this relative error.
constexpr double kClosedFormRelTol = 1e-12;
/// docs/materials.md prints s and p to ten digits.
constexpr double kSpecTableAbsTol = 5e-11;

std::shared_ptr<const Material> rigid(double rho = 1.0) { return make_material("rigid", {{"rest_density", rho}}); }
std::shared_ptr<const Material> hooke(double v, double rho = 1.0) {
  return make_material("hooke", {{"wave_speed", v}, {"rest_density", rho}});
}
std::shared_ptr<const Material> rigid_fluid(double rho = 1.0) {
  return make_material("rigid_fluid", {{"rest_density", rho}});
}
std::shared_ptr<const Material> constant_sound_speed(double v, double rho = 1.0) {
  return make_material("constant_sound_speed", {{"sound_speed", v}, {"rest_density", rho}});
}

void expect_relative(double actual, double expected, double tol, const std::string& what) {
  EXPECT_NEAR(actual, expected, tol * std::abs(expected)) << what;
}

// ---- docs/materials.md reference values: a bar at velocity v against a fixed wall -------------------

struct WallImpact {
  const char* material;
  double parameter;  ///< V for hooke (unused for rigid)
  double v;
  double s_exact;
  double p_exact;
  double s_table;  ///< as printed in docs/materials.md
  double p_table;
  double front_speed;  ///< relative to the unstrained bar
};

class WallImpactReference : public ::testing::TestWithParam<WallImpact> {
 protected:
  [[nodiscard]] std::shared_ptr<const Material> material() const {
    const WallImpact& c = GetParam();
    return std::string(c.material) == "rigid" ? rigid() : hooke(c.parameter);
  }
};

TEST_P(WallImpactReference, StretchAndPressureBehindTheFront) {
  const WallImpact& c = GetParam();
  auto m = material();
  ASSERT_TRUE(m->linearly_degenerate());
  // Linearly degenerate: J+ = φ + Ψ is continuous across the − front, so behind it
  // (φ = 0) Ψ(s) = artanh v.
  const Solved<Stretch> s = m->stretch_at_psi(std::atanh(c.v));
  ASSERT_TRUE(s.ok());
  expect_relative(s.value.value(), c.s_exact, kClosedFormRelTol, "s behind the front");
  expect_relative(m->pressure(s.value), c.p_exact, kClosedFormRelTol, "p behind the front");
  EXPECT_NEAR(s.value.value(), c.s_table, kSpecTableAbsTol);
  EXPECT_NEAR(m->pressure(s.value), c.p_table, kSpecTableAbsTol);
}

TEST_P(WallImpactReference, JumpConditionsHoldAcrossTheFront) {
  // Ahead: (v, s = 1); behind: (0, s*). Labels: −σ [s/γ] − [v] = 0; momentum:
  // −σ [(e+p) γ v s] + [p] = 0 (docs/physics.md), σ = dX/dt of the front.
  const WallImpact& c = GetParam();
  auto m = material();
  const Stretch natural = Stretch::natural();
  const Stretch behind = m->stretch_at_psi(std::atanh(c.v)).value;
  const double gamma = 1.0 / std::sqrt(1.0 - c.v * c.v);
  const double sigma = c.v / (behind.value() - 1.0 / gamma);  // from the labels law
  const double momentum_ahead = m->enthalpy_density(natural) * gamma * c.v;
  const double pressure_jump = m->pressure(behind) - m->pressure(natural);
  expect_relative(pressure_jump, sigma * (0.0 - momentum_ahead), kClosedFormRelTol, "momentum jump");
  // Lab speed of the front x' = v + σ x_X (x_X = s/γ ahead), and relative to the bar:
  const double lab = c.v + sigma / gamma;
  const double relative = (lab - c.v) / (1.0 - lab * c.v);
  expect_relative(-relative, c.front_speed, kClosedFormRelTol, "front speed relative to the bar");
  expect_relative(m->sound_speed(natural), c.front_speed, kClosedFormRelTol, "c_s(1)");
}

INSTANTIATE_TEST_SUITE_P(Spec, WallImpactReference,
                         ::testing::Values(WallImpact{"rigid", 1.0, 0.6, 0.5, 1.5, 0.5, 1.5, 1.0},
                                           WallImpact{"rigid", 1.0, 0.8, 1.0 / 3.0, 4.0, 1.0 / 3.0, 4.0, 1.0},
                                           WallImpact{"hooke", 0.5, 0.2, std::sqrt(3.0 / 8.0), 1.0 / 9.0, 0.6123724357,
                                                      0.1111111111, 0.5}),
                         [](const ::testing::TestParamInfo<WallImpact>& param) {
                           return std::string(param.param.material) + "_at_" +
                                  std::to_string(static_cast<int>(std::lround(param.param.v * 100))) + "_percent_c";
                         });

TEST(Messages, AStretchOutsideTheRangeIsPrintedWithEveryDigit) {
  // The stretch in the message reads back to the very double (shortest round-trip form),
  // where six significant digits printed 1.0000000001 as 1.
  const auto m = rigid_fluid();
  for (const Stretch s : {Stretch::from_log(1e-10), Stretch::from_value(1e12), Stretch::from_log(0.3)}) {
    const std::string message = m->admissibility_violation(s);
    const std::string::size_type at = message.find("stretch ");
    ASSERT_NE(at, std::string::npos) << message;
    EXPECT_EQ(std::stod(message.substr(at + 8)), s.value()) << message;
  }
}

TEST(Rigid, StretchBehindAWallImpactIsTheDopplerFactor) {
  // Paper eq. (15): s = sqrt((1 − v)/(1 + v)).
  auto m = rigid();
  for (double v : {1e-6, 0.1, 0.6, 0.8, 0.99, 0.999999}) {
    const Solved<Stretch> s = m->stretch_at_psi(std::atanh(v));
    ASSERT_TRUE(s.ok());
    expect_relative(s.value.value(), std::sqrt((1.0 - v) / (1.0 + v)), kClosedFormRelTol, "v = " + std::to_string(v));
  }
}

TEST(Rigid, LimitsAndLaw) {
  for (double rho : {1.0, 2.5}) {
    auto m = rigid(rho);
    EXPECT_EQ(m->max_tension(), -0.5 * rho);
    EXPECT_EQ(m->max_pressure(), std::numeric_limits<double>::infinity());
    EXPECT_EQ(m->psi_max(), std::numeric_limits<double>::infinity());
    EXPECT_EQ(m->psi_min(), -std::numeric_limits<double>::infinity());
    EXPECT_TRUE(m->linearly_degenerate());
    for (double s : {1e-9, 0.3, 2.0, 1e12}) {
      const Stretch st = Stretch::from_value(s);
      expect_relative(m->pressure(st), 0.5 * rho * (1.0 / (s * s) - 1.0), kClosedFormRelTol, "p (paper eq. 19)");
      expect_relative(m->energy_density(st), 0.5 * rho * (1.0 / (s * s) + 1.0), kClosedFormRelTol, "e (eq. 24)");
      expect_relative(m->strain_energy(st), 0.5 * rho * (1.0 / s + s), kClosedFormRelTol, "W (eq. 16)");
      expect_relative(m->riemann_psi(st), -std::log(s), kClosedFormRelTol, "Psi");
      EXPECT_EQ(m->sound_speed(st), 1.0);
    }
    EXPECT_EQ(m->stretch_at_pressure(-0.5 * rho).status, Status::out_of_range);
  }
}

// ---- hooke ----------------------------------------------------------------------------

TEST(Hooke, LawLimitsAndRanges) {
  for (double b : {0.1, 0.5, 0.9}) {
    auto m = hooke(b, 2.0);
    const double a2 = 1.0 - b * b;
    EXPECT_NEAR(m->max_pressure(), 2.0 * b * b / a2, kClosedFormRelTol * m->max_pressure());
    EXPECT_NEAR(m->max_tension(), -2.0 * b / (1.0 + b), kClosedFormRelTol);
    EXPECT_NEAR(m->psi_max(), std::atanh(b), kClosedFormRelTol);
    EXPECT_TRUE(m->linearly_degenerate());
    for (double s : {1e-9, 0.3, 2.0, 1e12}) {
      const Stretch st = Stretch::from_value(s);
      const double r = std::sqrt(b * b + a2 / (s * s));  // docs/materials.md
      const double e = 2.0 * (r - b * b) / a2;
      const std::string at = "b = " + std::to_string(b) + ", s = " + std::to_string(s);
      expect_relative(m->energy_density(st), e, 1e-9, "e " + at);  // the closed form cancels: 1e-9
      expect_relative(m->pressure(st), e / r - 2.0, 1e-9, "p " + at);
      expect_relative(m->sound_speed(st), b * s / std::sqrt(b * b * s * s + a2), kClosedFormRelTol, "c_s " + at);
      expect_relative(m->riemann_psi(st), std::asinh(b / std::sqrt(a2)) - std::asinh(b * s / std::sqrt(a2)), 1e-9,
                      "Psi " + at);
    }
    // An impact at v >= V cannot stop the bar: no stretch has Ψ = artanh v (docs/materials.md).
    EXPECT_EQ(m->stretch_at_psi(std::atanh(b)).status, Status::out_of_range);
    EXPECT_EQ(m->stretch_at_psi(std::atanh(std::min(1.0 - 1e-12, 1.01 * b))).status, Status::out_of_range);
    EXPECT_EQ(m->stretch_at_pressure(m->max_pressure()).status, Status::out_of_range);
    EXPECT_TRUE(m->stretch_at_psi(std::atanh(0.99 * b)).ok());
  }
}

TEST(Hooke, WaveSpeedOneIsExactlyRigid) {
  auto h = hooke(1.0, 1.7);
  auto r = rigid(1.7);
  for (Stretch s : stretch_grid(*r)) {
    // exp(±k ln s) carries the rounding of its argument: a few ulps times (1 + |ln s|).
    const double kRoundOff = 8 * kEpsilon * (1.0 + std::abs(s.log()));
    const std::string at = "s = " + std::to_string(s.value());
    expect_relative(h->pressure(s), r->pressure(s), kRoundOff, "p " + at);
    expect_relative(h->energy_density(s), r->energy_density(s), kRoundOff, "e " + at);
    expect_relative(h->strain_energy(s), r->strain_energy(s), kRoundOff, "W " + at);
    expect_relative(h->stiffness(s), r->stiffness(s), kRoundOff, "W'' " + at);
    EXPECT_EQ(h->sound_speed(s), 1.0) << at;
    EXPECT_NEAR(h->riemann_psi(s), r->riemann_psi(s), kRoundOff) << at;
  }
  for (double p : {-0.8, -0.1, 0.0, 1e-9, 3.0, 1e12}) {
    EXPECT_NEAR(h->stretch_at_pressure(p).value.log(), r->stretch_at_pressure(p).value.log(), 1e-14) << "p " << p;
  }
  for (double psi : {-25.0, -1.0, 0.0, 0.3, 25.0}) {
    EXPECT_NEAR(h->stretch_at_psi(psi).value.log(), r->stretch_at_psi(psi).value.log(), 1e-14) << "psi " << psi;
  }
  EXPECT_EQ(h->max_pressure(), r->max_pressure());
  EXPECT_EQ(h->max_tension(), r->max_tension());
  EXPECT_EQ(h->psi_max(), r->psi_max());
}

TEST(Hooke, WaveSpeedNearOneApproachesRigid) {
  // V = 1 − δ changes the law by O(a² (1 + 1/s²)) with a² = 1 − V² ≈ 2δ.
  const double v = 1.0 - 1e-9;
  const double a2 = 2e-9;
  auto h = hooke(v);
  auto r = rigid();
  for (double s : {0.1, 0.5, 0.9, 1.1, 2.0, 10.0}) {
    const Stretch st = Stretch::from_value(s);
    const double allowed = 10.0 * a2 * (1.0 + 1.0 / (s * s));
    expect_relative(h->pressure(st), r->pressure(st), allowed, "p at s = " + std::to_string(s));
    expect_relative(h->energy_density(st), r->energy_density(st), allowed, "e at s = " + std::to_string(s));
    EXPECT_NEAR(h->sound_speed(st), 1.0, allowed);
    EXPECT_NEAR(h->riemann_psi(st), r->riemann_psi(st), allowed);
  }
}

TEST(Hooke, NewtonianLimitIsHookesLawToSecondOrder) {
  // p = ρ00 V² (1 − s) + (3/2) ρ00 V⁴ (1 − s)² + O((1 − s)³) (series of docs/materials.md's law):
  // Young's modulus E = ρ00 V², and the error of Hooke's law falls as the strain squared.
  const double v = 1e-3;
  const double rho = 3.0;
  auto m = hooke(v, rho);
  EXPECT_NEAR(m->stiffness(Stretch::natural()), rho * v * v, kClosedFormRelTol * rho * v * v);
  double previous_error = 0.0;
  for (double strain : {1e-2, 5e-3, 2.5e-3, 1.25e-3}) {
    for (double sign : {-1.0, 1.0}) {
      const double eps = sign * strain;
      const double newtonian = -rho * v * v * eps;  // ρ00 V² (1 − s)
      const double error = m->pressure(Stretch::from_strain(eps)) - newtonian;
      EXPECT_NEAR(error / (1.5 * rho * std::pow(v, 4) * eps * eps), 1.0, 2.0 * strain) << "strain " << eps;
      if (sign < 0) continue;
      if (previous_error != 0.0) {
        EXPECT_NEAR(previous_error / error, 4.0, 0.05) << "halving the strain to " << eps;
      }
      previous_error = error;
    }
  }
}

// ---- rigid_fluid --------------------------------------------------------------------------

TEST(RigidFluid, EnergyIsRestEnergyPlusPressure) {
  for (double rho : {1.0, 0.25}) {
    auto m = rigid_fluid(rho);
    auto r = rigid(rho);
    for (Stretch s : stretch_grid(*m)) {
      const std::string at = "s = " + std::to_string(s.value());
      expect_relative(m->energy_density(s), rho + m->pressure(s), kClosedFormRelTol, "e = rho00 + p at " + at);
      expect_relative(m->pressure(s), r->pressure(s), kClosedFormRelTol, "p as rigid at " + at);
      expect_relative(m->energy_density(s), r->energy_density(s), kClosedFormRelTol, "e as rigid at " + at);
      EXPECT_EQ(m->riemann_psi(s), r->riemann_psi(s)) << at;
      EXPECT_EQ(m->sound_speed(s), 1.0) << at;
    }
  }
}

TEST(RigidFluid, CarriesNoTension) {
  auto m = rigid_fluid();
  EXPECT_EQ(m->admissible().log_max, 0.0);
  EXPECT_EQ(m->max_tension(), 0.0);
  EXPECT_EQ(m->cavitation_pressure(), 0.0);
  EXPECT_EQ(m->psi_min(), 0.0);
  EXPECT_NE(m->admissibility_violation(Stretch::from_value(2.0)), "");
  EXPECT_NE(m->admissibility_violation(Stretch::from_strain(1e-12)), "");
  EXPECT_EQ(m->admissibility_violation(Stretch::from_strain(-1e-12)), "");
  EXPECT_EQ(m->stretch_at_pressure(-1e-300).status, Status::out_of_range);
  EXPECT_EQ(m->stretch_at_psi(-1e-300).status, Status::out_of_range);
  const Solved<Stretch> natural = m->stretch_at_pressure(0.0);
  ASSERT_TRUE(natural.ok());
  EXPECT_EQ(natural.value.log(), 0.0);
}

// ---- constant_sound_speed ------------------------------------------------------------------

TEST(ConstantSoundSpeed, PressureOverEnergyDerivativeIsVSquared) {
  // dp/de by fourth-order differences in ln s: truncation ~h⁴, rounding ~ε e/(h |de/d ln s|)
  // with de/d ln s = −(e + p), which is why the stretches stop at 30 (e + p ≪ e beyond).
  constexpr double kRelTol = 1e-9;
  const double h = 1e-3;
  const double rho = 1.3;
  for (double v : {0.05, 0.3, 0.7, 1.0}) {
    auto m = constant_sound_speed(v, rho);
    for (double s : {1e-6, 0.2, 0.9, 1.0, 1.5, 30.0}) {
      const double t = std::log(s);
      auto pressure = [&](double x) { return m->pressure(Stretch::from_log(x)); };
      auto energy = [&](double x) { return m->energy_density(Stretch::from_log(x)); };
      const double dp = central_difference(pressure, t, h);
      const double de = central_difference(energy, t, h);
      EXPECT_NEAR(dp / de, v * v, kRelTol * v * v) << "V = " << v << ", s = " << s;
      // e + p = ρ00 s^{−(1+V²)}, to the rounding of e and p.
      const Stretch st = Stretch::from_log(t);
      EXPECT_NEAR(m->enthalpy_density(st), rho * std::pow(s, -(1.0 + v * v)),
                  kClosedFormRelTol * (m->energy_density(st) + std::abs(m->pressure(st))))
          << "V = " << v << ", s = " << s;
    }
  }
}

TEST(ConstantSoundSpeed, GenuinelyNonlinearBelowLight) {
  EXPECT_FALSE(constant_sound_speed(0.5)->linearly_degenerate());
  EXPECT_FALSE(constant_sound_speed(0.999)->linearly_degenerate());
  EXPECT_TRUE(constant_sound_speed(1.0)->linearly_degenerate());
  auto m = constant_sound_speed(0.4, 2.0);
  EXPECT_NEAR(m->max_tension(), -2.0 * 0.16 / 1.16, kClosedFormRelTol);
  expect_relative(m->riemann_psi(Stretch::from_value(0.01)), -0.4 * std::log(0.01), kClosedFormRelTol, "Psi = -V ln s");
}

TEST(ConstantSoundSpeed, SoundSpeedOneIsRigid) {
  auto m = constant_sound_speed(1.0);
  auto r = rigid();
  for (Stretch s : stretch_grid(*r)) {
    expect_relative(m->pressure(s), r->pressure(s), kClosedFormRelTol, "p");
    expect_relative(m->energy_density(s), r->energy_density(s), kClosedFormRelTol, "e");
  }
}

// ---- far beyond the contract range -------------------------------------------------------------

TEST(ExtremeStretches, UltraRelativisticImpactsKeepTheirStretch) {
  // Behind a wall impact at rapidity φ, Ψ(s) = φ: for the materials with c_s = c, s = e^{−φ}
  // however large φ is (a Lorentz factor of 1e130 at φ = 300).
  for (const auto& [model, values] : std::vector<std::pair<std::string, std::map<std::string, double>>>{
           {"rigid", {}},
           {"rigid_fluid", {}},
           {"hooke", {{"wave_speed", 1.0}}},
           {"constant_sound_speed", {{"sound_speed", 1.0}}}}) {
    auto m = make_material(model, values);
    for (double rapidity : {20.0, 40.0, 100.0, 300.0, 700.0}) {
      const Solved<Stretch> s = m->stretch_at_psi(rapidity);
      ASSERT_TRUE(s.ok()) << model << " at rapidity " << rapidity;
      EXPECT_NEAR(s.value.log(), -rapidity, 4 * kEpsilon * rapidity) << model << " at rapidity " << rapidity;
    }
  }
}

TEST(ExtremeStretches, NoNaNEvenWhereValuesOverflow) {
  // Between e^±700 a value may overflow to inf where the true value is beyond 1e308, but never NaN.
  for (const auto& [model, values] : std::vector<std::pair<std::string, std::map<std::string, double>>>{
           {"rigid", {}},
           {"rigid_fluid", {}},
           {"hooke", {{"wave_speed", 1e-6}}},
           {"hooke", {{"wave_speed", 0.5}}},
           {"hooke", {{"wave_speed", 1.0}}},
           {"constant_sound_speed", {{"sound_speed", 1e-6}}},
           {"constant_sound_speed", {{"sound_speed", 0.5}}},
           {"constant_sound_speed", {{"sound_speed", 1.0}}}}) {
    auto m = make_material(model, values);
    for (double t : {-700.0, -300.0, -100.0, 100.0, 300.0, 700.0}) {
      const Stretch s = Stretch::from_log(t);
      if (!m->admissible().contains(s)) continue;
      SCOPED_TRACE(model + " at ln s = " + std::to_string(t));
      for (double v : {m->pressure(s), m->energy_density(s), m->strain_energy(s), m->sound_speed(s), m->stiffness(s),
                       m->riemann_psi(s), m->enthalpy_density(s)}) {
        EXPECT_FALSE(std::isnan(v));
      }
      const Solved<Stretch> at_p = m->stretch_at_pressure(m->pressure(s));
      EXPECT_TRUE(!at_p.ok() || std::isfinite(at_p.value.log()));
      const Solved<Stretch> at_psi = m->stretch_at_psi(m->riemann_psi(s));
      EXPECT_TRUE(!at_psi.ok() || std::isfinite(at_psi.value.log()));
    }
  }
}

// ---- precision at tiny strains -----------------------------------------------------------------

struct SmallStrainSeries {
  std::string model;
  std::map<std::string, double> values;
  /// p/ρ00 = c1 ε + c2 ε² + O(ε³) at s = 1 + ε.
  double c1;
  double c2;
  bool compression_only;
};

TEST(SmallStrain, PressureKeepsFullPrecisionAtStrainOneInATrillion) {
  // p at s = 1 ± 1e-12 against its Taylor series (whose ε³ term is ~1e-24 relative):
  // computing 1/s² − 1 naively would keep only ~4 digits.
  constexpr double kRelTol = 1e-10;
  const double b = 0.3;
  const double v = 0.6;
  const std::vector<SmallStrainSeries> cases = {
      {"rigid", {}, -1.0, 1.5, false},
      {"rigid_fluid", {}, -1.0, 1.5, true},
      {"hooke", {{"wave_speed", b}}, -b * b, 1.5 * std::pow(b, 4), false},
      {"hooke", {{"wave_speed", 1.0}}, -1.0, 1.5, false},
      {"constant_sound_speed", {{"sound_speed", v}}, -v * v, v * v * (v * v + 2.0) / 2.0, false},
  };
  for (const SmallStrainSeries& c : cases) {
    auto m = make_material(c.model, c.values);
    for (double eps : {-1e-12, 1e-12, -3.7e-9}) {
      if (c.compression_only && eps > 0.0) continue;
      const double series = c.c1 * eps + c.c2 * eps * eps;
      EXPECT_NEAR(m->pressure(Stretch::from_strain(eps)), series, kRelTol * std::abs(series))
          << c.model << " at strain " << eps;
      const Solved<Stretch> back = m->stretch_at_pressure(series);
      ASSERT_TRUE(back.ok());
      EXPECT_NEAR(back.value.strain(), eps, kRelTol * std::abs(eps)) << c.model << " inverse at strain " << eps;
    }
  }
  // Every built-in is in the table (but `tabulated`, whose law is a table: tabulated_test.cpp, and
  // `formula`, whose expression takes s, not ln s, so that a strain of 1e-12 keeps only ~1e-4 of its
  // digits: formula_scene_test.cpp).
  for (const std::string& name : kBuiltinMaterials) {
    if (name == "tabulated" || name == "formula") continue;
    EXPECT_TRUE(std::any_of(cases.begin(), cases.end(), [&](const SmallStrainSeries& c) { return c.model == name; }))
        << name;
  }
}

}  // namespace
}  // namespace rigidity::testing
