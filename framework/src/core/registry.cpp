#include "rigidity/registry.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>

#include "rigidity/number_text.hpp"
#include "rigidity/spelling.hpp"

namespace rigidity {

MaterialRegistry& MaterialRegistry::instance() {
  static MaterialRegistry registry;
  return registry;
}

bool MaterialRegistry::add(MaterialInfo info) {
  const std::unique_lock lock(mutex_);
  return add_locked(std::move(info));
}

bool MaterialRegistry::add_locked(MaterialInfo info) {
  for (const MaterialInfo& existing : materials_) {
    if (existing.name != info.name) continue;
    std::string conflict = "material '" + info.name + "' is registered twice: at " + existing.file + ":" +
                           std::to_string(existing.line) + " and at " + info.file + ":" + std::to_string(info.line);
    if (sealed_ && !in_batch_) throw std::runtime_error(conflict);
    conflicts_.push_back(std::move(conflict));
    return false;
  }
  materials_.push_back(std::move(info));
  return true;
}

bool MaterialRegistry::add_compiled(int abi_version, Describe describe, const char* file, int line) {
  const std::unique_lock lock(mutex_);
  if (abi_version == kPluginAbiVersion) return add_locked(describe(file, line));
  std::string conflict = "the material registered at " + std::string(file) + ":" + std::to_string(line) +
                         " was compiled against rigidity plugin ABI " + std::to_string(abi_version) +
                         ", this rigidity has plugin ABI " + std::to_string(kPluginAbiVersion);
  if (sealed_ && !in_batch_) throw std::runtime_error(conflict);
  conflicts_.push_back(std::move(conflict));
  return false;
}

void MaterialRegistry::begin_batch() {
  const std::unique_lock lock(mutex_);
  in_batch_ = true;
  batch_first_material_ = materials_.size();
  batch_first_conflict_ = conflicts_.size();
}

std::vector<const MaterialInfo*> MaterialRegistry::batch_materials() const {
  const std::shared_lock lock(mutex_);
  std::vector<const MaterialInfo*> out;
  for (std::size_t i = batch_first_material_; i < materials_.size(); ++i) out.push_back(&materials_[i]);
  return out;
}

std::vector<std::string> MaterialRegistry::batch_conflicts() const {
  const std::shared_lock lock(mutex_);
  return {conflicts_.begin() + static_cast<std::ptrdiff_t>(batch_first_conflict_), conflicts_.end()};
}

void MaterialRegistry::end_batch(bool keep) {
  const std::unique_lock lock(mutex_);
  if (!keep)
    materials_.erase(materials_.begin() + static_cast<std::ptrdiff_t>(batch_first_material_), materials_.end());
  conflicts_.erase(conflicts_.begin() + static_cast<std::ptrdiff_t>(batch_first_conflict_), conflicts_.end());
  in_batch_ = false;
}

void MaterialRegistry::check() const {
  const std::shared_lock lock(mutex_);
  if (conflicts_.empty()) return;
  std::string all;
  for (const std::string& c : conflicts_) all += (all.empty() ? "" : "\n") + c;
  throw std::runtime_error(all);
}

const MaterialInfo* MaterialRegistry::find(std::string_view name) const {
  const std::shared_lock lock(mutex_);
  for (const MaterialInfo& m : materials_)
    if (m.name == name) return &m;
  return nullptr;
}

const MaterialInfo& MaterialRegistry::at(std::string_view name) const {
  if (const MaterialInfo* m = find(name)) return *m;
  std::string message = "unknown material model '" + std::string(name) + "'";
  const std::string near = closest(name);
  if (!near.empty()) message += " (did you mean '" + near + "'?)";
  message += "; registered:";
  for (const std::string& n : names()) message += " " + n;
  throw std::invalid_argument(message);
}

std::vector<std::string> MaterialRegistry::names() const {
  const std::shared_lock lock(mutex_);
  std::vector<std::string> out;
  for (const MaterialInfo& m : materials_) out.push_back(m.name);
  std::sort(out.begin(), out.end());
  return out;
}

std::string MaterialRegistry::closest(std::string_view name) const { return closest_match(name, names()); }

namespace {
/// Points of ln s at which a material is checked, ends included.
constexpr int kAdmissibilitySamples = 256;
/// Where an unbounded admissible range is sampled to: s in [1e-6, 1e6].
constexpr double kUnboundedLogStretch = 13.815510557964274;  // ln 1e6

std::string number_text(double v) { return significant(v, 6); }
}  // namespace

/// Empty if `material` is hyperbolic and causal at every sample of its admissible range (and
/// at s = 1), else why not.
std::string admissibility_problem(const Material& material) {
  const StretchRange range = material.admissible();
  const std::string name = "material '" + std::string(material.model()) + "'";
  if (!range.contains(Stretch::natural())) return name + ": its admissible range does not contain s = 1";
  const double lo = std::isfinite(range.log_min) ? range.log_min : std::min(-kUnboundedLogStretch, range.log_max);
  const double hi = std::isfinite(range.log_max) ? range.log_max : std::max(kUnboundedLogStretch, range.log_min);
  const std::string sampled = " (checked at " + std::to_string(kAdmissibilitySamples + 1) + " stretches from " +
                              number_text(std::exp(lo)) + " to " + number_text(std::exp(hi)) +
                              ", its admissible range)";
  for (int i = 0; i <= kAdmissibilitySamples + 1; ++i) {
    const Stretch s = i == kAdmissibilitySamples + 1 ? Stretch::natural()
                      : i == kAdmissibilitySamples   ? Stretch::from_log(hi)
                                                     : Stretch::from_log(lo + (hi - lo) * i / kAdmissibilitySamples);
    try {
      if (const std::string violation = material.admissibility_violation(s); !violation.empty())
        return violation + sampled;
      const double stiffness = material.stiffness(s);
      if (!(stiffness > 0.0))
        return name + " is not hyperbolic at stretch " + number_text(s.value()) + " (W'' = " + number_text(stiffness) +
               ")" + sampled;
      if (!std::isfinite(material.pressure(s)) || !std::isfinite(material.energy_density(s)) ||
          !std::isfinite(material.riemann_psi(s)))
        return name + " gives no number at stretch " + number_text(s.value()) + sampled;
    } catch (const std::exception& e) {
      return name + ": evaluating it at stretch " + number_text(s.value()) + " failed: " + e.what();
    }
  }
  return "";
}

namespace {

/// Parameter sets already found hyperbolic and causal on their range (a sweep builds the same
/// material thousands of times; the check samples the law at a thousand stretches). Only sets
/// of numbers: a text parameter may name a file whose contents can change between builds.
std::mutex admissible_mutex;
std::set<std::string> admissible_sets;

/// The key of a set of numbers for one registration; empty for a set with text parameters.
std::string parameter_key(const MaterialInfo& info, const ParameterValues& values) {
  if (!values.texts().empty()) return {};
  char number[40];
  std::snprintf(number, sizeof number, "%p", static_cast<const void*>(&info));  // one registration
  std::string key = info.name + "@" + number;
  for (const auto& [name, value] : values.numbers()) {
    std::snprintf(number, sizeof number, "%a", value);  // exact
    key += "\n" + name + "=" + number;
  }
  return key;
}

bool admissible_before(const std::string& key) {
  if (key.empty()) return false;
  const std::lock_guard<std::mutex> lock(admissible_mutex);
  return admissible_sets.count(key) != 0;
}

void remember_admissible(const std::string& key) {
  if (key.empty()) return;
  const std::lock_guard<std::mutex> lock(admissible_mutex);
  if (admissible_sets.size() > 100000) admissible_sets.clear();  // a bound, not a policy
  admissible_sets.insert(key);
}

}  // namespace

std::shared_ptr<const Material> build_material(const MaterialInfo& info, const ParameterValues& given) {
  ParameterValues values;
  values.set_directory(given.directory());
  values.set_units(given.units());
  for (const ParameterSpec& spec : info.parameters) {
    if (spec.default_number) values.set(spec.name, *spec.default_number);
    if (spec.default_text) values.set(spec.name, *spec.default_text);
  }
  const auto declared = [&info](const std::string& key) {
    return std::find_if(info.parameters.begin(), info.parameters.end(),
                        [&key](const ParameterSpec& p) { return p.name == key; });
  };
  for (const auto& entry : given.numbers()) {
    const std::size_t dot = entry.first.find('.');
    if (dot != std::string::npos) {  // an entry of a map of numbers (a formula's parameters): the material checks it
      const auto map = declared(entry.first.substr(0, dot));
      if (map == info.parameters.end() || map->type != ParameterType::numbers)
        throw std::invalid_argument("'" + info.name + "' has no parameter '" + entry.first + "'");
      values.set(entry.first, entry.second);
      continue;
    }
    const auto spec = declared(entry.first);
    if (spec == info.parameters.end())
      throw std::invalid_argument("'" + info.name + "' has no parameter '" + entry.first + "'");
    if (const std::string rule = spec->range_violation(entry.second); !rule.empty())
      throw std::invalid_argument(entry.first + " " + rule);
    values.set(entry.first, entry.second);
  }
  for (const auto& entry : given.texts()) {
    if (declared(entry.first) == info.parameters.end())
      throw std::invalid_argument("'" + info.name + "' has no parameter '" + entry.first + "'");
    values.set(entry.first, entry.second);
  }
  for (const ParameterSpec& spec : info.parameters)
    if (spec.required && !values.has(spec.name))
      throw std::invalid_argument("'" + info.name + "' needs '" + spec.name + "'");
  std::shared_ptr<const Material> material = info.make(values);
  const std::string key = parameter_key(info, values);
  if (admissible_before(key)) return material;
  if (const std::string problem = admissibility_problem(*material); !problem.empty())
    throw std::invalid_argument(problem);
  remember_admissible(key);
  return material;
}

std::shared_ptr<const Material> build_material(std::string_view name, const ParameterValues& given) {
  return build_material(MaterialRegistry::instance().at(name), given);
}

}  // namespace rigidity
