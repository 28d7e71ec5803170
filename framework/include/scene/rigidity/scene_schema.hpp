#pragma once
/// The scene schema (docs/scenes.md) as data: every key a scene file may hold, declared once
/// with its type, default, dimension, range and doc. The loader walks each file
/// against this declaration (the keys the file has, so that no typo passes unseen,
/// and the keys the schema has, so that no required key is missed); documentation
/// and error messages read the same declaration.
///
///   Key::number("velocity", "uniform initial velocity")
///       .in(Dimension::velocity).above(-1.0).below(1.0).note("|v| < c").defaults_to(0.0)
///
/// Bounds and defaults are in natural units (c = 1); an SI scene is converted before
/// its values are compared with them.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rigidity/parameters.hpp"
#include "rigidity/units.hpp"

namespace rigidity::schema {

/// Limits that keep any input, however large or hostile, from exhausting the machine.
inline constexpr std::size_t kMaxInputBytes = std::size_t{16} << 20;  ///< a scene file is at most 16 MiB
inline constexpr std::size_t kMaxNodes = 1000000;                     ///< YAML values in a scene (aliases expanded)
inline constexpr int kMaxDepth = 64;                                  ///< nesting of YAML maps and lists
inline constexpr std::size_t kMaxListItems = 100000;                  ///< entries in any one list

enum class Kind {
  text,        ///< a string
  choice,      ///< one of a fixed set of words
  number,      ///< a finite real (optionally, one of a few words instead: `at: left`)
  integer,     ///< a whole number
  boolean,     ///< true | false
  list,        ///< a YAML sequence of `fields[0]`
  tuple,       ///< a YAML sequence with one entry per `fields` (e.g. [t, v])
  map,         ///< a YAML map with the keys `fields` (and no others)
  dictionary,  ///< a YAML map from names the user chooses to `fields[0]` (e.g. materials)
};

/// A key that applies only if the sibling `sibling` is given (when `values` is empty)
/// or is a choice whose value is one of `values`. The sibling is declared earlier.
struct Condition {
  std::string sibling;
  std::vector<std::string> values;
};

/// Keys of a map that exclude each other: at most one may be given, exactly one if
/// `required` (and `when` holds). A default of a member applies only if none is given.
struct OneOf {
  std::vector<std::string> keys;
  bool required = false;
  std::optional<Condition> when;
};

struct Key;

/// Keys a map also takes, chosen by the value of one of its keys: a material entry
/// takes the parameters its `model` declares.
struct Extension {
  std::string selector;
  std::function<std::vector<Key>(const std::string& selected)> fields;
};

/// A default: none, a number (natural units), a boolean or a word.
using Fallback = std::variant<std::monostate, double, bool, std::string>;

struct Key {
  std::string name;  ///< "" for list entries
  Kind kind = Kind::text;
  std::string doc;
  Dimension dimension = Dimension::dimensionless;
  bool required = false;
  Fallback fallback;               ///< the default, if the key has a fixed one
  std::string derived_default;     ///< a default the loader computes, described ("the adjacent body's end")
  std::optional<Bound> lower;      ///< natural units
  std::optional<Bound> upper;      ///< natural units
  std::string note;                ///< why the range is what it is ("|v| < c"), quoted in messages
  std::vector<double> allowed;     ///< number/integer: the only values accepted (e.g. -1, +1)
  std::vector<std::string> words;  ///< choice: the values; number: words accepted instead of a number
  bool identifier = false;         ///< text: letters, digits, '_' and '-' only (names used in output files)
  std::size_t min_items = 0;       ///< list, dictionary
  std::size_t max_items = kMaxListItems;
  bool unique = false;  ///< list of words: no entry twice
  std::optional<Condition> only_if;
  bool number_or_map = false;  ///< number: a map of `fields` is accepted instead (a declared formula parameter)
  std::vector<Key> fields;     ///< map (and number_or_map): its keys; list, dictionary: [entry]; tuple: the positions
  std::vector<OneOf> one_of;   ///< map
  std::optional<Extension> extension;  ///< map

  // ---- declarations, read as sentences ------------------------------------------
  static Key text(std::string name, std::string doc);
  static Key choice(std::string name, std::vector<std::string> words, std::string doc);
  static Key number(std::string name, std::string doc);
  static Key integer(std::string name, std::string doc);
  static Key boolean(std::string name, std::string doc);
  static Key list(std::string name, Key entry, std::string doc);
  static Key tuple(std::string name, std::vector<Key> positions, std::string doc);
  static Key map(std::string name, std::vector<Key> keys, std::string doc);
  static Key dictionary(std::string name, Key entry, std::string doc);
  /// The declaration of a material parameter (registry.hpp) as a scene key.
  static Key parameter(const ParameterSpec& spec);

  Key& require();
  Key& defaults_to(double v);
  Key& defaults_to(bool v);
  Key& defaults_to(std::string word);
  Key& defaults_to_derived(std::string description);
  Key& in(Dimension d);
  Key& above(double v);     ///< > v
  Key& at_least(double v);  ///< >= v
  Key& below(double v);     ///< < v
  Key& at_most(double v);   ///< <= v
  Key& because(std::string why);
  Key& one_of_values(std::vector<double> values);
  Key& or_words(std::vector<std::string> alternatives);
  Key& as_identifier();
  Key& items(std::size_t min, std::size_t max = kMaxListItems);
  Key& distinct();
  Key& only_with(std::string sibling);
  Key& only_when(std::string sibling, std::vector<std::string> values);
  Key& exclusive(std::vector<std::string> keys, bool required = false, std::optional<Condition> when = {});
  Key& extended_by(std::string selector, std::function<std::vector<Key>(const std::string&)> fields);
  /// A number key that also takes a map of `keys` in its place: `k: 2.0` or `k: {value: 2.0, ...}`.
  Key& or_map_of(std::vector<Key> keys);

  /// The declared key `name` of a map, or nullptr.
  [[nodiscard]] const Key* field(const std::string& key_name) const;
  /// The range in `units`, e.g. "(0, 1]" or "> 0" or "(-299792458, 299792458) m/s"; "" if unbounded.
  [[nodiscard]] std::string range_text(UnitSystem units) const;
};

/// The whole scene schema. Material models are read from the registry when called,
/// so that plugins loaded before are included.
[[nodiscard]] Key scene_schema();

/// One line per key, indented by nesting: name, type, default, units, range, doc.
/// What `rigidity schema` prints.
[[nodiscard]] std::string describe(const Key& key, UnitSystem units = UnitSystem::natural);

/// Every key of a schema as a flat row, by its path (`bodies.*.velocity`; list entries are
/// `*`, a dictionary's names `<name>`), the keys each material model adds included
/// (`materials.<name>.wave_speed`, with `model` saying which). What `rigidity schema --json`
/// lists.
struct KeyRow {
  std::string path;
  std::string type;
  bool required = false;
  std::string default_value;  ///< "" if none
  std::string unit;           ///< "" if dimensionless
  std::string range;          ///< "" if unbounded
  std::string model;          ///< the material model that adds the key, else ""
  std::string doc;
};
[[nodiscard]] std::vector<KeyRow> flatten(const Key& key, UnitSystem units = UnitSystem::natural);

}  // namespace rigidity::schema
