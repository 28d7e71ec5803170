// The rigidity command line: dispatch, help, and the mapping of errors to exit
// status (SPEC §4).
#include "rigidity/cli.hpp"

#include <exception>
#include <iostream>

#include "rigidity/errors.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/spelling.hpp"
#include "rigidity/version.hpp"

namespace rigidity {

namespace cli {

namespace {

struct Command {
  std::string_view name;
  std::string_view usage;
  std::string_view summary;
  std::string_view details;
  int (*run)(std::span<const std::string>, std::ostream&);
};

constexpr Command kCommands[] = {
    {"run", "rigidity run [SCENE.yaml] [--out DIR] [--set key.path=value ...]",
     "evolve a scene and write its outputs (no SCENE: the paper's wall impact)",
     "Loads and validates SCENE (the embedded paper_wall_impact scene if none is given),\n"
     "evolves it to its end time and writes summary.json, the CSV files its outputs ask\n"
     "for and resolved_scene.yaml into DIR, then prints a short summary. For the default\n"
     "scene it also compares what it found with the paper's closed forms.\n"
     "\n"
     "options:\n"
     "  --out DIR              output directory (default out/<scene name>); an earlier run\n"
     "                         there is replaced as a whole\n"
     "  --set key.path=value   override a scene value before validation, e.g.\n"
     "                         --set bodies.0.velocity=0.8 (repeatable)\n",
     run_command},
    {"validate", "rigidity validate SCENE.yaml [--set key.path=value ...]", "check a scene file without running it",
     "Loads SCENE with every rule of the scene schema and reports the first error as\n"
     "FILE:LINE:COL: error: ... (exit 2), or 'SCENE: ok' (exit 0).\n"
     "\n"
     "options:\n"
     "  --set key.path=value   override a scene value before validation (repeatable)\n",
     validate_command},
    {"materials", "rigidity materials [NAME] [--json]",
     "list the registered materials: parameters, units, ranges and docs",
     "Lists every registered material (or only NAME) with its documentation and each of\n"
     "its parameters: type, default or required, units (natural and SI), range and doc.\n"
     "\n"
     "options:\n"
     "  --json                 print the list as JSON\n",
     materials_command},
};

const Command* find_command(std::string_view name) {
  for (const Command& c : kCommands)
    if (c.name == name) return &c;
  return nullptr;
}

constexpr std::string_view kExitStatus =
    "exit status: 0 done, 1 internal failure, 2 invalid input,\n"
    "             3 valid scene without a classical solution (physically inadmissible)\n";

}  // namespace

std::string usage(std::string_view command) {
  if (const Command* c = find_command(command)) return "usage: " + std::string(c->usage) + "\n";
  std::string out = "usage:\n";
  for (const Command& c : kCommands) out += "  " + std::string(c.usage) + "\n";
  out += "  rigidity --help | --version\n";
  return out;
}

std::string help(std::string_view command) {
  if (const Command* c = find_command(command))
    return usage(command) + "\n" + std::string(c->summary) + ".\n\n" + std::string(c->details) + "\n" +
           std::string(kExitStatus);
  std::string out = "rigidity " + std::string(version()) +
                    ": relativistic continuum mechanics in one dimension\n"
                    "(rigid bodies, shock fronts and the method of characteristics)\n\n" +
                    usage("") + "\ncommands:\n";
  for (const Command& c : kCommands) {
    std::string name(c.name);
    name.resize(11, ' ');
    out += "  " + name + std::string(c.summary) + "\n";
  }
  out +=
      "\nRun 'rigidity COMMAND --help' for a command's options.\n"
      "Scenes are YAML files (see configs/paper_wall_impact.yaml); inside, c = 1.\n\n";
  return out + std::string(kExitStatus);
}

namespace {

int dispatch(const std::vector<std::string>& args) {
  if (args.empty()) throw usage_error("", "no command given");
  const std::string& first = args.front();
  if (first.size() > 1 && first[0] == '-') {
    static constexpr OptionSpec kGlobal[] = {{"--version"}};
    const Arguments parsed = parse_arguments("", args, kGlobal);
    if (parsed.help) {
      std::cout << help(parsed.positional.empty() ? std::string_view() : std::string_view(parsed.positional[0]));
      return kExitOk;
    }
    if (parsed.has("--version")) {
      std::cout << "rigidity " << version() << "\n";
      return kExitOk;
    }
  }
  if (first == "help") {  // "rigidity help [COMMAND]", as people type it
    std::cout << help(args.size() > 1 ? std::string_view(args[1]) : std::string_view());
    return kExitOk;
  }
  const Command* command = find_command(first);
  if (command == nullptr) {
    std::vector<std::string> names;
    for (const Command& c : kCommands) names.emplace_back(c.name);
    std::string message = "unknown command '" + first + "'";
    const std::string near = closest_match(first, names);
    if (!near.empty()) message += " (did you mean '" + near + "'?)";
    throw usage_error("", message);
  }
  return command->run(std::span<const std::string>(args).subspan(1), std::cout);
}

}  // namespace
}  // namespace cli

int cli_main(int argc, char** argv) {
  try {
    try {
      MaterialRegistry& registry = MaterialRegistry::instance();
      registry.check();  // two materials under one name: the build (or a plugin) is broken
      registry.seal();
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return kExitInternal;
    }
    const std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
    return cli::dispatch(args);
  } catch (const cli::CommandError& e) {
    std::cerr << "error: " << e.what() << "\n";
    if (e.show_usage()) {
      std::cerr << cli::usage(e.command());
      std::cerr << "Run 'rigidity " << (e.command().empty() ? "" : e.command() + " ") << "--help' for more.\n";
    }
    return e.exit_status();
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";  // "FILE:LINE:COL: error: ..."
    return kExitInvalidInput;
  } catch (const InadmissibleError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInadmissible;
  } catch (const NumericalError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << "\n";
    return kExitInternal;
  } catch (...) {
    std::cerr << "internal error: unknown exception\n";
    return kExitInternal;
  }
}

}  // namespace rigidity
