#pragma once
/// The strict YAML scene loader (docs/scenes.md). Every key is declared; anything else —
/// an unknown key (with the nearest valid one), a wrong type, a value out of range,
/// NaN or inf, a missing required key, an inconsistent combination — throws
/// InputError "FILE:LINE:COL: error: key 'k': rule". Nothing is run on an invalid scene.

#include <string>
#include <string_view>
#include <vector>

#include "rigidity/scene.hpp"

namespace rigidity {

/// Reads and validates a scene file. `overrides` are "key.path=value" strings from
/// `--set` (list elements addressed by index: "bodies.0.velocity=0.8"), applied
/// before validation. The plugins the scene lists, and those on RIGIDITY_PLUGIN_PATH, are
/// loaded before its materials are read (plugins.hpp); relative paths in the scene (plugins,
/// a `tabulated` material's table) start at the file's directory. \throws InputError
[[nodiscard]] Scene load_scene_file(const std::string& path, const std::vector<std::string>& overrides = {});

/// The same, from text; `source` names it in messages; relative paths start at the working directory.
[[nodiscard]] Scene load_scene_string(std::string_view text, const std::string& source,
                                      const std::vector<std::string>& overrides = {});

/// The embedded default scene: the paper's wall impact (configs/paper_wall_impact.yaml).
[[nodiscard]] std::string_view default_scene_text();

}  // namespace rigidity
