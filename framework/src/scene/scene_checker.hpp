#pragma once
// The schema walker: checks a scene tree (scene_tree.hpp) against a schema::Key and returns the checked
// values (natural units, defaults filled in), from which the loader builds the Scene
// and resolved_scene.yaml is written. Internal to the scene loader.

#include <yaml-cpp/mark.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/scene_schema.hpp"
#include "rigidity/units.hpp"
#include "scene_input.hpp"

namespace rigidity::detail {

/// A value that passed its key's rules.
struct Checked {
  std::string name;  ///< the key, or the list index
  /// The dotted path of the map or list holding it, shared by all its entries (a scene of 10⁵
  /// segments holds 10⁶ values: one string per value would be most of what loading holds).
  std::shared_ptr<const std::string> parent_path;
  schema::Kind kind = schema::Kind::map;
  Dimension dimension = Dimension::dimensionless;
  YAML::Mark mark;               ///< of the value; for a default, of the enclosing map
  YAML::Mark key_mark;           ///< of the key (map entries); else the value's
  bool given = true;             ///< false: a default (fixed or derived)
  bool awaiting = false;         ///< a default the loader derives, not yet put()
  double number = 0.0;           ///< number, integer: natural units
  double as_written = 0.0;       ///< number, integer: in the scene's units
  std::string word;              ///< text, choice, or the word given instead of a number (`at: left`)
  bool flag = false;             ///< boolean
  std::vector<Checked> entries;  ///< list, tuple: the items; map, dictionary: the fields

  /// "bodies.0.velocity"
  [[nodiscard]] std::string path() const;
  /// The parent_path of its entries.
  [[nodiscard]] std::shared_ptr<const std::string> path_of_entries() const;
  [[nodiscard]] const Checked* find(std::string_view key) const;
  [[nodiscard]] bool has(std::string_view key) const { return find(key) != nullptr; }
  /// The field `key`, which the schema guarantees. \throws std::logic_error if absent
  [[nodiscard]] const Checked& operator[](std::string_view key) const;
  [[nodiscard]] Checked& operator[](std::string_view key);
  [[nodiscard]] bool is_word() const { return !word.empty(); }
  /// Fills in a default the loader derives (replacing the field of that name in place).
  void put(Checked field);
};

class Checker {
 public:
  Checker(const Sources& sources, UnitSystem units) : sources_(sources), units_(units) {}

  /// Checks `node` (the value `name` of the map or list at `parent_path`, none for the root,
  /// whose key sits at `key_mark`) against `key`. \throws InputError
  [[nodiscard]] Checked check(const TreeValue& node, const schema::Key& key,
                              std::shared_ptr<const std::string> parent_path, const std::string& name,
                              const YAML::Mark& key_mark);

  /// A value derived by the loader, in natural units, as a default field of `parent`.
  [[nodiscard]] Checked derived_number(const Checked& parent, const std::string& name, double natural,
                                       Dimension dimension) const;
  [[nodiscard]] Checked derived_text(const Checked& parent, const std::string& name, std::string text) const;

  /// \throws InputError at the value `at` (or at its key).
  [[noreturn]] void fail(const Checked& at, const std::string& message, bool at_key = false) const;

 private:
  struct Entry {
    std::string name;
    TreeValue key;
    TreeValue value;
  };

  Checked check_scalar(const TreeValue& node, const schema::Key& key, Checked out) const;
  Checked check_number(const TreeValue& node, const schema::Key& key, Checked out) const;
  Checked check_list(const TreeValue& node, const schema::Key& key, Checked out);
  Checked check_map(const TreeValue& node, const schema::Key& key, Checked out);
  Checked check_dictionary(const TreeValue& node, const schema::Key& key, Checked out);
  /// The value of an absent key that is neither required nor derived: its default.
  Checked absent(const schema::Key& key, const Checked& parent, std::shared_ptr<const std::string> parent_path);

  [[nodiscard]] std::vector<Entry> entries_of(const TreeValue& map, const std::string& path) const;
  [[noreturn]] void wrong_type(const TreeValue& node, const Checked& at, const std::string& expected) const;

  const Sources& sources_;
  UnitSystem units_;
  std::size_t visited_ = 0;
};

/// resolved_scene.yaml: the checked scene, every default filled in, in the scene's units.
[[nodiscard]] std::string emit_resolved(const Checked& scene, UnitSystem units);

}  // namespace rigidity::detail
