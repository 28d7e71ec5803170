#include "scene_checker.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "rigidity/spelling.hpp"
#include "scene_text.hpp"

namespace rigidity::detail {

using schema::Condition;
using schema::Key;
using schema::Kind;
using schema::OneOf;

// ---- Checked ------------------------------------------------------------------------------

std::string Checked::path() const {
  return parent_path == nullptr || parent_path->empty() ? name : *parent_path + "." + name;
}

std::shared_ptr<const std::string> Checked::path_of_entries() const {
  if (!entries.empty()) return entries.front().parent_path;
  return std::make_shared<const std::string>(path());
}

const Checked* Checked::find(std::string_view key) const {
  for (const Checked& e : entries)
    if (e.name == key) return &e;
  return nullptr;
}

const Checked& Checked::operator[](std::string_view key) const {
  if (const Checked* e = find(key)) return *e;
  throw std::logic_error("scene loader: '" + path() + "' has no field '" + std::string(key) + "'");
}

Checked& Checked::operator[](std::string_view key) {
  return const_cast<Checked&>(static_cast<const Checked&>(*this)[key]);
}

void Checked::put(Checked field) {
  for (Checked& e : entries)
    if (e.name == field.name) {
      e = std::move(field);
      return;
    }
  entries.push_back(std::move(field));
}

// ---- helpers --------------------------------------------------------------------------------

namespace {

std::string child_path(const std::string& path, const std::string& name) {
  return path.empty() ? name : path + "." + name;
}

bool is_scalar_kind(Kind k) { return k != Kind::list && k != Kind::tuple && k != Kind::map && k != Kind::dictionary; }

/// Plain scalars and explicit !!int / !!float are numbers; quoted text is a string.
bool is_plain(const TreeValue& node) { return node.is_plain(); }

std::string describe_value(const TreeValue& node) {
  if (!node.defined() || node.is_null()) return "nothing";
  if (node.is_list()) return "a list";
  if (node.is_map()) return "a map";
  return quoted(std::string(node.text()));
}

bool is_identifier(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

bool holds(const Condition& condition, const Checked& siblings) {
  const Checked* sibling = siblings.find(condition.sibling);
  if (condition.values.empty()) return sibling != nullptr && sibling->given;
  return sibling != nullptr &&
         std::find(condition.values.begin(), condition.values.end(), sibling->word) != condition.values.end();
}

std::string condition_text(const Condition& condition, const Checked& siblings) {
  if (condition.values.empty()) return "only applies together with '" + condition.sibling + "'";
  std::string values;
  for (std::size_t i = 0; i < condition.values.size(); ++i)
    values += (i == 0 ? "" : i + 1 == condition.values.size() ? " or " : ", ") + condition.values[i];
  const Checked* sibling = siblings.find(condition.sibling);
  return "only applies when " + condition.sibling + " is " + values +
         (sibling != nullptr ? ", not " + quoted(sibling->word) : "");
}

const OneOf* group_of(const Key& map, const std::string& name) {
  for (const OneOf& g : map.one_of)
    if (std::find(g.keys.begin(), g.keys.end(), name) != g.keys.end()) return &g;
  return nullptr;
}

/// The declared name a misspelt one was meant to be: the closest by edit distance, or
/// else one sharing a long stem ("quantity" for "quantities", "bonding" for "bonded").
std::string suggestion(const std::string& name, const std::vector<std::string>& names) {
  if (std::string near = closest_match(name, names); !near.empty()) return near;
  std::string best;
  std::size_t best_stem = 3;
  for (const std::string& n : names) {
    std::size_t stem = 0;
    while (stem < n.size() && stem < name.size() && n[stem] == name[stem]) ++stem;
    if (stem > best_stem && 2 * stem >= std::min(n.size(), name.size())) {
      best = n;
      best_stem = stem;
    }
  }
  return best;
}

/// The value to write for a natural-unit value so that reading it back gives exactly
/// that value: from_natural, nudged by an ulp or two where the conversion rounds.
double written_exactly(double natural, Dimension dimension, UnitSystem units) {
  double written = from_natural(natural, dimension, units);
  for (int attempt = 0; attempt < 4 && to_natural(written, dimension, units) != natural; ++attempt) {
    const double back = to_natural(written, dimension, units);
    written = std::nextafter(written, back < natural ? HUGE_VAL : -HUGE_VAL);
  }
  return written;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::vector<std::string> q;
  for (const std::string& n : names) q.push_back("'" + n + "'");
  return join(q);
}

}  // namespace

// ---- Checker ------------------------------------------------------------------------------

void Checker::fail(const Checked& at, const std::string& message, bool at_key) const {
  sources_.fail(at.path(), at_key ? at.key_mark : at.mark, message, at_key);
}

void Checker::wrong_type(const TreeValue& node, const Checked& at, const std::string& expected) const {
  fail(at, "must be " + expected + ", got " + describe_value(node));
}

Checked Checker::check(const TreeValue& node, const Key& key, std::shared_ptr<const std::string> parent_path,
                       const std::string& name, const YAML::Mark& key_mark) {
  Checked out;
  out.name = name;
  out.parent_path = std::move(parent_path);
  out.kind = key.kind;
  out.dimension = key.dimension;
  // An empty value's mark points past it; its key's mark is where the reader looks.
  out.mark = node.is_null() && key_mark.line >= 0 ? key_mark : node.mark();
  out.key_mark = key_mark.line >= 0 ? key_mark : out.mark;
  if (++visited_ > schema::kMaxNodes)
    fail(out, "too many values (with aliases expanded): a scene holds at most " + std::to_string(schema::kMaxNodes));

  switch (key.kind) {
    case Kind::list:
    case Kind::tuple: return check_list(node, key, std::move(out));
    case Kind::map: return check_map(node, key, std::move(out));
    case Kind::dictionary: return check_dictionary(node, key, std::move(out));
    case Kind::number:
      if (key.number_or_map && node.is_map()) {  // a declared formula parameter: {value, unit, ...}
        out.kind = Kind::map;
        return check_map(node, Key::map(key.name, key.fields, key.doc), std::move(out));
      }
      return check_number(node, key, std::move(out));
    case Kind::integer: return check_number(node, key, std::move(out));
    case Kind::text:
    case Kind::choice:
    case Kind::boolean: return check_scalar(node, key, std::move(out));
  }
  return out;
}

Checked Checker::check_scalar(const TreeValue& node, const Key& key, Checked out) const {
  const std::string expected = key.kind == Kind::boolean  ? "true or false"
                               : key.kind == Kind::choice ? "one of: " + join(key.words)
                                                          : "a string";
  if (!node.is_scalar()) wrong_type(node, out, expected);
  const std::string text(node.text());
  switch (key.kind) {
    case Kind::boolean: {
      if (!is_plain(node)) fail(out, "must be true or false, got the quoted string " + quoted(text));
      const int value = parse_boolean(text);
      if (value < 0) wrong_type(node, out, expected);
      out.flag = value == 1;
      return out;
    }
    case Kind::choice: {
      if (std::find(key.words.begin(), key.words.end(), text) == key.words.end()) {
        const std::string near = closest_match(text, key.words);
        fail(out, "must be one of: " + join(key.words) + "; got " + quoted(text) +
                      (near.empty() ? "" : " (did you mean '" + near + "'?)"));
      }
      out.word = text;
      return out;
    }
    default: {
      if (text.empty()) fail(out, "must not be empty");
      if (key.identifier && !is_identifier(text))
        fail(out, "must be a name of letters, digits, '_' and '-', got " + quoted(text));
      out.word = text;
      return out;
    }
  }
}

Checked Checker::check_number(const TreeValue& node, const Key& key, Checked out) const {
  const std::string expected = std::string(key.kind == Kind::integer ? "a whole number" : "a number") +
                               (key.words.empty() ? "" : " or one of: " + join(key.words));
  if (!node.is_scalar()) wrong_type(node, out, expected);
  const std::string text(node.text());
  if (std::find(key.words.begin(), key.words.end(), text) != key.words.end()) {
    out.word = text;
    return out;
  }
  if (!is_plain(node)) fail(out, "must be " + expected + ", got the quoted string " + quoted(text));
  const NumberLiteral literal = parse_number(text);
  if (literal.syntax == NumberSyntax::non_finite) fail(out, "must be a finite number, got " + text);
  if (literal.syntax == NumberSyntax::invalid) {
    const std::string near = key.words.empty() ? "" : closest_match(text, key.words);
    fail(out,
         "must be " + expected + ", got " + quoted(text) + (near.empty() ? "" : " (did you mean '" + near + "'?)"));
  }
  const double value = literal.value;
  if (key.kind == Kind::integer && std::trunc(value) != value) fail(out, "must be a whole number, got " + text);
  out.as_written = value;
  out.number = to_natural(value, key.dimension, units_);
  if (!std::isfinite(out.number)) fail(out, "is too large (" + text + ")");

  if (!key.allowed.empty() && std::find(key.allowed.begin(), key.allowed.end(), value) == key.allowed.end()) {
    std::vector<std::string> values;
    for (double v : key.allowed) values.push_back(format_number(v));
    fail(out, "must be one of " + join(values) + ", got " + text);
  }
  const bool too_low =
      key.lower && (key.lower->inclusive ? out.number < key.lower->value : out.number <= key.lower->value);
  const bool too_high =
      key.upper && (key.upper->inclusive ? out.number > key.upper->value : out.number >= key.upper->value);
  if (too_low || too_high)
    fail(out, "must be " + std::string(key.lower && key.upper ? "in " : "") + key.range_text(units_) +
                  (key.note.empty() ? "" : " (" + key.note + ")") + ", got " + text);
  return out;
}

Checked Checker::check_list(const TreeValue& node, const Key& key, Checked out) {
  const bool tuple = key.kind == Kind::tuple;
  if (!node.is_list()) wrong_type(node, out, tuple ? "a list " + key.doc : std::string("a list"));
  const std::size_t size = node.size();
  if (tuple && size != key.fields.size())
    fail(out, "must be a list of " + std::to_string(key.fields.size()) + " numbers " + key.doc + ", got " +
                  std::to_string(size));
  if (!tuple && size > key.max_items)
    fail(out, "has " + std::to_string(size) + " entries; at most " + std::to_string(key.max_items) + " are allowed");
  if (!tuple && size < key.min_items)
    fail(out, "must have at least " + std::to_string(key.min_items) + (key.min_items == 1 ? " entry" : " entries"));

  std::set<std::string> seen;
  out.entries.reserve(size);
  const auto self = std::make_shared<const std::string>(out.path());
  for (std::size_t index = 0; index < size; ++index) {
    const TreeValue item = node.item(index);
    const Key& entry_key = tuple ? key.fields[index] : key.fields.front();
    Checked entry = check(item, entry_key, self, std::to_string(index), item.mark());
    if (key.unique && !entry.word.empty() && !seen.insert(entry.word).second)
      fail(entry, quoted(entry.word) + " is listed twice");
    out.entries.push_back(std::move(entry));
  }
  return out;
}

std::vector<Checker::Entry> Checker::entries_of(const TreeValue& map, const std::string& path) const {
  std::vector<Entry> entries;
  std::map<std::string, int> first_line;
  for (std::size_t e = 0; e < map.size(); ++e) {
    const TreeValue k = map.key(e);
    if (!k.is_scalar() || k.text().empty())
      sources_.fail(child_path(path, "?"), k.mark(), "a key must be a plain name, got " + describe_value(k), true);
    std::string name(k.text());
    if (const auto [first, inserted] = first_line.emplace(name, k.mark().line + 1); !inserted)
      sources_.fail(child_path(path, name), k.mark(),
                    "duplicate key '" + name + "' (first given at line " + std::to_string(first->second) + ")", true);
    entries.push_back(Entry{std::move(name), k, map.value(e)});
  }
  return entries;
}

Checked Checker::check_map(const TreeValue& node, const Key& key, Checked out) {
  if (!node.is_map()) wrong_type(node, out, "a map");
  const auto self = std::make_shared<const std::string>(out.path());
  const std::vector<Entry> entries = entries_of(node, *self);
  auto given = [&](const std::string& name) -> const Entry* {
    for (const Entry& e : entries)
      if (e.name == name) return &e;
    return nullptr;
  };

  // The keys that apply: the declared ones, and those the extension's selector chooses.
  std::vector<const Key*> keys;
  for (const Key& k : key.fields) keys.push_back(&k);
  std::vector<Key> chosen;
  if (key.extension) {
    const Key* selector = key.field(key.extension->selector);
    const Entry* e = given(selector->name);
    if (e == nullptr)
      sources_.fail(child_path(*self, selector->name), out.mark,
                    "missing required key '" + selector->name + "' (" + selector->doc + ")");
    const Checked selected = check(e->value, *selector, self, e->name, e->key.mark());
    chosen = key.extension->fields(selected.word);
    for (const Key& k : chosen) keys.push_back(&k);
  }

  // Every key the file has must be declared.
  for (const Entry& e : entries) {
    const bool declared = std::any_of(keys.begin(), keys.end(), [&](const Key* k) { return k->name == e.name; });
    if (declared) continue;
    std::vector<std::string> names;
    for (const Key* k : keys) names.push_back(k->name);
    const std::string near = suggestion(e.name, names);
    sources_.fail(child_path(*self, e.name), e.key.mark(),
                  "unknown key '" + e.name + "'" +
                      (near.empty() ? "; expected one of: " + join(names) : " (did you mean '" + near + "'?)"),
                  true);
  }

  // Every declared key, in declaration order (a condition refers to an earlier key).
  for (const Key* declared : keys) {
    const Key& k = *declared;
    const OneOf* group = group_of(key, k.name);
    const std::string path = child_path(*self, k.name);
    if (const Entry* e = given(k.name)) {
      if (k.only_if && !holds(*k.only_if, out))
        sources_.fail(path, e->key.mark(), "'" + k.name + "' " + condition_text(*k.only_if, out), true);
      if (group != nullptr)
        for (const std::string& other : group->keys)
          if (other != k.name && out.has(other))
            sources_.fail(
                path, e->key.mark(),
                "give only one of " + quoted_list(group->keys) + ", not both '" + other + "' and '" + k.name + "'",
                true);
      out.entries.push_back(check(e->value, k, self, k.name, e->key.mark()));
      continue;
    }
    if (k.only_if && !holds(*k.only_if, out)) continue;
    if (k.required) sources_.fail(path, out.mark, "missing required key '" + k.name + "' (" + k.doc + ")");
    if (group != nullptr) {
      const bool any_given = std::any_of(group->keys.begin(), group->keys.end(),
                                         [&](const std::string& n) { return given(n) != nullptr; });
      if (any_given) continue;
      if (group->required && (!group->when || holds(*group->when, out)) && group->keys.front() == k.name)
        sources_.fail(path, out.mark, "missing required key: give one of " + quoted_list(group->keys));
    }
    if (!k.derived_default.empty()) {
      // Kept in declaration order; the loader computes the value.
      Checked awaiting = derived_number(out, k.name, 0.0, k.dimension);
      awaiting.kind = k.kind;
      awaiting.awaiting = true;
      out.entries.push_back(std::move(awaiting));
    } else if (!std::holds_alternative<std::monostate>(k.fallback) || !is_scalar_kind(k.kind)) {
      out.entries.push_back(absent(k, out, self));
    }
  }
  return out;
}

Checked Checker::check_dictionary(const TreeValue& node, const Key& key, Checked out) {
  if (!node.is_map()) wrong_type(node, out, "a map of names");
  const auto self = std::make_shared<const std::string>(out.path());
  const std::vector<Entry> entries = entries_of(node, *self);
  if (entries.size() > key.max_items)
    fail(out, "has " + std::to_string(entries.size()) + " entries; at most " + std::to_string(key.max_items) +
                  " are allowed");
  if (entries.size() < key.min_items) fail(out, "must have at least " + std::to_string(key.min_items) + " entry");
  for (const Entry& e : entries) {
    if (!is_identifier(e.name))
      sources_.fail(child_path(*self, e.name), e.key.mark(),
                    "a name must be letters, digits, '_' and '-', got " + quoted(e.name), true);
    out.entries.push_back(check(e.value, key.fields.front(), self, e.name, e.key.mark()));
  }
  return out;
}

Checked Checker::absent(const Key& key, const Checked& parent, std::shared_ptr<const std::string> parent_path) {
  Checked out;
  out.name = key.name;
  out.parent_path = std::move(parent_path);
  out.kind = key.kind;
  out.dimension = key.dimension;
  out.mark = parent.mark;
  out.key_mark = parent.mark;
  out.given = false;
  if (key.kind == Kind::map) {
    // An absent map is an empty one: its own defaults apply.
    out = check_map(SceneTree::empty_map(), key, std::move(out));
    out.mark = parent.mark;
    return out;
  }
  if (const auto* number = std::get_if<double>(&key.fallback)) {
    out.number = *number;
    out.as_written = written_exactly(*number, key.dimension, units_);
  } else if (const auto* flag = std::get_if<bool>(&key.fallback)) {
    out.flag = *flag;
  } else if (const auto* word = std::get_if<std::string>(&key.fallback)) {
    out.word = *word;
  }
  return out;  // lists and dictionaries: empty
}

Checked Checker::derived_number(const Checked& parent, const std::string& name, double natural,
                                Dimension dimension) const {
  Checked out;
  out.name = name;
  out.parent_path = parent.path_of_entries();
  out.kind = Kind::number;
  out.dimension = dimension;
  out.mark = out.key_mark = parent.mark;
  out.given = false;
  out.number = natural;
  out.as_written = written_exactly(natural, dimension, units_);
  return out;
}

Checked Checker::derived_text(const Checked& parent, const std::string& name, std::string text) const {
  Checked out;
  out.name = name;
  out.parent_path = parent.path_of_entries();
  out.kind = Kind::text;
  out.mark = out.key_mark = parent.mark;
  out.given = false;
  out.word = std::move(text);
  return out;
}

// ---- resolved_scene.yaml --------------------------------------------------------------------

namespace {

std::string scalar_text(const Checked& c) {
  switch (c.kind) {
    case Kind::number: return c.is_word() ? c.word : format_number(c.as_written);
    case Kind::integer: return std::to_string(static_cast<long long>(c.as_written));  // |n| <= 1e12 by the schema
    case Kind::boolean: return c.flag ? "true" : "false";
    default: return c.word;
  }
}

bool is_keyed(const Checked& c) { return c.kind == Kind::map || c.kind == Kind::dictionary; }

/// Width of c written in flow style (large if it nests collections in collections).
std::size_t flow_width(const Checked& c, int depth = 0) {
  constexpr std::size_t kTooWide = 1000;
  if (is_scalar_kind(c.kind)) return scalar_text(c).size() + 2;
  if (depth >= 2) return kTooWide;
  std::size_t width = 2;
  for (const Checked& e : c.entries) width += (is_keyed(c) ? e.name.size() + 2 : 0) + flow_width(e, depth + 1);
  return std::min(width, kTooWide);
}

/// Block style for the sections of the scene and for anything wide; flow style for
/// short lists and maps ([p, v], {model: rigid, rest_density: 1}); the entries of one
/// list all in the same style.
void emit(YAML::Emitter& out, const Checked& c, int depth, bool may_flow = true) {
  constexpr std::size_t kFlowWidth = 72;
  if (c.awaiting) throw std::logic_error("scene loader: no value derived for '" + c.path() + "'");
  if (is_scalar_kind(c.kind)) {
    const std::string text = scalar_text(c);
    if (c.kind == Kind::text && needs_quotes(text)) out << YAML::DoubleQuoted;
    out << text;
    return;
  }
  const auto narrow = [&](const Checked& e) { return flow_width(e) <= kFlowWidth; };
  const bool flat =
      std::all_of(c.entries.begin(), c.entries.end(), [](const Checked& e) { return is_scalar_kind(e.kind); });
  if (may_flow && ((!is_keyed(c) && flat) || (narrow(c) && (depth > 1 || flat)))) out << YAML::Flow;
  const bool entries_may_flow = is_keyed(c) || std::all_of(c.entries.begin(), c.entries.end(), narrow);
  out << (is_keyed(c) ? YAML::BeginMap : YAML::BeginSeq);
  for (const Checked& e : c.entries) {
    // A text whose default is empty (a formula's unused `pressure` or `strain_energy`) is
    // left out: written as "" it would not load again.
    if (!e.given && e.kind == Kind::text && e.word.empty()) continue;
    if (is_keyed(c)) out << YAML::Key << e.name << YAML::Value;
    emit(out, e, depth + 1, entries_may_flow);
  }
  out << (is_keyed(c) ? YAML::EndMap : YAML::EndSeq);
}

}  // namespace

std::string emit_resolved(const Checked& scene, UnitSystem units) {
  YAML::Emitter out;
  out.SetIndent(2);
  out << YAML::BeginMap;
  for (const Checked& section : scene.entries) {
    out << YAML::Key << section.name << YAML::Value;
    emit(out, section, 1);
  }
  out << YAML::EndMap;
  return std::string("# The scene as run: every default filled in, in ") +
         (units == UnitSystem::si ? "SI units" : "natural units (c = 1)") + ".\n" + out.c_str() + "\n";
}

}  // namespace rigidity::detail
