#pragma once
// From scene text to a YAML tree: hostile-input guards, `--set` overrides, and the
// file:line:column of every value for error messages. Internal to the scene loader.

#include <yaml-cpp/mark.h>

#include <string>
#include <string_view>
#include <vector>

#include "rigidity/errors.hpp"
#include "scene_tree.hpp"

namespace rigidity::detail {

/// Where a value sits in the scene tree: map keys and list indices ("bodies", "0", "velocity").
using Path = std::vector<std::string>;

/// "bodies.0.velocity"
[[nodiscard]] std::string dotted(const Path& path);
/// The components of a dotted path (keys are plain names and list indices: no dots).
[[nodiscard]] Path split_dotted(std::string_view dotted);

/// Where the values of a scene came from: the file, and the `--set` overrides that
/// replaced parts of it. `--set` arguments are the lines of a virtual file "<--set>":
/// the n-th argument is line n, and columns count characters within it.
class Sources {
 public:
  explicit Sources(std::string file) : file_(std::move(file)) {}

  [[nodiscard]] const std::string& file() const { return file_; }

  /// The location of the value (or, with at_key, of the key) at `path` whose YAML mark is `mark`.
  [[nodiscard]] SourceLocation locate(const Path& path, const YAML::Mark& mark, bool at_key = false) const;
  /// The same for a dotted path (split only where `--set` overrides are to be matched).
  [[nodiscard]] SourceLocation locate(const std::string& dotted_path, const YAML::Mark& mark,
                                      bool at_key = false) const;

  /// \throws InputError at `path`, keyed by its dotted form.
  [[noreturn]] void fail(const Path& path, const YAML::Mark& mark, const std::string& message,
                         bool at_key = false) const;
  [[noreturn]] void fail(const std::string& dotted_path, const YAML::Mark& mark, const std::string& message,
                         bool at_key = false) const;

  /// Parses "key.path=value" and applies it to `tree`; later overrides win. \throws InputError
  void apply_override(SceneTree& tree, const std::string& assignment);

 private:
  struct Override {
    Path path;
    std::vector<int> columns;  ///< 1-based column of each path component
    int value_column = 1;      ///< 1-based column of the first character of the value
    int line = 1;              ///< ordinal of the `--set` argument
    std::size_t existed = 0;   ///< how many leading path components the file had (the rest were created)
  };
  std::string file_;
  std::vector<Override> overrides_;
};

/// Parses the text of a scene file into a tree whose root is a map, in one pass,
/// refusing (InputError naming `source`, a line and a column) what is not a scene: bytes
/// that are not UTF-8 text, YAML syntax errors, more than one document, an empty document,
/// a top level that is not a map, nesting deeper than schema::kMaxDepth, more than
/// schema::kMaxNodes values.
[[nodiscard]] SceneTree parse_scene_text(std::string_view text, const std::string& source);

}  // namespace rigidity::detail
