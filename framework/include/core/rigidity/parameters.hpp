#pragma once
/// Declared parameters of a material: one declaration (name, type, default or
/// required, dimension, range, doc) that the YAML loader, `rigidity materials` and
/// the docs all read.

#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rigidity/units.hpp"

namespace rigidity {

/// number: one number; text: one string; numbers: a map from names the scene chooses to numbers
/// (a formula's parameters), whose values ParameterValues holds as numbers named "KEY.NAME".
enum class ParameterType { number, text, numbers };

struct Bound {
  double value = 0.0;
  bool inclusive = true;
};

struct ParameterSpec {
  std::string name;
  std::string doc;
  ParameterType type = ParameterType::number;
  Dimension dimension = Dimension::dimensionless;
  bool required = false;
  std::optional<double> default_number;     ///< default of an optional number
  std::optional<std::string> default_text;  ///< default of an optional text
  std::optional<Bound> lower;               ///< in natural units
  std::optional<Bound> upper;               ///< in natural units

  /// Builders, read as a declaration:
  ///   ParameterSpec::number("wave_speed", "shock speed V relative to the unstrained bar")
  ///       .with_dimension(Dimension::velocity).require().above(0.0).at_most(1.0)
  static ParameterSpec number(std::string name, std::string doc);
  static ParameterSpec text(std::string name, std::string doc);
  /// A map of names to numbers, optional, empty by default; no dimension or range of its own: each
  /// entry is a number or its declaration {value, unit, min, max, doc}, whose range the scene
  /// loader checks, and the material checks the rest.
  static ParameterSpec numbers(std::string name, std::string doc);
  ParameterSpec& with_dimension(Dimension d);
  ParameterSpec& require();
  ParameterSpec& defaults_to(double v);
  ParameterSpec& defaults_to(std::string v);
  ParameterSpec& above(double v);     ///< > v
  ParameterSpec& at_least(double v);  ///< >= v
  ParameterSpec& below(double v);     ///< < v
  ParameterSpec& at_most(double v);   ///< <= v

  /// Empty if v satisfies the range, else the rule it breaks, e.g. "must be in (0, 1]".
  [[nodiscard]] std::string range_violation(double v) const;
  /// The range as text, "(0, 1]", "> 0", or "" if unbounded.
  [[nodiscard]] std::string range_text() const;
};

/// Validated parameter values of one material instance, in natural units.
class ParameterValues {
 public:
  void set(const std::string& name, double v) { numbers_[name] = v; }
  void set(const std::string& name, std::string v) { texts_[name] = std::move(v); }
  /// \throws std::out_of_range if absent (the loader fills every default first)
  [[nodiscard]] double number(const std::string& name) const;
  [[nodiscard]] const std::string& text(const std::string& name) const;
  [[nodiscard]] bool has(const std::string& name) const { return numbers_.count(name) != 0 || texts_.count(name) != 0; }
  [[nodiscard]] const std::map<std::string, double>& numbers() const { return numbers_; }
  [[nodiscard]] const std::map<std::string, std::string>& texts() const { return texts_; }
  /// The entries of a ParameterType::numbers parameter: name (without "KEY.") to value.
  [[nodiscard]] std::map<std::string, double> numbers_under(const std::string& key) const;

  /// The directory a relative file name among the texts (a table) is taken from: the scene
  /// file's (the loader sets it); empty for the working directory.
  void set_directory(std::string directory) { directory_ = std::move(directory); }
  [[nodiscard]] const std::string& directory() const { return directory_; }

  /// The scene's unit system, in which the numbers of a file among the texts (a table) are
  /// written (the loader sets it); the numbers above are already natural.
  void set_units(UnitSystem units) { units_ = units; }
  [[nodiscard]] UnitSystem units() const { return units_; }

 private:
  std::map<std::string, double> numbers_;
  std::map<std::string, std::string> texts_;
  std::string directory_;
  UnitSystem units_ = UnitSystem::natural;
};

/// A material's objection to one of its parameters, which the scene loader reports at that
/// key (`parameter` is its dotted name under the material: "pressure", "parameters.rho").
class ParameterError : public std::invalid_argument {
 public:
  ParameterError(std::string parameter, const std::string& message)
      : std::invalid_argument(message), parameter_(std::move(parameter)) {}
  [[nodiscard]] const std::string& parameter() const noexcept { return parameter_; }

 private:
  std::string parameter_;
};

/// The `rest_density` declaration every material shares (ρ00, default 1).
[[nodiscard]] ParameterSpec rest_density_parameter();

}  // namespace rigidity
