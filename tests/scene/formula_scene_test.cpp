// The `formula` material in a scene (materials/formula.cpp): what it accepts, and the errors a
// bad law gives at load time, each naming the file, the line, the key and where in the
// expression or at which stretch.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"

namespace rigidity {
namespace {

/// A scene whose material `m` is `material` (a YAML flow map on line 4 of "formula.yaml").
std::string scene(const std::string& material, const std::string& units = "natural") {
  return "name: formula\n"
         "units: " +
         units +
         "\n"
         "materials:\n"
         "  m: " +
         material +
         "\n"
         "bodies:\n"
         "  - {name: bar, material: m, position: 0.0, length: 1.0, velocity: 0.5}\n"
         "boundaries: {left: {type: free}, right: {type: wall}}\n"
         "time: {end: 1.0}\n";
}

/// The InputError loading `text` throws; fails the test if none.
InputError load_error(const std::string& text) {
  try {
    (void)load_scene_string(text, "formula.yaml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "loaded without error:\n" << text;
  return InputError({}, "", "");
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// `text` with `from` (which must occur) replaced by `to`.
std::string replaced_once(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(FormulaScene, AcceptsAPressureOrAStrainEnergyAndDerivesTheRest) {
  const Scene p = load_scene_string(
      scene(R"y({model: formula, pressure: "0.5*rho*(1/s^2 - 1)", parameters: {rho: 2.0}, rest_density: 2.0})y"),
      "formula.yaml");
  const Material& rigid = *p.materials.at("m").material;
  EXPECT_EQ(rigid.model(), "formula");
  const Stretch half = Stretch::from_value(0.5);
  EXPECT_NEAR(rigid.pressure(half), 3.0, 1e-14);                   // (ρ00/2)(1/s² − 1)
  EXPECT_NEAR(rigid.energy_density(half), 5.0, 1e-13);             // (ρ00/2)(1/s² + 1)
  EXPECT_NEAR(rigid.sound_speed(half), 1.0, 1e-11);                // the rigid law: c_s = c
  EXPECT_NEAR(rigid.riemann_psi(half), std::log(2.0), 1e-10);      // Ψ = −ln s
  EXPECT_NEAR(std::exp(rigid.admissible().log_min), 0.01, 1e-15);  // the default range
  EXPECT_NEAR(std::exp(rigid.admissible().log_max), 10.0, 1e-13);

  // constant_sound_speed at V = 0.5 as its strain energy, on a declared range.
  const Scene w = load_scene_string(scene(R"y({model: formula, strain_energy: "(s^(-V^2) + V^2*s)/(1 + V^2)",
                                              parameters: {V: 0.5}, min_stretch: 0.1, max_stretch: 10
  })y"),
                                    "formula.yaml");
  const Material& fluid = *w.materials.at("m").material;
  const double k = 1.25;
  EXPECT_NEAR(fluid.pressure(half), 0.25 / k * (std::pow(0.5, -k) - 1.0), 1e-11);
  EXPECT_NEAR(fluid.sound_speed(half), 0.5, 1e-9);
  EXPECT_NEAR(std::exp(fluid.admissible().log_min), 0.1, 1e-15);
}

TEST(FormulaScene, InAnSiSceneTheExpressionIsInPascalAndKnowsRestDensityAndC) {
  // steel-like rest density; the rigid law in Pa: (ρ00 c²/2)(1/s² − 1).
  const Scene si = load_scene_string(
      "name: formula\nunits: si\nmaterials:\n"
      "  m: {model: formula, pressure: \"0.5*rest_density*c^2*(1/s^2 - 1)\", rest_density: 7850}\n"
      "bodies:\n  - {name: bar, material: m, position: 0.0, length: 1.0, velocity: 100.0}\n"
      "boundaries: {left: {type: free}, right: {type: wall}}\ntime: {end: 1.0e-9}\n",
      "formula.yaml");
  const Material& m = *si.materials.at("m").material;
  EXPECT_NEAR(m.sound_speed(Stretch::from_value(0.9)), 1.0, 1e-11);
  EXPECT_NEAR(m.pressure(Stretch::from_value(0.5)) / m.rest_density(), 1.5, 1e-13);
}

TEST(FormulaScene, ASyntaxErrorNamesFileLineKeyAndTheCharacter) {
  const InputError e =
      load_error(scene(R"y({model: formula, pressure: "0.5*rho*(1/s^2 - 1", parameters: {rho: 1.0}})y"));
  EXPECT_EQ(e.where().file, "formula.yaml");
  EXPECT_EQ(e.where().line, 4);
  EXPECT_EQ(e.key(), "materials.m.pressure");
  EXPECT_TRUE(contains(e.message(), "syntax error at the end of the expression: Missing parenthesis")) << e.what();
  EXPECT_TRUE(contains(e.message(), "0.5*rho*(1/s^2 - 1")) << e.what();
  // A misplaced operator: muparser names the character it stopped at (1-based here).
  const InputError op = load_error(scene(R"y({model: formula, pressure: "0.5**(1/s^2 - 1)"
  })y"));
  EXPECT_EQ(op.key(), "materials.m.pressure");
  EXPECT_TRUE(contains(op.message(), "at character 5 ('0.5*' <here> '*(1/s^2 - 1)')")) << op.what();
}

TEST(FormulaScene, AnUnknownNameIsNamedWithTheClosestDeclaredOne) {
  const InputError e = load_error(scene(R"y({model: formula, pressure: "0.5*rh*(1/s^2 - 1)", parameters: {
rho:
  1.0}})y"));
  EXPECT_EQ(e.key(), "materials.m.pressure");
  EXPECT_EQ(e.where().line, 4);
  EXPECT_TRUE(contains(e.message(), "unknown name 'rh' at character 5 (did you mean 'rho'?)")) << e.what();
}

TEST(FormulaScene, AnAcausalRangeIsRefusedAtTheStretchWhereItStarts) {
  // p = A (1/s^4 - 1), A = 0.1: c_s^2 = s W''/(e + p) is 0.4 at s = 1 and reaches 1 at s = 0.67510
  // (solved with NumPy); causal above.
  const InputError e = load_error(scene(R"y({model: formula, pressure: "A*(1/s^4 - 1)", parameters: {A: 0.1},
                                            min_stretch: 0.5, max_stretch: 2})y"));
  EXPECT_EQ(e.key(), "materials.m.pressure");
  EXPECT_EQ(e.where().line, 4);
  EXPECT_TRUE(contains(e.message(), "acausal: the sound speed c_s = ")) << e.what();
  const std::size_t at = e.message().find("at s = ");
  ASSERT_NE(at, std::string::npos);
  const double s = std::stod(e.message().substr(at + 7));  // the first acausal sample below 0.67510
  EXPECT_LT(s, 0.67510);
  EXPECT_GT(s, 0.66);
  // Within the causal range it loads.
  EXPECT_NO_THROW((void)load_scene_string(scene(R"y({model: formula, pressure: "A*(1/s^4 - 1)", parameters: {A: 0.1},
                                                    min_stretch: 0.68, max_stretch: 2
  })y"),
                                          "formula.yaml"));
}

TEST(FormulaScene, ANonHyperbolicPointIsRefusedNamingItsStretch) {
  // p rises again beyond s = 2: dp/ds > 0 there.
  const InputError e = load_error(
      scene(R"y({model: formula, pressure: "0.1*(1/s - 1) + 0.02*(s - 1)^2", min_stretch: 0.5, max_stretch: 4})y"));
  EXPECT_EQ(e.key(), "materials.m.pressure");
  EXPECT_TRUE(contains(e.message(), "not hyperbolic: dp/ds = ")) << e.what();
  EXPECT_TRUE(contains(e.message(), "is not negative (p must fall as s grows)")) << e.what();
  // The first failing stretch: dp/ds = -0.1/s² + 0.04 (s − 1) vanishes at s = 1.78480 (solved
  // with SciPy); the samples are 0.5% apart in s there.
  const std::size_t at = e.message().find("at s = ");
  ASSERT_NE(at, std::string::npos);
  const double s = std::stod(e.message().substr(at + 7));
  EXPECT_GT(s, 1.78480);
  EXPECT_LT(s, 1.80);
}

TEST(FormulaScene, OtherDefectsNameTheirKey) {
  // A parameter named like a built-in name.
  EXPECT_EQ(load_error(scene(R"y({model: formula, pressure: "c*(1/s - 1)", parameters: {
c:
  1.0}})y"))
                .key(),
            "materials.m.parameters.c");
  // Unstressed at s = 1.
  EXPECT_TRUE(contains(load_error(scene(R"y({model: formula, pressure: "1/s^2"})y")).message(),
                       "the natural state s = 1 is unstressed"));
  // W(1) is the rest energy.
  EXPECT_TRUE(contains(load_error(scene(R"y({model: formula, strain_energy: "2*(1/s + s)"
  })y"))
                           .message(),
                       "W(1) is the rest energy"));
  // No law, or two.
  EXPECT_EQ(load_error(scene("{model: formula}")).key(), "materials.m.model");
  EXPECT_EQ(load_error(scene(R"y({model: formula, pressure: "1/s - 1", strain_energy: "s"})y")).key(),
            "materials.m.strain_energy");
  // A number where a parameter's value goes.
  EXPECT_EQ(load_error(scene(R"y({model: formula, pressure: "1/s - 1", parameters: {k: soft}})y")).key(),
            "materials.m.parameters.k");
  // No number at some stretch of the range.
  EXPECT_TRUE(contains(load_error(scene(R"y({model: formula, pressure: "0.1*(1/s - 1) + sqrt(s - 0.5) - sqrt(0.5)"
  })y"))
                           .message(),
                       "gives no finite number"));
}

/// The root of f in [a, b], where f changes sign, by bisection.
double root(const std::function<double(double)>& f, double a, double b) {
  const bool negative_at_a = f(a) < 0.0;
  for (int k = 0; k < 200; ++k) {
    const double m = 0.5 * (a + b);
    ((f(m) < 0.0) == negative_at_a ? a : b) = m;
  }
  return 0.5 * (a + b);
}

TEST(FormulaScene, TheInflectionIsFoundWhereTheConvexityChangesSign) {
  // p = A x + B ((x - x0)^3 + x0^3), x = 1 - s: W = 1 + A x^2/2 + B ((x - x0)^4/4 - x0^4/4 + x0^3 x),
  // W'' = A + 3 B (x - x0)^2, W''' = -6 B (x - x0). The stiffness is least at s = 1 - x0, so the
  // genuine nonlinearity g = c_s (s W'''/(2 W'') + 3 c_s^2/2) (c_s^2 = s^2 W''/(W + s p)) changes
  // sign near there: compressions are shocks below, fans above.
  const double A = 0.01, B = 0.05, x0 = 0.2;
  const auto g_over_cs = [&](double s) {
    const double x = 1.0 - s, y = x - x0;
    const double W = 1.0 + A * x * x / 2.0 + B * (y * y * y * y / 4.0 - x0 * x0 * x0 * x0 / 4.0 + x0 * x0 * x0 * x);
    const double p = A * x + B * (y * y * y + x0 * x0 * x0), W2 = A + 3.0 * B * y * y, W3 = -6.0 * B * y;
    return s * W3 / (2.0 * W2) + 1.5 * s * s * W2 / (W + s * p);
  };
  const double inflection = root(g_over_cs, 0.7, 0.9);
  EXPECT_NEAR(inflection, 0.799203, 1e-6);  // solved the same way with Python: 0.79920253
  const std::string law =
      R"y(pressure: "A*(1 - s) + B*((1 - s - x0)^3 + x0^3)", parameters: {A: 0.01, B: 0.05, x0: 0.2})y";
  // The law loads, and its material knows where its waves may be composite.
  const Scene loaded =
      load_scene_string(scene("{model: formula, " + law + ", min_stretch: 0.5, max_stretch: 1.5}"), "formula.yaml");
  const std::vector<double>& found = loaded.materials.at("m").material->inflection_logs();
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(std::exp(found.front()), inflection, 1e-6);
  // On one side of it there is none.
  const Scene one_side =
      load_scene_string(scene("{model: formula, " + law + ", min_stretch: 0.85, max_stretch: 1.5}"), "formula.yaml");
  EXPECT_TRUE(one_side.materials.at("m").material->inflection_logs().empty());
}

TEST(FormulaScene, LinearlyDegenerateAndReversedLawsPassTheConvexityCheck) {
  // Brotas's Hooke law as a strain energy (g = 0: the tables' noise in c_s must not read as a
  // change of sign), and the linear law p = V^2 (1 - s), whose g > 0 everywhere (convexity_test.cpp).
  EXPECT_NO_THROW((void)load_scene_string(
      scene(R"y({model: formula, strain_energy: "s*(sqrt(b^2 + (1 - b^2)/s^2) - b^2)/(1 - b^2)", parameters: {b: 0.5},
                min_stretch: 0.05, max_stretch: 10})y"),
      "formula.yaml"));
  EXPECT_NO_THROW((void)load_scene_string(
      scene(R"y({model: formula, pressure: "0.09*(1 - s)", min_stretch: 0.5, max_stretch: 2})y"), "formula.yaml"));
}

TEST(FormulaScene, ADeclaredParameterHasAUnitAndARangeInTheScenesUnits) {
  // An SI scene: K in Pa, the expression in Pa.
  const std::string si =
      "name: formula\nunits: si\nmaterials:\n"
      "  m: {model: formula, pressure: \"K*(1/s - 1)\", rest_density: 1000,\n"
      "      parameters: {K: {value: 2.0e9, unit: pressure, min: 0, max: 1.0e12, doc: stiffness}}}\n"
      "bodies:\n  - {name: bar, material: m, position: 0.0, length: 1.0, velocity: 10.0}\n"
      "boundaries: {left: {type: free}, right: {type: wall}}\ntime: {end: 1.0e-4}\n";
  const Scene loaded = load_scene_string(si, "formula.yaml");
  const Material& m = *loaded.materials.at("m").material;
  const double c = 299792458.0;
  EXPECT_NEAR(m.pressure(Stretch::from_value(0.5)) * c * c, 2.0e9, 1e-12 * 2.0e9);
  EXPECT_NEAR(m.sound_speed(Stretch::natural()) * c, std::sqrt(2.0e9 / 1000.0), 1e-6);  // sqrt(K/rho00)
  const std::string resolved = loaded.resolved_yaml();
  EXPECT_TRUE(contains(resolved, "unit: pressure")) << resolved;
  // The resolved scene loads again, to the same law.
  const Scene again = load_scene_string(resolved, "resolved.yaml");
  EXPECT_EQ(again.materials.at("m").material->pressure(Stretch::from_value(0.5)), m.pressure(Stretch::from_value(0.5)));

  // Out of range: the error names the value, the bound and the unit, at the value's key and line.
  const InputError low = load_error(replaced_once(si, "value: 2.0e9", "value: -2.0e9"));
  EXPECT_EQ(low.key(), "materials.m.parameters.K.value");
  EXPECT_EQ(low.where().line, 5);
  EXPECT_TRUE(contains(low.message(), "parameter 'K' = -2e9 Pa is below its declared min = 0 Pa")) << low.what();
  const InputError high = load_error(replaced_once(si, "value: 2.0e9", "value: 2.0e13"));
  EXPECT_EQ(high.key(), "materials.m.parameters.K.value");
  EXPECT_TRUE(contains(high.message(), "is above its declared max = 1e12 Pa")) << high.what();
  const InputError crossed = load_error(replaced_once(si, "max: 1.0e12", "max: -1"));
  EXPECT_EQ(crossed.key(), "materials.m.parameters.K.max");
  EXPECT_TRUE(contains(crossed.message(), "is below min = 0 Pa")) << crossed.what();
  // A unit that is not a dimension, a misspelt key, a missing value.
  const InputError unit = load_error(replaced_once(si, "unit: pressure", "unit: presure"));
  EXPECT_EQ(unit.key(), "materials.m.parameters.K.unit");
  EXPECT_TRUE(contains(unit.message(), "did you mean 'pressure'?")) << unit.what();
  const InputError misspelt = load_error(replaced_once(si, "min: 0", "mim: 0"));
  EXPECT_EQ(misspelt.key(), "materials.m.parameters.K.mim");
  EXPECT_TRUE(contains(misspelt.message(), "did you mean 'min'?")) << misspelt.what();
  const InputError missing = load_error(replaced_once(si, "value: 2.0e9, ", ""));
  EXPECT_EQ(missing.key(), "materials.m.parameters.K.value");
  EXPECT_TRUE(contains(missing.message(), "missing required key 'value'")) << missing.what();
  // The plain form and the declared one mix; a dimensionless declaration needs no unit.
  EXPECT_NO_THROW((void)load_scene_string(
      scene(R"y({model: formula, pressure: "k*n*(1/s - 1)", parameters: {k: 0.1, n: {value: 2, min: 1}}})y"),
      "formula.yaml"));
}

}  // namespace
}  // namespace rigidity
