#pragma once
/// The material registry. A material registers itself from its own file:
///
///   class Rigid final : public rigidity::Material {
///    public:
///     static constexpr std::string_view kName = "rigid";
///     static std::string doc();
///     static std::vector<rigidity::ParameterSpec> parameters();
///     explicit Rigid(const rigidity::ParameterValues& values);
///     ...
///   };
///   RIGIDITY_REGISTER_MATERIAL(Rigid);
///
/// Adding a material touches no central list. A duplicate name is an error naming
/// both places; an unknown name lists the registered ones and the closest match.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/parameters.hpp"

namespace rigidity {

using MaterialFactory = std::function<std::shared_ptr<const Material>(const ParameterValues&)>;

struct MaterialInfo {
  std::string name;
  std::string doc;
  std::vector<ParameterSpec> parameters;
  MaterialFactory make;
  std::string file;  ///< where it registered (__FILE__)
  int line = 0;      ///< (__LINE__)
};

class MaterialRegistry {
 public:
  static MaterialRegistry& instance();

  /// Records a material. A duplicate name is recorded as a conflict (reported by
  /// check()) during static initialisation, and thrown as std::runtime_error after it.
  bool add(MaterialInfo info);

  /// \throws std::runtime_error naming both places if two materials share a name.
  void check() const;

  /// nullptr if unknown.
  [[nodiscard]] const MaterialInfo* find(std::string_view name) const;
  /// \throws std::invalid_argument listing the registered names and the closest match.
  [[nodiscard]] const MaterialInfo& at(std::string_view name) const;
  /// Registered names, sorted.
  [[nodiscard]] std::vector<std::string> names() const;
  /// The registered name closest to `name` (edit distance), or "" if none is close.
  [[nodiscard]] std::string closest(std::string_view name) const;

  /// Called by main() once static initialisation is over: later duplicates throw.
  void seal() { sealed_ = true; }

 private:
  MaterialRegistry() = default;
  std::vector<MaterialInfo> materials_;
  std::vector<std::string> conflicts_;
  bool sealed_ = false;
};

/// The MaterialInfo of a material class that follows the pattern above.
template <class M>
MaterialInfo describe_material(const char* file, int line) {
  MaterialInfo info;
  info.name = std::string(M::kName);
  info.doc = M::doc();
  info.parameters = M::parameters();
  info.make = [](const ParameterValues& values) -> std::shared_ptr<const Material> {
    return std::make_shared<const M>(values);
  };
  info.file = file;
  info.line = line;
  return info;
}

}  // namespace rigidity

#define RIGIDITY_DETAIL_CONCAT2(a, b) a##b
#define RIGIDITY_DETAIL_CONCAT(a, b) RIGIDITY_DETAIL_CONCAT2(a, b)

/// Registers material class M (see above) under M::kName, recording file and line.
#define RIGIDITY_REGISTER_MATERIAL(M)                                                     \
  [[maybe_unused]] static const bool RIGIDITY_DETAIL_CONCAT(rigidity_registered_, __LINE__) = \
      ::rigidity::MaterialRegistry::instance().add(::rigidity::describe_material<M>(__FILE__, __LINE__))
