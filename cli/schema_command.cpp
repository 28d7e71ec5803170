// rigidity schema [--json] [--si]: every scene key from the one declaration the loader
// checks scenes against (scene_schema.hpp), with the keys each registered material adds.
#include <ostream>
#include <string>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/json_writer.hpp"
#include "rigidity/plugins.hpp"
#include "rigidity/scene_schema.hpp"

namespace rigidity::cli {

int schema_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--json"}, {"--si"}};
  const Arguments parsed = parse_arguments("schema", args, kOptions);
  if (parsed.help) {
    out << help("schema");
    return kExitOk;
  }
  if (!parsed.positional.empty()) throw usage_error("schema", "schema takes no file");
  load_environment_plugins();  // their materials' keys too
  const UnitSystem units = parsed.has("--si") ? UnitSystem::si : UnitSystem::natural;
  const schema::Key scene = schema::scene_schema();
  if (!parsed.has("--json")) {
    out << "# every key of a scene file, in " << (units == UnitSystem::si ? "SI units" : "natural units (c = 1)")
        << ": type, required or default, [unit], range  # doc\n";
    for (const schema::Key& key : scene.fields) out << schema::describe(key, units);
    return kExitOk;
  }
  JsonWriter json("schema");
  json.begin_object();
  json.key("units").text(units == UnitSystem::si ? "si" : "natural");
  json.key("keys").begin_array();
  for (const schema::KeyRow& row : schema::flatten(scene, units)) {
    json.begin_object(JsonLayout::line);
    json.key("path").text(row.path);
    json.key("type").text(row.type);
    json.key("required").boolean(row.required);
    if (!row.default_value.empty()) json.key("default").text(row.default_value);
    if (!row.unit.empty()) json.key("unit").text(row.unit);
    if (!row.range.empty()) json.key("range").text(row.range);
    if (!row.model.empty()) json.key("model").text(row.model);
    json.key("doc").text(row.doc);
    json.end_object();
  }
  json.end_array();
  json.end_object();
  out << json.take();
  return kExitOk;
}

}  // namespace rigidity::cli
