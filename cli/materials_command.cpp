// rigidity materials [NAME] [--json]: the registry, read from each material's own
// declaration (doc, parameters, units, ranges).
#include <algorithm>
#include <ostream>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/json_writer.hpp"
#include "rigidity/registry.hpp"

namespace rigidity::cli {

namespace {

std::string_view type_name(ParameterType t) {
  return t == ParameterType::number ? "number" : t == ParameterType::text ? "text" : "map of numbers";
}

std::string registered_at(const MaterialInfo& info) { return info.file + ":" + std::to_string(info.line); }

/// "required", "default 1" or "default \"x\"" (or "optional" if no default is declared).
std::string default_text(const ParameterSpec& p) {
  if (p.required) return "required";
  std::string out = "default ";
  if (p.default_number) {
    append_shortest(out, *p.default_number);
  } else if (p.default_text) {
    append_json_string(out, *p.default_text);
  } else if (p.type == ParameterType::numbers) {
    out += "{}";  // none
  } else {
    return "optional";
  }
  return out;
}

/// `text` wrapped at word boundaries to lines of at most `width` characters (a longer
/// word keeps its own line), every line after the first indented by `indent`.
std::string wrap(std::string_view text, std::size_t indent, std::size_t width = 92) {
  std::string out;
  std::size_t column = indent;
  std::size_t start = 0;
  while (start < text.size()) {
    if (text[start] == '\n') {  // an explicit line break in the doc
      out += '\n';
      out.append(indent, ' ');
      column = indent;
      ++start;
      continue;
    }
    if (text[start] == ' ') {
      ++start;
      continue;
    }
    const std::size_t end = std::min(text.find_first_of(" \n", start), text.size());
    const std::string_view word = text.substr(start, end - start);
    if (column > indent && column + 1 + word.size() > width) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
    } else if (column > indent) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    start = end;
  }
  return out;
}

void print_text(std::ostream& out, const std::vector<const MaterialInfo*>& materials) {
  if (materials.empty()) {
    out << "no materials are registered\n";
    return;
  }
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const MaterialInfo& m = *materials[i];
    if (i > 0) out << "\n";
    out << m.name << "\n";
    if (!m.doc.empty()) out << "  " << wrap(m.doc, 2) << "\n";
    std::size_t width = 0;
    for (const ParameterSpec& p : m.parameters) width = std::max(width, p.name.size());
    out << "  parameters:" << (m.parameters.empty() ? " none" : "") << "\n";
    for (const ParameterSpec& p : m.parameters) {
      const std::size_t column = 4 + width + 2;
      std::string name = p.name;
      name.resize(width + 2, ' ');
      out << "    " << name << type_name(p.type) << ", " << default_text(p);
      if (const std::string range = p.range_text(); !range.empty()) out << ", range " << range;
      out << "\n";
      if (p.type == ParameterType::number) {
        out << std::string(column, ' ') << "units: ";
        if (p.dimension == Dimension::dimensionless) {
          out << "dimensionless\n";
        } else {
          out << unit_symbol(p.dimension, UnitSystem::natural) << " (natural), "
              << unit_symbol(p.dimension, UnitSystem::si) << " (SI)\n";
        }
      }
      if (!p.doc.empty()) out << std::string(column, ' ') << wrap(p.doc, column) << "\n";
    }
    out << "  registered at " << registered_at(m) << "\n";
  }
}

void print_json(std::ostream& out, const std::vector<const MaterialInfo*>& materials) {
  JsonWriter json("rigidity materials --json");
  json.begin_array();
  for (const MaterialInfo* m : materials) {
    json.begin_object();
    json.key("name").text(m->name);
    json.key("doc").text(m->doc);
    json.key("parameters").begin_array();
    for (const ParameterSpec& p : m->parameters) {
      json.begin_object();
      json.key("name").text(p.name);
      json.key("type").text(type_name(p.type));
      json.key("required").boolean(p.required);
      json.key("default");
      if (p.default_number) {
        json.number(*p.default_number);
      } else if (p.default_text) {
        json.text(*p.default_text);
      } else if (p.type == ParameterType::numbers) {
        json.begin_object();  // none: an empty map
        json.end_object();
      } else {
        json.null();
      }
      json.key("dimension").text(dimension_name(p.dimension));
      json.key("units_natural").text(unit_symbol(p.dimension, UnitSystem::natural));
      json.key("units_si").text(unit_symbol(p.dimension, UnitSystem::si));
      if (const std::string range = p.range_text(); range.empty()) {
        json.key("range").null();
      } else {
        json.key("range").text(range);
      }
      json.key("doc").text(p.doc);
      json.end_object();
    }
    json.end_array();
    json.key("registered_at").text(registered_at(*m));
    json.end_object();
  }
  json.end_array();
  out << json.take();
}

}  // namespace

int materials_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--json"}};
  const Arguments parsed = parse_arguments("materials", args, kOptions);
  if (parsed.help) {
    out << help("materials");
    return kExitOk;
  }
  if (parsed.positional.size() > 1) throw usage_error("materials", "materials takes at most one material name");

  const MaterialRegistry& registry = MaterialRegistry::instance();
  std::vector<const MaterialInfo*> selected;
  if (parsed.positional.empty()) {
    for (const std::string& name : registry.names()) selected.push_back(registry.find(name));
  } else {
    try {
      selected.push_back(&registry.at(parsed.positional[0]));
    } catch (const std::invalid_argument& e) {  // names the closest match and lists the registered ones
      throw CommandError(kExitInvalidInput, e.what());
    }
  }
  if (parsed.has("--json")) {
    print_json(out, selected);
  } else {
    print_text(out, selected);
  }
  return kExitOk;
}

}  // namespace rigidity::cli
