#pragma once
/// Every registered material, built from its declared parameters, for the tests that claim
/// "every material": the registry is iterated, never a list of names. Required numbers take
/// values inside their declared ranges, required texts the samples of material_test_support.
/// For the materials of docs/materials.md the closed-form law (exact/law.hpp) is given beside.

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/material_test_support.hpp"
#include "exact/law.hpp"
#include "rigidity/registry.hpp"

namespace rigidity::exact {

struct MaterialSample {
  std::string model;
  std::map<std::string, double> values;
  std::shared_ptr<const Material> material;
  /// The closed form of docs/materials.md, for the four built-in laws it gives; empty otherwise.
  std::optional<ClosedFormLaw<double>> closed_form() const {
    const double rho = values.at("rest_density");
    if (model == "rigid") return rigid(rho);
    if (model == "rigid_fluid") return rigid_fluid(rho);
    if (model == "hooke") return hooke(rho, values.at("wave_speed"));
    if (model == "constant_sound_speed") return constant_sound_speed(rho, values.at("sound_speed"));
    return std::nullopt;
  }
};

/// Each registered material at rest density 1.3 and, for each required number, the values
/// 0.5 and 0.8 where its range allows (else the middle of its range).
inline std::vector<MaterialSample> registry_samples() {
  std::vector<MaterialSample> out;
  const MaterialRegistry& registry = MaterialRegistry::instance();
  for (const std::string& name : registry.names()) {
    const MaterialInfo& info = registry.at(name);
    std::vector<std::map<std::string, double>> variants{{{"rest_density", 1.3}}};
    for (const ParameterSpec& spec : info.parameters) {
      if (spec.type != ParameterType::number || !spec.required) continue;
      std::vector<double> choices;
      for (double v : {0.5, 0.8})
        if (spec.range_violation(v).empty()) choices.push_back(v);
      if (choices.empty() && spec.lower && spec.upper) choices.push_back(0.5 * (spec.lower->value + spec.upper->value));
      std::vector<std::map<std::string, double>> next;
      for (const auto& base : variants)
        for (double v : choices) {
          auto values = base;
          values[spec.name] = v;
          next.push_back(values);
        }
      variants = next;
    }
    for (const auto& values : variants) {
      const bool has_rho = std::any_of(info.parameters.begin(), info.parameters.end(),
                                       [](const ParameterSpec& p) { return p.name == "rest_density"; });
      auto given = values;
      if (!has_rho) given.erase("rest_density");
      out.push_back({name, values, testing::make_material(name, given)});
    }
  }
  return out;
}

}  // namespace rigidity::exact
