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
///
/// A plugin (plugins.hpp) registers its materials with the same macro. The registration passes
/// the plugin ABI version the material was compiled against before anything whose layout
/// could differ, so that a material built against another version is refused, not misread.

#include <deque>
#include <functional>
#include <memory>
#include <shared_mutex>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/parameters.hpp"

namespace rigidity {

/// The version of everything a plugin and the framework share (Material, MaterialInfo,
/// ParameterSpec, ParameterValues, Stretch, Solved, NumericMaterial, PiecewiseChebyshev...):
/// bump it whenever one of their layouts or virtual functions changes.
inline constexpr int kPluginAbiVersion = 3;

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

  /// What RIGIDITY_REGISTER_MATERIAL calls: add(describe(file, line)) if `abi_version` is this
  /// framework's kPluginAbiVersion; else `describe` is not called (its MaterialInfo may not be
  /// ours) and the mismatch is a conflict, as a duplicate is.
  using Describe = MaterialInfo (*)(const char* file, int line);
  bool add_compiled(int abi_version, Describe describe, const char* file, int line);

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

  // ---- plugin loading (plugins.cpp) ------------------------------------------------
  // The materials a library registers while it is being opened form a batch. During a batch a
  // conflict is recorded even when sealed (an exception must not cross the dynamic loader),
  // and the batch can be withdrawn if the plugin is refused.

  /// Starts a batch. \pre no batch is open
  void begin_batch();
  /// The materials added since begin_batch(), in order.
  [[nodiscard]] std::vector<const MaterialInfo*> batch_materials() const;
  /// The conflicts recorded since begin_batch().
  [[nodiscard]] std::vector<std::string> batch_conflicts() const;
  /// Ends the batch: keeps its materials, or removes them again; its conflicts are dropped
  /// either way (the plugin loader reports them).
  void end_batch(bool keep);

 private:
  MaterialRegistry() = default;
  bool add_locked(MaterialInfo info);
  /// Lookups share it; adding and withdrawing take it alone, so that a sweep case loading a
  /// plugin on one thread does not race another case looking a material up.
  mutable std::shared_mutex mutex_;
  std::deque<MaterialInfo> materials_;  ///< a deque: references stay valid as plugins add more
  std::vector<std::string> conflicts_;
  bool sealed_ = false;
  bool in_batch_ = false;
  std::size_t batch_first_material_ = 0;
  std::size_t batch_first_conflict_ = 0;
};

/// The one way to build a registered material, for a scene, a plugin check, `compare`, a test
/// or a benchmark alike: the declared defaults, then `given` (a number given must lie in its
/// declared range, and the material must declare it), every required parameter present; then
/// the material, with exactly these parameters, must be hyperbolic and causal on its admissible
/// range (admissibility_problem). \throws std::invalid_argument saying which rule broke.
[[nodiscard]] std::shared_ptr<const Material> build_material(const MaterialInfo& info, const ParameterValues& given);
/// The same for a registered name. \throws std::invalid_argument for an unknown name too.
[[nodiscard]] std::shared_ptr<const Material> build_material(std::string_view name, const ParameterValues& given = {});

/// Empty if `material` is hyperbolic (W'' > 0) and causal (c_s ≤ c), with finite pressure,
/// energy and Ψ, at s = 1 and at 257 stretches spanning its admissible range (s in [1e-6, 1e6]
/// where the range is unbounded); else the first violation and where.
[[nodiscard]] std::string admissibility_problem(const Material& material);

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
#define RIGIDITY_REGISTER_MATERIAL(M)                                                         \
  [[maybe_unused]] static const bool RIGIDITY_DETAIL_CONCAT(rigidity_registered_, __LINE__) = \
      ::rigidity::MaterialRegistry::instance().add_compiled(::rigidity::kPluginAbiVersion,    \
                                                            &::rigidity::describe_material<M>, __FILE__, __LINE__)
