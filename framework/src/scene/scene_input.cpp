#include "scene_input.hpp"

#include <yaml-cpp/exceptions.h>

#include <algorithm>
#include <charconv>
#include <sstream>

#include "rigidity/scene_schema.hpp"
#include "scene_text.hpp"

namespace rigidity::detail {

std::string dotted(const Path& path) { return join(path, "."); }

Path split_dotted(std::string_view dotted) {
  Path path;
  if (dotted.empty()) return path;
  for (std::size_t start = 0;;) {
    const std::size_t dot = dotted.find('.', start);
    path.emplace_back(dotted.substr(start, dot - start));
    if (dot == std::string_view::npos) return path;
    start = dot + 1;
  }
}

// ---- locations ----------------------------------------------------------------------

namespace {

bool has_prefix(const Path& path, const Path& prefix) {
  if (prefix.size() > path.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (path[i] != prefix[i]) return false;
  return true;
}

bool valid(const YAML::Mark& mark) { return mark.line >= 0 && mark.column >= 0; }

}  // namespace

SourceLocation Sources::locate(const Path& path, const YAML::Mark& mark, bool at_key) const {
  for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it) {
    // A map the override created for its path points at that component.
    if (has_prefix(it->path, path) && path.size() > it->existed && path.size() < it->path.size())
      return {"<--set>", it->line, it->columns[path.size() - 1]};
    if (!has_prefix(path, it->path)) continue;
    // A key named in the override's path points at that component; anything else, into the value.
    if (at_key && path.size() <= it->path.size()) return {"<--set>", it->line, it->columns[path.size() - 1]};
    return {"<--set>", it->line, it->value_column + (valid(mark) && mark.line == 0 ? mark.column : 0)};
  }
  if (!valid(mark)) return {file_, 1, 1};
  return {file_, mark.line + 1, mark.column + 1};
}

void Sources::fail(const Path& path, const YAML::Mark& mark, const std::string& message, bool at_key) const {
  throw InputError(locate(path, mark, at_key), dotted(path), message);
}

SourceLocation Sources::locate(const std::string& dotted_path, const YAML::Mark& mark, bool at_key) const {
  if (overrides_.empty()) return locate(Path{}, mark, at_key);  // the path only matters for overrides
  return locate(split_dotted(dotted_path), mark, at_key);
}

void Sources::fail(const std::string& dotted_path, const YAML::Mark& mark, const std::string& message,
                   bool at_key) const {
  throw InputError(locate(dotted_path, mark, at_key), dotted_path, message);
}

// ---- --set overrides ------------------------------------------------------------------

namespace {

/// The first control character (other than tab) in text, or npos.
std::size_t first_control_character(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && c != '\t') || c == 0x7f) return i;
  }
  return std::string_view::npos;
}

std::string kind_of(const TreeValue& node) {
  if (node.is_map()) return "a map";
  if (node.is_list()) return "a list";
  if (node.is_null()) return "empty";
  return "the value " + quoted(std::string(node.text()));
}

/// The entry of a map named `key` (the first, if the file repeats it), or npos.
std::size_t map_entry(const TreeValue& map, const std::string& key) {
  for (std::size_t e = 0; e < map.size(); ++e) {
    const TreeValue k = map.key(e);
    if (k.is_scalar() && k.text() == key) return e;
  }
  return std::string::npos;
}

}  // namespace

void Sources::apply_override(SceneTree& tree, const std::string& assignment) {
  Override o;
  o.line = static_cast<int>(overrides_.size()) + 1;
  auto fail_at = [&](int column, const std::string& key, const std::string& message) {
    throw InputError(SourceLocation{"<--set>", o.line, column}, key,
                     message + " (in --set " + quoted(assignment) + ")");
  };

  if (const std::size_t bad = first_control_character(assignment); bad != std::string::npos)
    fail_at(static_cast<int>(bad) + 1, "", "control character in the override");
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos) fail_at(1, "", "expected key.path=value");
  if (equals == 0) fail_at(1, "", "missing key path before '='");

  // The path: components separated by dots, each non-empty.
  const std::string path_text = assignment.substr(0, equals);
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path_text.find('.', start);
    const std::string component = path_text.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (component.empty())
      fail_at(static_cast<int>(start) + 1, path_text, "empty component in key path " + quoted(path_text));
    o.path.push_back(component);
    o.columns.push_back(static_cast<int>(start) + 1);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }

  // The value: a YAML scalar or flow collection.
  o.value_column = static_cast<int>(equals) + 2;
  const std::string value_text = assignment.substr(equals + 1);
  SceneTree parsed;
  try {
    parsed = SceneTree::parse(value_text, schema::kMaxNodes, schema::kMaxDepth);
  } catch (const YAML::Exception& e) {
    fail_at(o.value_column + (e.mark.column > 0 ? e.mark.column : 0), dotted(o.path), "malformed value: " + e.msg);
  } catch (const TreeLimit& e) {
    fail_at(o.value_column + (e.mark.column > 0 ? e.mark.column : 0), dotted(o.path), e.message);
  }
  if (parsed.root().is_null() && value_text.find_first_not_of(" \t") == std::string::npos)
    fail_at(o.value_column, dotted(o.path), "missing value after '='");
  const int value = tree.graft(parsed, parsed.root().index());

  // Walk to the parent of the last component, creating maps where the file has none.
  int node = tree.root().index();
  o.existed = o.path.size();
  for (std::size_t i = 0; i < o.path.size(); ++i) {
    const std::string& component = o.path[i];
    const Path here(o.path.begin(), o.path.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    const bool last = i + 1 == o.path.size();
    const TreeValue at = tree.at(node);
    if (at.is_list()) {
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(component.data(), component.data() + component.size(), index);
      if (ec != std::errc() || end != component.data() + component.size() || index >= at.size()) {
        const Path parent(here.begin(), here.end() - 1);
        const std::string indices =
            at.size() == 0 ? "it is empty" : "expected an index from 0 to " + std::to_string(at.size() - 1);
        fail_at(o.columns[i], dotted(here),
                "'" + dotted(parent) + "' is a list of " + std::to_string(at.size()) + " entries; " + indices +
                    ", got " + quoted(component));
      }
      if (last)
        tree.set_item(node, index, value);
      else
        node = at.item(index).index();
    } else if (at.is_map()) {
      const std::size_t entry = map_entry(at, component);
      if (last) {
        if (entry != std::string::npos)
          tree.set_value(node, entry, value);
        else
          tree.add_entry(node, component, value);
      } else if (entry == std::string::npos) {
        o.existed = std::min(o.existed, i);
        const int created = tree.add_map();
        tree.add_entry(node, component, created);
        node = created;
      } else {
        const int child = at.value(entry).index();
        if (tree.at(child).is_null()) tree.null_to_map(child);
        node = child;
      }
    } else {
      const Path parent(here.begin(), here.end() - 1);
      fail_at(o.columns[i], dotted(here), "'" + dotted(parent) + "' is " + kind_of(at) + ", not a map or list");
    }
  }
  overrides_.push_back(std::move(o));
}

// ---- parsing ----------------------------------------------------------------------------

namespace {

/// Line and column (1-based) of byte `offset` in text.
SourceLocation position_of(std::string_view text, std::size_t offset, const std::string& source) {
  int line = 1;
  int column = 1;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++column;  // count characters, not UTF-8 continuation bytes
    }
  }
  return {source, line, column};
}

/// Byte offset of the first byte that makes text not UTF-8 YAML text (invalid UTF-8,
/// or a control character other than tab, newline, carriage return), or npos.
std::size_t first_non_text_byte(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f) return i;
      ++i;
      continue;
    }
    std::size_t length = 0;
    unsigned min = 0;
    unsigned code = 0;
    if ((c & 0xE0) == 0xC0) {
      length = 2;
      min = 0x80;
      code = c & 0x1Fu;
    } else if ((c & 0xF0) == 0xE0) {
      length = 3;
      min = 0x800;
      code = c & 0x0Fu;
    } else if ((c & 0xF8) == 0xF0) {
      length = 4;
      min = 0x10000;
      code = c & 0x07u;
    } else
      return i;
    if (i + length > text.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const auto d = static_cast<unsigned char>(text[i + k]);
      if ((d & 0xC0) != 0x80) return i;
      code = (code << 6) | (d & 0x3Fu);
    }
    if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return i;
    i += length;
  }
  return std::string_view::npos;
}

constexpr const char* kEmptyScene = "the scene is empty; expected a map with at least name, materials, bodies, time";

SourceLocation at_mark(const YAML::Mark& mark, const std::string& source) {
  if (mark.line < 0) return {source, 1, 1};
  return {source, mark.line + 1, mark.column + 1};
}

}  // namespace

SceneTree parse_scene_text(std::string_view text, const std::string& source) {
  if (text.size() > schema::kMaxInputBytes)
    throw InputError({source, 1, 1}, "",
                     "the file is " + std::to_string(text.size()) + " bytes; a scene file is at most " +
                         std::to_string(schema::kMaxInputBytes) + " bytes");
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte order mark
  if (const std::size_t bad = first_non_text_byte(text); bad != std::string_view::npos) {
    std::ostringstream byte;
    byte << "0x" << std::hex << static_cast<unsigned>(static_cast<unsigned char>(text[bad]));
    throw InputError(position_of(text, bad, source), "",
                     "not a text file: byte " + byte.str() + " is not UTF-8 text (a scene is a YAML text file)");
  }

  try {
    SceneTree tree = SceneTree::parse(text, schema::kMaxNodes, schema::kMaxDepth);
    const TreeValue root = tree.root();
    if (root.is_null()) {
      const YAML::Mark& mark = tree.document_mark();
      throw InputError(at_mark(mark, source), "", kEmptyScene);
    }
    if (!root.is_map())
      throw InputError(at_mark(root.mark(), source), "",
                       "the scene must be a map of keys (name, units, materials, bodies, ...), got " +
                           std::string(root.is_list() ? "a list" : "a single value"));
    return tree;
  } catch (const TreeLimit& e) {
    throw InputError(at_mark(e.mark, source), "", e.message);
  } catch (const YAML::Exception& e) {
    throw InputError(at_mark(e.mark, source), "", "YAML syntax error: " + e.msg);
  }
}

}  // namespace rigidity::detail
