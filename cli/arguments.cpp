// Command-line parsing: options declared per command, unknown ones named with the
// closest valid spelling.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/spelling.hpp"

namespace rigidity::cli {

CommandError usage_error(const std::string& command, const std::string& message) {
  return CommandError(kExitInvalidInput, message, true, command);
}

bool Arguments::has(std::string_view option) const {
  return std::any_of(options.begin(), options.end(), [&](const auto& o) { return o.first == option; });
}

std::optional<std::string> Arguments::value(std::string_view option) const {
  for (const auto& [name, v] : options)
    if (name == option) return v;
  return std::nullopt;
}

std::vector<std::string> Arguments::values(std::string_view option) const {
  std::vector<std::string> out;
  for (const auto& [name, v] : options)
    if (name == option) out.push_back(v);
  return out;
}

Arguments parse_arguments(const std::string& command, std::span<const std::string> args,
                          std::span<const OptionSpec> options) {
  const std::string where = command.empty() ? std::string("rigidity") : "'rigidity " + command + "'";
  Arguments parsed;
  bool options_ended = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (options_ended || arg.size() < 2 || arg[0] != '-') {
      parsed.positional.push_back(arg);
      continue;
    }
    if (arg == "--") {
      options_ended = true;
      continue;
    }
    if (arg == "-h" || arg == "--help") {
      parsed.help = true;
      continue;
    }
    const std::size_t equals = arg.find('=');
    const std::string name = arg.substr(0, equals);
    const auto spec = std::find_if(options.begin(), options.end(), [&](const OptionSpec& o) { return o.name == name; });
    if (spec == options.end()) {
      std::vector<std::string> known{"--help"};
      for (const OptionSpec& o : options) known.emplace_back(o.name);
      std::string message = "unknown option '" + name + "' for " + where;
      const std::string near = closest_match(name, known);
      if (!near.empty()) message += " (did you mean '" + near + "'?)";
      throw usage_error(command, message);
    }
    if (!spec->repeatable && parsed.has(name)) throw usage_error(command, "option " + name + " is given twice");
    std::string value;
    if (spec->takes_value) {
      if (equals != std::string::npos) {
        value = arg.substr(equals + 1);
      } else if (i + 1 < args.size()) {
        value = args[++i];
      } else {
        throw usage_error(command, "option " + name + " needs a value");
      }
    } else if (equals != std::string::npos) {
      throw usage_error(command, "option " + name + " takes no value");
    }
    parsed.options.emplace_back(name, std::move(value));
  }
  return parsed;
}

std::optional<double> parse_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::vector<std::string> scene_overrides(const Arguments& args, const std::string& command) {
  std::vector<std::string> overrides = args.values("--set");
  for (const std::string& o : overrides) {
    const std::size_t equals = o.find('=');
    if (equals == std::string::npos || equals == 0)
      throw usage_error(command, "--set expects key.path=value (e.g. bodies.0.velocity=0.8), got '" + o + "'");
  }
  return overrides;
}

}  // namespace rigidity::cli
