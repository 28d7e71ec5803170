// The material contract (material.hpp, docs/physics.md), checked for every registered material
// at once: the suite is instantiated over MaterialRegistry::instance().names(), so a
// material added later (built in or registered by a test) is covered without edits.
//
// Each material is built with its defaults, with every required number set in turn to a
// few values across its declared range (e.g. V ∈ {0.1, 0.5, 0.999, 1}), and once more with
// rest_density = 2.5; then checked on a grid of stretches across its admissible range,
// 1e-9 to 1e12 where the range allows.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "rigidity/numeric_material.hpp"
#include "rigidity/registry.hpp"

namespace rigidity::testing {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Closed-form identities hold to this relative error (their rounding is a few ulps).
constexpr double kClosedFormRelTol = 1e-12;

/// How closely a material meets the contract. Closed forms are held to kClosedFormRelTol; a
/// numeric material to the accuracy its header states.
struct ContractTolerances {
  /// Relative error of each function value (p, e, W, W'', c_s, Ψ).
  double value = kClosedFormRelTol;
  /// Absolute error of p and of W, in units of e (a numeric p = −W' rounds at the scale of W).
  double pressure_noise = 0.0;
  /// Relative error of c_s and W'' (numeric derivatives).
  double sound_speed = kClosedFormRelTol;
  /// Relative error of Ψ.
  double psi = kClosedFormRelTol;
  /// Relative error of Ψ beyond its rounding: 0 for a closed form, the quadrature's for a numeric one.
  double psi_noise = 0.0;
};

ContractTolerances tolerances_for(const Material& material) {
  ContractTolerances tol;
  if (dynamic_cast<const PressureLawMaterial*>(&material) != nullptr) {
    tol.pressure_noise = 1e-13;  // W by quadrature
    tol.sound_speed = 1e-9;      // W'' by central differences
    tol.psi = 1e-9;
    tol.psi_noise = tol.psi;
  } else if (dynamic_cast<const StrainEnergyMaterial*>(&material) != nullptr) {
    tol.pressure_noise = 1e-10;  // p by central differences
    tol.sound_speed = 1e-6;      // W'' by second differences
    tol.psi = 1e-7;
    tol.psi_noise = tol.psi;
  }
  return tol;
}

/// Step in ln s of the finite differences the tests take, and the relative error allowed for
/// their truncation (fourth order: ~h⁴ times the fifth derivative, ~1e-13 here).
constexpr double kFiniteDifferenceStep = 1e-3;
constexpr double kFiniteDifferenceRelTol = 1e-9;
/// Relative accuracy of the independent quadrature of Ψ.
constexpr double kReferenceQuadratureRelTol = 1e-12;
/// Rounding error, in ulps, allowed on each side of an inverse round trip.
constexpr double kRoundTripUlps = 64.0;

// ---- the instances to check -----------------------------------------------------------

struct MaterialCase {
  std::string model;
  std::map<std::string, double> values;
  std::string label;                         ///< test-name suffix
  std::map<std::string, std::string> texts;  ///< required texts (kTextSamples); default: the first sample
};

/// A few values across the declared range of a required number: for (0, 1], {0.1, 0.5, 0.999, 1}.
std::vector<double> sample_values(const ParameterSpec& spec) {
  std::vector<double> out;
  if (spec.lower && spec.upper) {
    const double lo = spec.lower->value;
    const double hi = spec.upper->value;
    for (double f : {0.1, 0.5, 0.999}) out.push_back(lo + f * (hi - lo));
    if (spec.upper->inclusive) out.push_back(hi);
  } else if (spec.lower) {
    for (double d : {0.5, 1.0, 10.0}) out.push_back(spec.lower->value + d);
  } else if (spec.upper) {
    for (double d : {0.5, 1.0, 10.0}) out.push_back(spec.upper->value - d);
  } else {
    out = {0.5, 1.0, 2.0};
  }
  return out;
}

/// v for a test name: 0.5 → "0p5", -1e-06 → "m1em06".
std::string label_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  std::string out;
  for (const char c : std::string(buffer)) {
    if (c == '.')
      out += 'p';
    else if (c == '-')
      out += 'm';
    else if (c != '+')
      out += c;
  }
  return out;
}

std::vector<MaterialCase> registry_cases() {
  std::vector<MaterialCase> cases;
  for (const std::string& name : MaterialRegistry::instance().names()) {
    const MaterialInfo& info = MaterialRegistry::instance().at(name);
    std::map<std::string, std::vector<double>> samples;
    std::size_t count = 1;
    for (const ParameterSpec& spec : info.parameters) {
      if (!spec.required || spec.type != ParameterType::number) continue;
      samples[spec.name] = sample_values(spec);
      count = std::max(count, samples[spec.name].size());
    }
    for (std::size_t i = 0; i < count; ++i) {
      MaterialCase c{name, {}, name, {}};
      for (const auto& [key, values] : samples) {
        c.values[key] = values[std::min(i, values.size() - 1)];
        c.label += "_" + key + "_" + label_text(c.values[key]);
      }
      cases.push_back(c);
    }
    // Once more at another rest density, with the second sample of each required number.
    MaterialCase dense = cases[cases.size() - count + std::min<std::size_t>(1, count - 1)];
    dense.values["rest_density"] = 2.5;
    dense.label += "_rest_density_2p5";
    cases.push_back(dense);
    // And with each further sample of each required text (the first is make_material's default).
    if (const auto texts = kTextSamples.find(name); texts != kTextSamples.end()) {
      for (const auto& [key, words] : texts->second) {
        for (std::size_t i = 1; i < words.size(); ++i) {
          MaterialCase c{name, {}, name + "_" + key + "_" + std::to_string(i), {{key, words[i]}}};
          cases.push_back(c);
        }
      }
    }
  }
  return cases;
}

// ---- the fixture ----------------------------------------------------------------------

class MaterialContract : public ::testing::TestWithParam<MaterialCase> {
 protected:
  void SetUp() override {
    material_ = make_material(GetParam().model, GetParam().values, GetParam().texts);
    tol_ = tolerances_for(*material_);
    grid_ = stretch_grid(*material_);
    ASSERT_GE(grid_.size(), 3u) << "too few admissible stretches to check";
  }

  [[nodiscard]] const Material& material() const { return *material_; }
  [[nodiscard]] double rho() const { return material_->rest_density(); }

  std::shared_ptr<const Material> material_;
  ContractTolerances tol_;
  std::vector<Stretch> grid_;
};

#define AT_STRETCH(s) "at s = " << (s).value() << " (ln s = " << (s).log() << ")"

/// True if a finite-difference stencil of half-width 2h around ln s reaches a point where the law
/// is not smooth (a `tabulated` material's rows): differences across it measure the kink.
std::vector<double> law_breaks(const Material& material) {
  const auto* numeric = dynamic_cast<const NumericMaterial*>(&material);
  return numeric != nullptr ? numeric->law_breaks() : std::vector<double>{};
}
bool straddles_a_break(const Material& material, Stretch s, double h) {
  for (const double b : law_breaks(material))
    if (std::abs(b - s.log()) <= 2.0 * h) return true;
  return false;
}

TEST_P(MaterialContract, NaturalStateIsUnstressedWithRestEnergy) {
  const Stretch one = Stretch::natural();
  EXPECT_NEAR(material().pressure(one), 0.0, tol_.pressure_noise * rho());
  EXPECT_NEAR(material().energy_density(one), rho(), 4.0 * kEpsilon * rho());
  EXPECT_NEAR(material().strain_energy(one), rho(), 4.0 * kEpsilon * rho());
  EXPECT_EQ(material().riemann_psi(one), 0.0);
  EXPECT_EQ(material().admissibility_violation(one), "");
}

TEST_P(MaterialContract, EveryValueIsFiniteAndAdmissible) {
  for (Stretch s : grid_) {
    SCOPED_TRACE(::testing::Message() << AT_STRETCH(s));
    EXPECT_TRUE(std::isfinite(material().pressure(s)));
    EXPECT_TRUE(std::isfinite(material().energy_density(s)));
    EXPECT_TRUE(std::isfinite(material().strain_energy(s)));
    EXPECT_TRUE(std::isfinite(material().stiffness(s)));
    EXPECT_TRUE(std::isfinite(material().riemann_psi(s)));
    EXPECT_GT(material().energy_density(s), 0.0);
    EXPECT_GE(material().enthalpy_density(s), 0.0);
    EXPECT_GT(material().stiffness(s), 0.0) << "W'' > 0 (hyperbolic)";
    const double cs = material().sound_speed(s);
    EXPECT_GT(cs, 0.0);
    EXPECT_LE(cs, 1.0) << "causal";
    EXPECT_EQ(material().admissibility_violation(s), "");
  }
}

TEST_P(MaterialContract, EnergyDensityIsStrainEnergyPerStretch) {
  for (Stretch s : grid_) {
    const double w = material().strain_energy(s);
    EXPECT_NEAR(material().energy_density(s) * s.value(), w, tol_.value * w) << AT_STRETCH(s);
  }
}

TEST_P(MaterialContract, PressureIsMinusStrainEnergyDerivative) {
  // dW/d ln s = s W' = −s p, by fourth-order differences in ln s.
  const double h = kFiniteDifferenceStep;
  for (Stretch s : grid_) {
    if (!material().admissible().contains(Stretch::from_log(s.log() - 2 * h)) ||
        !material().admissible().contains(Stretch::from_log(s.log() + 2 * h)) || straddles_a_break(material(), s, h))
      continue;
    double largest = 0.0;  // |W| over the stencil: the scale of its rounding
    auto energy = [&](double t) {
      const double w = material().strain_energy(Stretch::from_log(t));
      largest = std::max(largest, std::abs(w));
      return w;
    };
    const double slope = central_difference(energy, s.log(), h);
    const double expected = -s.value() * material().pressure(s);
    const double allowed =
        kFiniteDifferenceRelTol * std::abs(expected) + (kEpsilon + tol_.pressure_noise) * 16.0 * largest / h;
    EXPECT_NEAR(slope, expected, allowed) << AT_STRETCH(s);
  }
}

TEST_P(MaterialContract, StiffnessIsMinusPressureDerivative) {
  // dp/d ln s = −s W''.
  const double h = kFiniteDifferenceStep;
  for (Stretch s : grid_) {
    if (!material().admissible().contains(Stretch::from_log(s.log() - 2 * h)) ||
        !material().admissible().contains(Stretch::from_log(s.log() + 2 * h)) || straddles_a_break(material(), s, h))
      continue;
    double largest = 0.0;  // |p| + e over the stencil: the scale of the rounding of p
    auto pressure = [&](double t) {
      const Stretch at = Stretch::from_log(t);
      largest = std::max(largest, std::abs(material().pressure(at)) + material().energy_density(at));
      return material().pressure(at);
    };
    const double slope = central_difference(pressure, s.log(), h);
    const double expected = -s.value() * material().stiffness(s);
    const double allowed = (kFiniteDifferenceRelTol + tol_.sound_speed) * std::abs(expected) +
                           (kEpsilon + tol_.pressure_noise) * 16.0 * largest / h;
    EXPECT_NEAR(slope, expected, allowed) << AT_STRETCH(s);
  }
}

TEST_P(MaterialContract, SoundSpeedSquaredIsStretchTimesStiffnessOverEnthalpy) {
  for (Stretch s : grid_) {
    const double cs = material().sound_speed(s);
    const double e = material().energy_density(s);
    const double p = material().pressure(s);
    // c_s² (e + p) = s W'': e + p rounds at the scale e + |p| (it cancels in far tension).
    const double lhs = cs * cs * (e + p);
    const double rhs = s.value() * material().stiffness(s);
    const double allowed =
        2.0 * tol_.sound_speed * rhs + (tol_.value + tol_.pressure_noise) * cs * cs * (e + std::abs(p));
    EXPECT_NEAR(lhs, rhs, allowed) << AT_STRETCH(s);
  }
}

TEST_P(MaterialContract, PressureAndPsiDecreaseWithStretchWithinTheirLimits) {
  double previous_p = kInfinity;
  double previous_psi = kInfinity;
  const double slack_p = tol_.pressure_noise * rho();
  for (Stretch s : grid_) {
    SCOPED_TRACE(::testing::Message() << AT_STRETCH(s));
    const double p = material().pressure(s);
    const double psi = material().riemann_psi(s);
    EXPECT_LE(p, previous_p + slack_p);
    EXPECT_LE(psi, previous_psi + tol_.psi * std::abs(psi));
    EXPECT_LE(p, material().max_pressure() + slack_p);
    EXPECT_GE(p, material().max_tension() - slack_p);
    EXPECT_LE(psi, material().psi_max() + tol_.psi * std::abs(psi));
    EXPECT_GE(psi, material().psi_min() - tol_.psi * std::abs(psi));
    previous_p = p;
    previous_psi = psi;
  }
  EXPECT_LE(material().max_tension(), 0.0);
  EXPECT_GE(material().max_pressure(), 0.0);
  EXPECT_LE(material().psi_min(), 0.0);
  EXPECT_GE(material().psi_max(), 0.0);
  EXPECT_LE(material().cavitation_pressure(), material().max_tension());
}

TEST_P(MaterialContract, LimitsAreTheValuesAtFiniteEndsOfTheRange) {
  const StretchRange range = material().admissible();
  if (std::isfinite(range.log_min)) {
    const Stretch end = Stretch::from_log(range.log_min);
    EXPECT_NEAR(material().max_pressure(), material().pressure(end), tol_.value * std::abs(material().pressure(end)));
    EXPECT_NEAR(material().psi_max(), material().riemann_psi(end), tol_.psi * std::abs(material().riemann_psi(end)));
  }
  if (std::isfinite(range.log_max)) {
    const Stretch end = Stretch::from_log(range.log_max);
    EXPECT_NEAR(material().max_tension(), material().pressure(end), tol_.value * std::abs(material().pressure(end)));
    EXPECT_NEAR(material().psi_min(), material().riemann_psi(end), tol_.psi * std::abs(material().riemann_psi(end)));
  }
}

TEST_P(MaterialContract, PsiIsTheIntegralOfSoundSpeedOverLnStretch) {
  // A numeric c_s is only as smooth as its own accuracy: ask no more of the quadrature.
  const double epsrel = std::max(kReferenceQuadratureRelTol, 0.1 * tol_.psi);
  for (Stretch s : grid_) {
    const double reference = reference_psi(material(), s, epsrel, law_breaks(material()));
    EXPECT_NEAR(material().riemann_psi(s), reference, (tol_.psi + 10.0 * epsrel) * std::abs(reference))
        << AT_STRETCH(s);
  }
}

TEST_P(MaterialContract, StretchAtPressureInvertsPressure) {
  for (Stretch s : grid_) {
    const double p = material().pressure(s);
    const Solved<Stretch> found = material().stretch_at_pressure(p);
    const StretchRange range = material().admissible();
    const bool at_open_end = (p >= material().max_pressure() && !std::isfinite(range.log_min)) ||
                             (p <= material().max_tension() && !std::isfinite(range.log_max));
    if (at_open_end) {  // p rounded onto a limit only reached as s → 0 or ∞
      EXPECT_EQ(found.status, Status::out_of_range) << AT_STRETCH(s);
      continue;
    }
    ASSERT_TRUE(found.ok()) << AT_STRETCH(s) << ", p = " << p << ": " << to_string(found.status);
    // d ln s / dp = −1/(s W''): an error δp in p moves ln s by δp/(s W'').
    const double rounding_p =
        kRoundTripUlps * kEpsilon * std::abs(p) + tol_.pressure_noise * material().energy_density(s);
    const double allowed = kRoundTripUlps * kEpsilon * std::abs(s.log()) +
                           rounding_p / (s.value() * material().stiffness(s)) * (1.0 + tol_.sound_speed);
    EXPECT_NEAR(found.value.log(), s.log(), allowed) << AT_STRETCH(s) << ", p = " << p;
  }
}

TEST_P(MaterialContract, StretchAtPsiInvertsPsi) {
  for (Stretch s : grid_) {
    const double psi = material().riemann_psi(s);
    const Solved<Stretch> found = material().stretch_at_psi(psi);
    const StretchRange range = material().admissible();
    const bool at_open_end = (psi >= material().psi_max() && !std::isfinite(range.log_min)) ||
                             (psi <= material().psi_min() && !std::isfinite(range.log_max));
    if (at_open_end) {
      EXPECT_EQ(found.status, Status::out_of_range) << AT_STRETCH(s);
      continue;
    }
    ASSERT_TRUE(found.ok()) << AT_STRETCH(s) << ", psi = " << psi << ": " << to_string(found.status);
    // d ln s / dΨ = −1/c_s.
    const double rounding_psi = (kRoundTripUlps * kEpsilon + tol_.psi_noise) * std::abs(psi);
    const double allowed = kRoundTripUlps * kEpsilon * std::abs(s.log()) + rounding_psi / material().sound_speed(s);
    EXPECT_NEAR(found.value.log(), s.log(), allowed) << AT_STRETCH(s) << ", psi = " << psi;
  }
}

TEST_P(MaterialContract, InversesRefuseWhatTheMaterialCannotReach) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double p : {nan, kInfinity, -kInfinity}) EXPECT_FALSE(material().stretch_at_pressure(p).ok()) << "p = " << p;
  for (double psi : {nan, kInfinity, -kInfinity}) EXPECT_FALSE(material().stretch_at_psi(psi).ok()) << "psi = " << psi;

  const StretchRange range = material().admissible();
  auto beyond = [](double limit, double direction) { return limit + direction * (1e-6 * std::abs(limit) + 1e-6); };
  auto check_limit = [&](const char* what, double limit, double direction, bool end_is_open, auto inverse) {
    SCOPED_TRACE(what);
    if (!std::isfinite(limit)) return;
    EXPECT_EQ(inverse(beyond(limit, direction)).status, Status::out_of_range) << "beyond the limit " << limit;
    EXPECT_EQ(inverse(limit).ok(), !end_is_open) << "at the limit " << limit;
  };
  auto at_pressure = [&](double p) { return material().stretch_at_pressure(p); };
  auto at_psi = [&](double psi) { return material().stretch_at_psi(psi); };
  check_limit("max_pressure", material().max_pressure(), +1.0, !std::isfinite(range.log_min), at_pressure);
  check_limit("max_tension", material().max_tension(), -1.0, !std::isfinite(range.log_max), at_pressure);
  check_limit("psi_max", material().psi_max(), +1.0, !std::isfinite(range.log_min), at_psi);
  check_limit("psi_min", material().psi_min(), -1.0, !std::isfinite(range.log_max), at_psi);
}

TEST_P(MaterialContract, InadmissibleStretchesAreExplained) {
  EXPECT_NE(material().admissibility_violation(Stretch::from_log(std::numeric_limits<double>::quiet_NaN())), "");
  EXPECT_NE(material().admissibility_violation(Stretch::from_log(-kInfinity)), "") << "s = 0";
  EXPECT_NE(material().admissibility_violation(Stretch::from_log(kInfinity)), "") << "s = inf";
  const StretchRange range = material().admissible();
  if (std::isfinite(range.log_min)) {
    EXPECT_NE(material().admissibility_violation(Stretch::from_log(range.log_min - 0.5)), "") << "below the range";
  }
  if (std::isfinite(range.log_max)) {
    EXPECT_NE(material().admissibility_violation(Stretch::from_log(range.log_max + 0.5)), "") << "above the range";
  }
}

TEST_P(MaterialContract, LinearDegeneracyMatchesTheWaveSpeeds) {
  // The lab speed of a + wave is tanh(φ + artanh c_s) with φ = J− + Ψ along it: the family
  // is linearly degenerate iff Ψ + artanh c_s is constant, or c_s = c throughout.
  constexpr double kNearLight = 1.0 - 1e-6;  // beyond, artanh c_s is not resolved
  double lo = kInfinity;
  double hi = -kInfinity;
  bool all_light = true;
  double allowed = 0.0;
  for (Stretch s : grid_) {
    const double cs = material().sound_speed(s);
    if (cs < 1.0) all_light = false;
    if (cs >= kNearLight) continue;
    const double psi = material().riemann_psi(s);
    const double invariant = psi + std::atanh(cs);
    lo = std::min(lo, invariant);
    hi = std::max(hi, invariant);
    allowed = std::max(allowed, tol_.psi * std::abs(psi) + (tol_.sound_speed + 4.0 * kEpsilon) * cs / (1.0 - cs * cs) +
                                    4.0 * kEpsilon * std::abs(invariant));
  }
  if (material().linearly_degenerate()) {
    if (!all_light) {
      EXPECT_LE(hi - lo, allowed) << "Psi + artanh(c_s) varies from " << lo << " to " << hi;
    }
  } else {
    EXPECT_FALSE(all_light) << "c_s = c everywhere, yet not declared linearly degenerate";
    EXPECT_GT(hi - lo, 1e-3) << "Psi + artanh(c_s) is constant, yet not declared linearly degenerate";
  }
}

TEST_P(MaterialContract, SoundAtLightSpeedIsDeclaredOnlyWhereItHolds) {
  // The front tracker lets the fronts of such a material pass each other unvisited: a
  // material that claims it must have c_s = c at every stretch, and be linearly degenerate.
  if (!material().sound_at_light_speed()) return;
  EXPECT_TRUE(material().linearly_degenerate());
  for (Stretch s : grid_) EXPECT_EQ(material().sound_speed(s), 1.0) << "ln s = " << s.log();
}

TEST_P(MaterialContract, LawsAtOneStretchAreThoseOfEachLaw) {
  // The finite-volume face states take p, e + p and c_s from one call, which a material may
  // override to share their work: it must give what the three functions give (to round-off).
  for (Stretch s : grid_) {
    SCOPED_TRACE(::testing::Message() << AT_STRETCH(s));
    const LawValues laws = material().laws_at(s);
    const double p = material().pressure(s), w = material().enthalpy_density(s), c = material().sound_speed(s);
    EXPECT_NEAR(laws.pressure, p, 4e-16 * (std::abs(p) + material().rest_density()));
    EXPECT_NEAR(laws.enthalpy, w, 4e-16 * std::abs(w));
    EXPECT_NEAR(laws.sound_speed, c, 4e-16 * c);
  }
}

std::string case_label(const ::testing::TestParamInfo<MaterialCase>& param_info) { return param_info.param.label; }

INSTANTIATE_TEST_SUITE_P(Registry, MaterialContract, ::testing::ValuesIn(registry_cases()), case_label);

}  // namespace
}  // namespace rigidity::testing
