#include "rigidity/parameters.hpp"

#include <cmath>
#include <stdexcept>

#include "rigidity/number_text.hpp"

namespace rigidity {

ParameterSpec ParameterSpec::number(std::string name, std::string doc) {
  ParameterSpec p;
  p.name = std::move(name);
  p.doc = std::move(doc);
  p.type = ParameterType::number;
  return p;
}

ParameterSpec ParameterSpec::text(std::string name, std::string doc) {
  ParameterSpec p;
  p.name = std::move(name);
  p.doc = std::move(doc);
  p.type = ParameterType::text;
  return p;
}

ParameterSpec ParameterSpec::numbers(std::string name, std::string doc) {
  ParameterSpec p;
  p.name = std::move(name);
  p.doc = std::move(doc);
  p.type = ParameterType::numbers;
  return p;
}

ParameterSpec& ParameterSpec::with_dimension(Dimension d) {
  dimension = d;
  return *this;
}
ParameterSpec& ParameterSpec::require() {
  required = true;
  return *this;
}
ParameterSpec& ParameterSpec::defaults_to(double v) {
  default_number = v;
  required = false;
  return *this;
}
ParameterSpec& ParameterSpec::defaults_to(std::string v) {
  default_text = std::move(v);
  required = false;
  return *this;
}
ParameterSpec& ParameterSpec::above(double v) {
  lower = Bound{v, false};
  return *this;
}
ParameterSpec& ParameterSpec::at_least(double v) {
  lower = Bound{v, true};
  return *this;
}
ParameterSpec& ParameterSpec::below(double v) {
  upper = Bound{v, false};
  return *this;
}
ParameterSpec& ParameterSpec::at_most(double v) {
  upper = Bound{v, true};
  return *this;
}

namespace {
std::string number_text(double v) { return significant(v, 15); }
}  // namespace

std::string ParameterSpec::range_text() const {
  if (lower && upper)
    return std::string(lower->inclusive ? "[" : "(") + number_text(lower->value) + ", " + number_text(upper->value) +
           (upper->inclusive ? "]" : ")");
  if (lower) return std::string(lower->inclusive ? ">= " : "> ") + number_text(lower->value);
  if (upper) return std::string(upper->inclusive ? "<= " : "< ") + number_text(upper->value);
  return "";
}

std::string ParameterSpec::range_violation(double v) const {
  const bool below_lower = lower && (lower->inclusive ? v < lower->value : v <= lower->value);
  const bool above_upper = upper && (upper->inclusive ? v > upper->value : v >= upper->value);
  if (!std::isfinite(v)) return "must be a finite number";
  if (below_lower || above_upper) {
    const std::string range = range_text();
    return (lower && upper) ? "must be in " + range : "must be " + range;
  }
  return "";
}

double ParameterValues::number(const std::string& name) const {
  auto it = numbers_.find(name);
  if (it == numbers_.end()) throw std::out_of_range("material parameter '" + name + "' has no value");
  return it->second;
}

const std::string& ParameterValues::text(const std::string& name) const {
  auto it = texts_.find(name);
  if (it == texts_.end()) throw std::out_of_range("material parameter '" + name + "' has no value");
  return it->second;
}

std::map<std::string, double> ParameterValues::numbers_under(const std::string& key) const {
  std::map<std::string, double> out;
  const std::string prefix = key + ".";
  for (auto it = numbers_.lower_bound(prefix); it != numbers_.end() && it->first.compare(0, prefix.size(), prefix) == 0;
       ++it)
    out.emplace(it->first.substr(prefix.size()), it->second);
  return out;
}

ParameterSpec rest_density_parameter() {
  return ParameterSpec::number("rest_density", "rho00: mass density of the unstrained material at rest")
      .with_dimension(Dimension::density)
      .defaults_to(1.0)
      .above(0.0);
}

}  // namespace rigidity
