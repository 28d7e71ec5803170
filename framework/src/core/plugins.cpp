// Loading material plugins (plugins.hpp): dlopen, the ABI check, the batch of materials the
// library registered, and the admissibility check of each before it is kept.
#include "rigidity/plugins.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <sstream>
#include <system_error>

#include "rigidity/config.hpp"
#include "rigidity/material.hpp"

namespace rigidity {
namespace {

namespace fs = std::filesystem;

/// The file name ending of a shared library on this platform.
#ifdef __APPLE__
constexpr std::string_view kLibrarySuffix = ".dylib";
#else
constexpr std::string_view kLibrarySuffix = ".so";
#endif

/// The plugins loaded so far (a deque: references stay valid), and the lock of all loading.
struct Plugins {
  std::recursive_mutex mutex;
  std::deque<LoadedPlugin> loaded;
  std::string environment;  ///< the value of RIGIDITY_PLUGIN_PATH last loaded in full
};

Plugins& plugins() {
  static Plugins instance;
  return instance;
}

/// Empty if the library just opened (its materials the registry's open batch) may be kept,
/// else why not; `plugin` receives its materials and notes.
std::string refusal(void* handle, const MaterialRegistry& registry, LoadedPlugin& plugin) {
  using AbiVersion = int (*)();
  using BuiltAgainst = const char* (*)();
  const auto abi_version = reinterpret_cast<AbiVersion>(dlsym(handle, "rigidity_plugin_abi_version"));
  if (abi_version == nullptr)
    return "is not a rigidity plugin: it does not define rigidity_plugin_abi_version() (RIGIDITY_PLUGIN() in one "
           "of its source files defines it; see rigidity/plugins.hpp)";
  if (const int abi = abi_version(); abi != kPluginAbiVersion) {
    const auto built_against = reinterpret_cast<BuiltAgainst>(dlsym(handle, "rigidity_plugin_built_against"));
    const std::string against = built_against != nullptr ? std::string("rigidity ") + built_against() : "a rigidity";
    return "was built against " + against + " (plugin ABI " + std::to_string(abi) +
           "); this is rigidity " RIGIDITY_VERSION_STRING " (plugin ABI " + std::to_string(kPluginAbiVersion) +
           "): rebuild it against this version";
  }
  if (const std::vector<std::string> conflicts = registry.batch_conflicts(); !conflicts.empty()) {
    std::string all;
    for (const std::string& c : conflicts) all += (all.empty() ? "" : "; ") + c;
    return "cannot register its materials: " + all;
  }
  const std::vector<const MaterialInfo*> materials = registry.batch_materials();
  if (materials.empty())
    return "registers no material (a plugin registers each of its materials with RIGIDITY_REGISTER_MATERIAL)";
  for (const MaterialInfo* info : materials) {
    plugin.materials.push_back(info->name);
    std::string required;
    for (const ParameterSpec& p : info->parameters)
      if (p.required) required += (required.empty() ? "'" : ", '") + p.name + "'";
    if (!required.empty()) {
      plugin.notes.push_back("material '" + info->name + "' was not checked at load: it requires " + required +
                             " (a scene that uses it checks it with the parameters it gives)");
      continue;
    }
    try {
      (void)build_material(*info, ParameterValues{});
    } catch (const std::exception& e) {
      return "is refused: material '" + info->name + "' with its default parameters: " + e.what();
    }
  }
  return "";
}

std::string plugin_error(const std::string& path, const std::string& reason) {
  return "plugin '" + path + "' " + reason;
}

}  // namespace

const LoadedPlugin& load_plugin(const fs::path& path) {
  Plugins& all = plugins();
  const std::lock_guard lock(all.mutex);
  std::error_code ec;
  const fs::path canonical = fs::canonical(path, ec);
  if (ec)
    throw PluginError(plugin_error(path.string(), ec == std::errc::no_such_file_or_directory
                                                      ? "does not exist"
                                                      : "cannot be read: " + ec.message()));
  if (!fs::is_regular_file(canonical, ec)) throw PluginError(plugin_error(canonical.string(), "is not a file"));
  for (const LoadedPlugin& p : all.loaded)
    if (p.path == canonical.string()) return p;

  MaterialRegistry& registry = MaterialRegistry::instance();
  LoadedPlugin plugin;
  plugin.path = canonical.string();
  registry.begin_batch();
  // RTLD_NOW: a symbol this rigidity does not have (a plugin built against another version)
  // fails here, with the symbol's name, and not later in the middle of a run.
  void* handle = dlopen(plugin.path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    registry.end_batch(false);
    const char* reason = dlerror();
    std::string message = "cannot be loaded: " + std::string(reason != nullptr ? reason : "unknown error");
    if (message.find("undefined symbol") != std::string::npos)
      message += " (was it built against another version of rigidity?)";
    throw PluginError(plugin_error(plugin.path, message));
  }
  std::string reason;
  try {
    reason = refusal(handle, registry, plugin);
  } catch (...) {
    registry.end_batch(false);
    dlclose(handle);
    throw;
  }
  if (!reason.empty()) {
    registry.end_batch(false);  // first: the materials' code lives in the library
    dlclose(handle);
    throw PluginError(plugin_error(plugin.path, reason));
  }
  registry.end_batch(true);
  all.loaded.push_back(std::move(plugin));
  return all.loaded.back();
}

void load_scene_plugins(const std::vector<PluginReference>& references, const fs::path& directory) {
  for (const PluginReference& reference : references) {
    const fs::path written(reference.path);
    const fs::path path = written.is_absolute() || directory.empty() ? written : directory / written;
    try {
      static_cast<void>(load_plugin(path));
    } catch (const PluginError& e) {
      throw InputError(reference.where, reference.key, e.what());
    }
  }
}

void load_environment_plugins() {
  const char* value = std::getenv("RIGIDITY_PLUGIN_PATH");
  if (value == nullptr || *value == '\0') return;
  Plugins& all = plugins();
  const std::lock_guard lock(all.mutex);
  if (all.environment == value) return;
  const SourceLocation where{"RIGIDITY_PLUGIN_PATH", 0, 0};
  std::vector<fs::path> files;
  std::string_view rest(value);
  while (!rest.empty()) {
    const std::size_t colon = rest.find(':');
    const fs::path entry(rest.substr(0, colon));
    rest = colon == std::string_view::npos ? std::string_view() : rest.substr(colon + 1);
    if (entry.empty()) continue;
    std::error_code ec;
    if (fs::is_directory(entry, ec)) {
      std::vector<fs::path> found;
      for (const fs::directory_entry& file : fs::directory_iterator(entry, ec))
        if (file.path().extension() == kLibrarySuffix && file.is_regular_file(ec)) found.push_back(file.path());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(entry, ec)) {
      files.push_back(entry);
    } else {
      throw InputError(where, "", "'" + entry.string() + "' is neither a directory nor a file");
    }
  }
  for (const fs::path& file : files) {
    try {
      static_cast<void>(load_plugin(file));
    } catch (const PluginError& e) {
      throw InputError(where, "", e.what());
    }
  }
  all.environment = value;
}

std::vector<LoadedPlugin> loaded_plugins() {
  Plugins& all = plugins();
  const std::lock_guard lock(all.mutex);
  return {all.loaded.begin(), all.loaded.end()};
}

}  // namespace rigidity
