/// `formula`: a material whose law the scene writes as an expression of the stretch s, parsed
/// by muparser (Debian's libmuparser-dev):
///
///   materials:
///     soft:
///       model: formula
///       pressure: "0.5*rest_density*c^2*(1/s^2 - 1)"     # p(s), or
///       # strain_energy: "rest_density*c^2*(1/s + s)/2"   # W(s) = e s, rest energy included
///       parameters: {k: 2.0, K: {value: 2.0e9, unit: pressure, min: 0}}   # names the expression may use
///       min_stretch: 0.1                                   # the admissible range
///       max_stretch: 10                                    # (the defaults: [0.01, 10])
///
/// The expression may use s, the parameters declared beside it, rest_density (as the scene
/// writes it) and c (1 in a natural scene, 299792458 in an SI one), with muparser's operators
/// (+ - * / ^), functions (sqrt, exp, ln, log10, sin, tanh, min, max, ...) and `a ? b : c`. Its
/// value is in the scene's units of pressure (Pa in an SI scene, rest_density c² in a natural
/// one), and so is every parameter: a plain number, or one declared with its unit and range,
/// which the scene loader checks (scene_loader.cpp) before it hands over the value as written.
///
/// A pressure law is a PressureLawMaterial, a strain energy a StrainEnergyMaterial
/// (numeric_material.hpp): W (or p), e, W'', c_s, Ψ and the inverses are derived from the
/// expression exactly as for a table or a plugin, and the Hugoniot by the solvers from p and e.
///
/// Checked when the material is built, each error naming the key ("pressure", "parameters.k")
/// that the scene loader turns into file and line: the expression parses (muparser's message and
/// the character where it failed), uses no name but those above, gives a finite number at
/// kChecks stretches spanning [min_stretch, max_stretch], is unstressed at s = 1 (p(1) = 0, and
/// W(1) = rest_density c²), and at every sample has e + p > 0, W'' = −dp/ds > 0 (hyperbolic) and
/// c_s ≤ c (causal), the failing stretch named. Where the genuine nonlinearity changes sign on the
/// range (an inflection), the scene loader refuses the law for the front tracker, as it does any
/// material's (rigidity/convexity.hpp); the finite-volume solver runs it.

#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigidity/number_text.hpp"
#include "rigidity/numeric_material.hpp"
#include "rigidity/parameters.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/spelling.hpp"
#include "rigidity/units.hpp"

namespace rigidity {
namespace {

constexpr std::string_view kName = "formula";
/// Stretches, evenly spaced in ln s over the admissible range, at which the law is checked.
constexpr int kChecks = 400;
/// |p(1)| (and |W(1) − ρ00|) within this fraction of ρ00 c² is the natural state.
constexpr double kNaturalStateTolerance = 1e-12;
/// |p(1)| of a strain energy, found by differences of W, within this fraction of ρ00 c².
constexpr double kNaturalPressureTolerance = 1e-8;
/// The names an expression has besides its parameters.
constexpr std::string_view kStretchName = "s";
constexpr std::string_view kRestDensityName = "rest_density";
constexpr std::string_view kLightSpeedName = "c";

/// An expression of s, parsed once; evaluated under a lock (a muparser Parser holds its
/// variables and stack in itself).
class Expression {
 public:
  /// \throws ParameterError at `key` (syntax, unknown name) or at "parameters.NAME" (a bad name)
  Expression(std::string key, std::string text, const std::map<std::string, double>& parameters,
             double rest_density_as_written, double light_speed_as_written, double to_natural)
      : key_(std::move(key)), text_(std::move(text)), to_natural_(to_natural) {
    variables_[std::string(kRestDensityName)] = rest_density_as_written;
    variables_[std::string(kLightSpeedName)] = light_speed_as_written;
    for (const auto& [name, value] : parameters) {
      if (variables_.count(name) != 0 || name == kStretchName)
        throw ParameterError("parameters." + name, "the parameter name '" + name + "' is taken: an expression has " +
                                                       "s, c and rest_density already");
      if (!std::isfinite(value))
        throw ParameterError("parameters." + name, "parameter '" + name + "' must be a finite number");
      variables_[name] = value;
    }
    try {
      parser_.DefineVar(std::string(kStretchName), &s_);
    } catch (const mu::Parser::exception_type& e) {
      throw std::logic_error("formula: cannot define s: " + e.GetMsg());
    }
    for (auto& [name, value] : variables_) {
      try {
        parser_.DefineVar(name, &value);  // std::map: the address stays
      } catch (const mu::Parser::exception_type& e) {
        throw ParameterError("parameters." + name, "'" + name + "' cannot be a parameter name (" + e.GetMsg() +
                                                       "); use letters, digits and '_', not starting with a digit, " +
                                                       "and not the name of one of muparser's functions");
      }
    }
    if (text_.find_first_not_of(" \t") == std::string::npos)
      throw ParameterError(key_, key_ + " is empty: write the law as an expression of s");
    try {
      parser_.SetExpr(text_);
      s_ = 1.0;
      (void)parser_.Eval();  // parses: syntax errors and unknown names show here
    } catch (const mu::Parser::exception_type& e) {
      throw ParameterError(key_, describe_error(e));
    }
  }

  /// The value at s, in natural units; NaN if muparser fails there.
  [[nodiscard]] double operator()(double s) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    s_ = s;
    try {
      return to_natural_ * parser_.Eval();
    } catch (const mu::Parser::exception_type&) {
      return std::nan("");
    }
  }

  [[nodiscard]] const std::string& key() const { return key_; }
  /// `pressure "0.5*(1/s^2 - 1)"`
  [[nodiscard]] std::string quoted() const { return key_ + " \"" + text_ + "\""; }

 private:
  /// muparser's message, the character where it stopped (1-based) and the text around it; for
  /// an unknown name, the names there are and the closest of them.
  [[nodiscard]] std::string describe_error(const mu::Parser::exception_type& e) const {
    std::string out = quoted() + ": ";
    const int position = e.GetPos();
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN && !e.GetToken().empty()) {
      std::vector<std::string> names{std::string(kStretchName)};
      std::string listed = std::string(kStretchName);
      for (const auto& entry : variables_) {
        names.push_back(entry.first);
        listed += ", " + entry.first;
      }
      const std::string near = closest_match(e.GetToken(), names);
      out += "unknown name '" + e.GetToken() + "'";
      if (position >= 0) out += " at character " + std::to_string(position + 1);
      out += (near.empty() ? std::string() : " (did you mean '" + near + "'?)") + "; an expression may use " + listed +
             " (declare more under `parameters`) and muparser's functions";
      return out;
    }
    out += "syntax error";
    if (position >= 0 && static_cast<std::size_t>(position) < text_.size()) {
      const auto at = static_cast<std::size_t>(position);
      out += " at character " + std::to_string(at + 1) + " ('" + text_.substr(0, at) + "' <here> '" + text_.substr(at) +
             "')";
    } else if (position >= 0) {
      out += " at the end of the expression";
    }
    // muparser's message counts from 0 ("found at position 4"): the position is given above.
    std::string message = e.GetMsg();
    const std::string counted = " at position " + std::to_string(position);
    if (const std::size_t found = message.find(counted); found != std::string::npos)
      message.erase(found, counted.size());
    if (const std::size_t found = message.find(" found"); found != std::string::npos && found + 6 == message.size())
      message.erase(found);
    return out + ": " + message;
  }

  std::string key_;
  std::string text_;
  double to_natural_;
  std::map<std::string, double> variables_;
  mutable double s_ = 1.0;
  mutable mu::Parser parser_;
  mutable std::mutex mutex_;
};

std::string doc() {
  return "A law written in the scene: `pressure` p(s) or `strain_energy` W(s) = e s (rest energy included, W(1) = "
         "rest_density c^2), an expression of s parsed by muparser, which may use the numbers declared under "
         "`parameters`, rest_density and c (1 in a natural scene, 299792458 in an SI one); its value is in the scene's "
         "units (Pa in an SI scene, rest_density c^2 in a natural one). e, W'' (or p), c_s, the Riemann invariant and "
         "the inverses are derived numerically, as for `tabulated`. Admissible on [min_stretch, max_stretch], where "
         "it is checked at load (finite, p(1) = 0, e + p > 0, W'' = -dp/ds > 0, c_s <= c; for the front tracker "
         "also one sign of the genuine nonlinearity: no inflection); errors name the key, the stretch and, for a bad "
         "expression, the character. "
         "A parameter may be declared with its unit and range: {value: 2.0e9, unit: pressure, min: 0}.";
}

std::vector<ParameterSpec> parameters() {
  return {
      rest_density_parameter(),
      ParameterSpec::text("pressure", "p(s): the pressure as an expression of s (give this or strain_energy)")
          .defaults_to(std::string()),
      ParameterSpec::text("strain_energy",
                          "W(s) = e s: the energy per unit unstrained volume as an expression of s, rest energy "
                          "included (give this or pressure)")
          .defaults_to(std::string()),
      ParameterSpec::numbers("parameters",
                             "named numbers the expression may use, e.g. {k: 2.0}, each a number or declared with "
                             "its unit and range: {K: {value: 2.0e9, unit: pressure, min: 0}}"),
      ParameterSpec::number("min_stretch", "smallest admissible stretch (most compressed)")
          .defaults_to(0.01)
          .above(0.0)
          .below(1.0),
      ParameterSpec::number("max_stretch", "largest admissible stretch (most stretched)").defaults_to(10.0).above(1.0)};
}

/// The expression a scene gave, and the window. \throws ParameterError
struct Law {
  std::unique_ptr<Expression> expression;
  bool is_pressure = true;
  StretchRange window;
};

Law read_law(const ParameterValues& values) {
  const std::string pressure = values.has("pressure") ? values.text("pressure") : std::string();
  const std::string energy = values.has("strain_energy") ? values.text("strain_energy") : std::string();
  if (pressure.empty() == energy.empty())
    throw ParameterError(pressure.empty() ? "model" : "strain_energy",
                         pressure.empty() ? "a formula material needs its law: `pressure` p(s) or `strain_energy` W(s)"
                                          : "give `pressure` or `strain_energy`, not both");
  const UnitSystem units = values.units();
  const double rho = values.number("rest_density");
  Law law;
  law.is_pressure = !pressure.empty();
  law.expression = std::make_unique<Expression>(
      law.is_pressure ? "pressure" : "strain_energy", law.is_pressure ? pressure : energy,
      values.numbers_under("parameters"), from_natural(rho, Dimension::density, units),
      from_natural(1.0, Dimension::velocity, units), to_natural(1.0, Dimension::pressure, units));
  const double lo = values.number("min_stretch");
  const double hi = values.number("max_stretch");
  if (!(lo > 0.0 && lo < 1.0)) throw ParameterError("min_stretch", "min_stretch must be in (0, 1)");
  if (!(hi > 1.0 && std::isfinite(hi))) throw ParameterError("max_stretch", "max_stretch must be finite and above 1");
  law.window = StretchRange{std::log(lo), std::log(hi)};
  return law;
}

/// The load-time checks, shared by both forms, at stretches taken outward from s = 1, so that
/// the stretch an error names is the first bad one seen from the natural state, and the law is
/// admissible between it and 1 (to the sampling). \throws ParameterError at the expression's key
void check_law(const NumericMaterial& material, const Expression& expression, bool is_pressure, StretchRange window) {
  const double rho = material.rest_density();
  const auto fail = [&](double s, const std::string& what) {
    throw ParameterError(expression.key(), expression.quoted() + ": at s = " + twelve_digits(s) + ": " + what);
  };
  std::vector<double> logs;
  for (int k = 0; k <= kChecks; ++k)
    logs.push_back(window.log_min + (window.log_max - window.log_min) * static_cast<double>(k) / kChecks);
  std::stable_sort(logs.begin(), logs.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  std::vector<double> stretches{1.0};
  for (const double t : logs) stretches.push_back(std::exp(t));
  for (const double s : stretches) {
    const double value = expression(s);
    if (!std::isfinite(value))
      fail(s,
           "the expression gives no finite number (" + twelve_digits(value) + "); narrow [min_stretch, max_stretch]");
  }
  if (is_pressure) {
    const double p1 = expression(1.0);
    if (!(std::abs(p1) <= kNaturalStateTolerance * rho))
      fail(1.0, "p = " + twelve_digits(p1) +
                    " (in units of rest_density c^2); the natural state s = 1 is unstressed, p = 0");
  } else {
    const double w1 = expression(1.0);
    if (!(std::abs(w1 - rho) <= kNaturalStateTolerance * rho))
      fail(1.0, "W = " + twelve_digits(w1) + " (in units of rest_density c^2 = " + twelve_digits(rho) +
                    "); W(1) is the rest energy, rest_density c^2");
    const double p1 = material.pressure(Stretch::natural());
    if (!(std::abs(p1) <= kNaturalPressureTolerance * rho))
      fail(1.0,
           "p = -dW/ds = " + twelve_digits(p1) + " (in units of rest_density c^2); the natural state is unstressed");
  }
  for (const double value : stretches) {
    const Stretch s = Stretch::from_value(value);
    const double enthalpy = material.enthalpy_density(s);
    const double stiffness = material.stiffness(s);
    if (!(enthalpy > 0.0)) fail(value, "e + p = " + twelve_digits(enthalpy) + " is not positive");
    if (!(stiffness > 0.0))
      fail(value,
           std::string("not hyperbolic: ") +
               (is_pressure ? "dp/ds = " + twelve_digits(-stiffness) + " is not negative (p must fall as s grows)"
                            : "W'' = " + twelve_digits(stiffness) + " is not positive (W must be convex)"));
    // c_s² = s W''/(e + p) (docs/physics.md), taken as c where above it by less than the tables' accuracy:
    // the material's own sound_speed, which the solvers and the registry's check read.
    if (!(material.sound_speed(s) <= 1.0))
      fail(value, "acausal: the sound speed c_s = " + twelve_digits(std::sqrt(value * stiffness / enthalpy)) +
                      " c exceeds c; narrow [min_stretch, max_stretch] or change the law");
  }
}

class FormulaPressure final : public PressureLawMaterial {
 public:
  FormulaPressure(const ParameterValues& values, Law law)
      : PressureLawMaterial(values.number("rest_density"), law.window), expression_(std::move(law.expression)) {
    check_law(*this, *expression_, true, admissible());
  }
  [[nodiscard]] std::string_view model() const override { return kName; }

 private:
  [[nodiscard]] double pressure_law(double s) const override { return (*expression_)(s); }
  std::unique_ptr<Expression> expression_;
};

class FormulaStrainEnergy final : public StrainEnergyMaterial {
 public:
  FormulaStrainEnergy(const ParameterValues& values, Law law)
      : StrainEnergyMaterial(values.number("rest_density"), law.window), expression_(std::move(law.expression)) {
    check_law(*this, *expression_, false, admissible());
  }
  [[nodiscard]] std::string_view model() const override { return kName; }

 private:
  [[nodiscard]] double strain_energy_law(double s) const override { return (*expression_)(s); }
  std::unique_ptr<Expression> expression_;
};

std::shared_ptr<const Material> make_formula(const ParameterValues& values) {
  Law law = read_law(values);
  if (law.is_pressure) return std::make_shared<const FormulaPressure>(values, std::move(law));
  return std::make_shared<const FormulaStrainEnergy>(values, std::move(law));
}

/// registry.hpp's pattern, with a factory that picks the form the scene wrote.
MaterialInfo describe_formula(const char* file, int line) {
  MaterialInfo info;
  info.name = std::string(kName);
  info.doc = doc();
  info.parameters = parameters();
  info.make = &make_formula;
  info.file = file;
  info.line = line;
  return info;
}

[[maybe_unused]] const bool registered =
    MaterialRegistry::instance().add_compiled(kPluginAbiVersion, &describe_formula, __FILE__, __LINE__);

}  // namespace
}  // namespace rigidity
