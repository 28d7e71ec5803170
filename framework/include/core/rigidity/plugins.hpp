#pragma once
/// Materials from outside the tree. A plugin is a shared library that registers its materials
/// exactly as a built-in does, plus one line that makes it a plugin:
///
///   #include <rigidity/numeric_material.hpp>
///   #include <rigidity/plugins.hpp>
///   class MyMaterial final : public rigidity::PressureLawMaterial { ... };   // registry.hpp's pattern
///   RIGIDITY_REGISTER_MATERIAL(MyMaterial);
///   RIGIDITY_PLUGIN();
///
/// built against the installed package (`find_package(rigidity)`, link `rigidity::rigidity`; see
/// examples/plugin/). It is loaded when a scene lists it (`plugins: [path]`, relative to the scene
/// file) or when it lies on RIGIDITY_PLUGIN_PATH (directories, whose *.so files are all loaded,
/// or files, separated by ':'), before the scene's materials are read, so that a scene can use
/// the materials of the plugins it lists.
///
/// Loading refuses, with a message naming the file and the reason, a library that
///   - cannot be opened (dlopen's own message: a missing file, an undefined symbol, ...),
///   - is not a plugin (it does not define rigidity_plugin_abi_version: no RIGIDITY_PLUGIN()),
///   - was built against an incompatible rigidity (another kPluginAbiVersion),
///   - registers no material, or one whose name is taken,
///   - registers a material that, built with its defaults, is not hyperbolic (W'' > 0) or not
///     causal (0 < c_s <= 1) somewhere on its declared admissible range (sampled in ln s).
/// A refused library is unloaded and none of its materials stays registered. A material
/// with required parameters cannot be built with defaults; it is not checked at load (a note
/// says so) and is checked where a scene builds it.
///
/// Each library is loaded once per process (by its canonical path) and never unloaded.
/// Loading is serialised by a mutex.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "rigidity/config.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/registry.hpp"

/// Makes the library a rigidity plugin: defines the C functions the loader reads, the plugin
/// ABI version and the rigidity version it was compiled against. Once per plugin, at namespace scope.
#define RIGIDITY_PLUGIN()                                                                         \
  extern "C" __attribute__((visibility("default"))) int rigidity_plugin_abi_version() {           \
    return ::rigidity::kPluginAbiVersion;                                                         \
  }                                                                                               \
  extern "C" __attribute__((visibility("default"))) const char* rigidity_plugin_built_against() { \
    return RIGIDITY_VERSION_STRING;                                                               \
  }                                                                                               \
  static_assert(true, "")

namespace rigidity {

/// A library that cannot be used as a plugin; what() is "plugin 'PATH': reason".
class PluginError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A plugin as loaded.
struct LoadedPlugin {
  std::string path;                    ///< canonical (absolute, symbolic links resolved)
  std::vector<std::string> materials;  ///< the materials it registered
  std::vector<std::string> notes;      ///< what the load-time check could not cover
};

/// Loads the plugin at `path` (once: a later call for the same file returns the first result).
/// \throws PluginError, after which nothing of the library remains loaded or registered
const LoadedPlugin& load_plugin(const std::filesystem::path& path);

/// A plugin as a scene names it.
struct PluginReference {
  std::string path;      ///< as written
  std::string key;       ///< "plugins.0"
  SourceLocation where;  ///< of the value
};

/// Loads the plugins a scene lists, relative paths taken from `directory` (the scene file's;
/// empty: the working directory). \throws InputError at the reference of the first refused one
void load_scene_plugins(const std::vector<PluginReference>& plugins, const std::filesystem::path& directory);

/// Loads every plugin RIGIDITY_PLUGIN_PATH names; a value already loaded is not read again.
/// \throws InputError located at "RIGIDITY_PLUGIN_PATH" for an entry that is neither a directory
/// nor a file, or a refused plugin
void load_environment_plugins();

/// The plugins loaded so far, in the order they were loaded.
[[nodiscard]] std::vector<LoadedPlugin> loaded_plugins();

}  // namespace rigidity
