// rigidity validate SCENE.yaml: the scene loader's verdict, nothing run.
#include <ostream>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"

namespace rigidity::cli {

namespace {
std::string count(std::size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}
}  // namespace

int validate_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--set", true, true}};
  const Arguments parsed = parse_arguments("validate", args, kOptions);
  if (parsed.help) {
    out << help("validate");
    return kExitOk;
  }
  if (parsed.positional.size() != 1)
    throw usage_error("validate",
                      parsed.positional.empty() ? "validate needs a scene file" : "validate takes one scene file");
  const std::string& path = parsed.positional[0];
  const Scene scene = load_scene_file(path, scene_overrides(parsed, "validate"));  // throws InputError: exit 2
  out << path << ": ok (" << count(scene.bodies.size(), "body", "bodies") << ", "
      << count(scene.materials.size(), "material", "materials") << ")\n";
  return kExitOk;
}

}  // namespace rigidity::cli
