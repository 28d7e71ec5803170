#include "rigidity/registry.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>

#include "rigidity/spelling.hpp"

namespace rigidity {

MaterialRegistry& MaterialRegistry::instance() {
  static MaterialRegistry registry;
  return registry;
}

bool MaterialRegistry::add(MaterialInfo info) {
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
  if (abi_version == kPluginAbiVersion) return add(describe(file, line));
  std::string conflict = "the material registered at " + std::string(file) + ":" + std::to_string(line) +
                         " was compiled against rigidity plugin ABI " + std::to_string(abi_version) +
                         ", this rigidity has plugin ABI " + std::to_string(kPluginAbiVersion);
  if (sealed_ && !in_batch_) throw std::runtime_error(conflict);
  conflicts_.push_back(std::move(conflict));
  return false;
}

void MaterialRegistry::begin_batch() {
  in_batch_ = true;
  batch_first_material_ = materials_.size();
  batch_first_conflict_ = conflicts_.size();
}

std::vector<const MaterialInfo*> MaterialRegistry::batch_materials() const {
  std::vector<const MaterialInfo*> out;
  for (std::size_t i = batch_first_material_; i < materials_.size(); ++i) out.push_back(&materials_[i]);
  return out;
}

std::vector<std::string> MaterialRegistry::batch_conflicts() const {
  return {conflicts_.begin() + static_cast<std::ptrdiff_t>(batch_first_conflict_), conflicts_.end()};
}

void MaterialRegistry::end_batch(bool keep) {
  if (!keep)
    materials_.erase(materials_.begin() + static_cast<std::ptrdiff_t>(batch_first_material_), materials_.end());
  conflicts_.erase(conflicts_.begin() + static_cast<std::ptrdiff_t>(batch_first_conflict_), conflicts_.end());
  in_batch_ = false;
}

void MaterialRegistry::check() const {
  if (conflicts_.empty()) return;
  std::string all;
  for (const std::string& c : conflicts_) all += (all.empty() ? "" : "\n") + c;
  throw std::runtime_error(all);
}

const MaterialInfo* MaterialRegistry::find(std::string_view name) const {
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
  std::vector<std::string> out;
  for (const MaterialInfo& m : materials_) out.push_back(m.name);
  std::sort(out.begin(), out.end());
  return out;
}

std::string MaterialRegistry::closest(std::string_view name) const { return closest_match(name, names()); }

}  // namespace rigidity
