// The rigidity command line: dispatch, help, and the mapping of errors to exit
// status (docs/cli.md).
#include "rigidity/cli.hpp"

#include <exception>
#include <iostream>

#include "rigidity/errors.hpp"
#include "rigidity/plugins.hpp"
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
    {"run", "rigidity run [SCENE.yaml] [--out DIR] [--set key.path=value ...] [--quiet] [--print-scene]",
     "evolve a scene and write its outputs (no SCENE: the paper's wall impact)",
     "Loads and validates SCENE (the embedded paper_wall_impact scene if none is given),\n"
     "evolves it to its end time and writes summary.json, events.csv, the CSV files its\n"
     "outputs ask for and resolved_scene.yaml into DIR, then prints a short summary. For\n"
     "the default scene it also compares what it found with the paper's closed forms.\n"
     "The CSV files are written as the run goes, into a temporary directory renamed to\n"
     "DIR at the end: a run that fails leaves nothing behind.\n"
     "\n"
     "A run that takes more than a second shows a progress line on stderr when stderr is\n"
     "a terminal. Ctrl-C stops it cleanly: the outputs up to the time reached are written,\n"
     "with status 'interrupted' (exit 130); so does SIGTERM (kill, timeout, a batch\n"
     "system's time limit; exit 143), however often it is sent. A second Ctrl-C, half a\n"
     "second or more after the first, quits at once without the outputs. A run that\n"
     "reaches solver.max_fronts or solver.max_interactions stops the same way with status\n"
     "'stopped' (exit 1), and says what to change. A run that meets a state with no\n"
     "classical solution (a material crushed to zero length) stops there the same way,\n"
     "with status 'inadmissible' (exit 3), the error bound at that instant, and whether\n"
     "that bound could move or remove the stop.\n"
     "\n"
     "options:\n"
     "  --out DIR              output directory (default out/<scene name>); an earlier run's\n"
     "                         files there are replaced, any other file there stays\n"
     "  --set key.path=value   override a scene value before validation, e.g.\n"
     "                         --set bodies.0.velocity=0.8 (repeatable); a time.end set\n"
     "                         shorter drops the snapshot times beyond it, with a note\n"
     "  --quiet                print nothing but errors (no summary, notes, warnings or progress)\n"
     "  --print-scene          print the scene as it would run (every default filled in)\n"
     "                         and exit without running it\n",
     run_command},
    {"validate", "rigidity validate SCENE.yaml [--set key.path=value ...]", "check a scene file without running it",
     "Loads SCENE with every rule of the scene schema and reports the first error as\n"
     "FILE:LINE:COL: error: ... (exit 2), or 'SCENE: ok' (exit 0).\n"
     "\n"
     "options:\n"
     "  --set key.path=value   override a scene value before validation (repeatable)\n",
     validate_command},
    {"schema", "rigidity schema [--json] [--si]", "list every scene key: type, default, unit, range, doc",
     "Prints every key a scene file may hold, from the one declaration the loader checks\n"
     "scenes against: its type, whether it is required or its default, its unit, its range\n"
     "and its doc, nested as in a scene; the keys each registered material model adds to\n"
     "its entry under materials are listed under it.\n"
     "\n"
     "options:\n"
     "  --json                 one row per key, by path (bodies.*.velocity), as JSON\n"
     "  --si                   defaults and ranges in SI units (m, s, kg/m^3, Pa, m/s)\n",
     schema_command},
    {"materials", "rigidity materials [NAME] [--json]",
     "list the registered materials: parameters, units, ranges and docs",
     "Lists every registered material (or only NAME) with its documentation and each of\n"
     "its parameters: type, default or required, units (natural and SI), range and doc.\n"
     "\n"
     "options:\n"
     "  --json                 print the list as JSON\n",
     materials_command},
    {"compare",
     "rigidity compare [--scene FILE] [--materials a,b] [--out DIR] [--speeds v,...] [--impact-speed v] "
     "[--param model.name=x ...]",
     "compare the materials: stress-strain laws, sound speeds, wall impacts and Hugoniots",
     "For every registered material (or those named by --materials) tabulates the\n"
     "stress-strain law p(s) in compression and traction, the sound speed c_s(s), and the\n"
     "exact wall impact of an unstrained bar at each speed v (exact Riemann solver): the\n"
     "stretch s and pressure p behind the reflected front, and the front's speed relative\n"
     "to the unstrained bar. Writes into DIR (default out/compare):\n"
     "  materials.csv      one row per material: parameters, c_s at s = 1, maximum pressure\n"
     "                     and tension (inf if unbounded), linear degeneracy, the impact at\n"
     "                     --impact-speed, and crush_speed, the impact speed that crushes it\n"
     "                     (empty cells: no classical solution, or no such speed)\n"
     "  stress_strain.csv  material,s,p,e,cs on a grid of s (admissible stretches only)\n"
     "  impact.csv         material,v,s,p,front_speed (speeds below the crush speed only)\n"
     "  hugoniot.csv       material,s,p,v_shock,v_smooth: a compression from rest to s, the\n"
     "                     speed of the material behind a shock (the Hugoniot) and behind a\n"
     "                     smooth wave (the isentrope) to it\n"
     "  stress_strain.png, sound_speed.png, impact.png, hugoniot.png and the gnuplot\n"
     "                     scripts (.gp)\n"
     "that draw them, and prints a markdown summary. Without gnuplot the tables and\n"
     "scripts are written and a warning says the plots were not drawn.\n"
     "A parameter that is required and has no default takes a representative value: the\n"
     "midpoint of a bounded range, else 1 if allowed, else one unit inside its bound.\n"
     "\n"
     "options:\n"
     "  --materials a,b,...    the materials to compare (default: every registered one)\n"
     "  --out DIR              output directory (default out/compare)\n"
     "  --speeds v1,v2,...     wall impact speeds in (0, 1) for impact.csv\n"
     "                         (default 0.01, 0.02, ..., 0.99)\n"
     "  --impact-speed v       the impact speed of materials.csv (default 0.5)\n"
     "  --param model.name=x   a material parameter, e.g. --param hooke.wave_speed=0.3\n"
     "                         (repeatable)\n"
     "  --scene FILE           compare the materials FILE declares, under its names and\n"
     "                         with its parameters (two hooke materials at V = 0.5 and 0.9,\n"
     "                         say); --materials then picks among those names\n",
     compare_command},
    {"plot", "rigidity plot RUN_DIR [--out DIR] [--no-animation | --animation]",
     "draw a run's outputs as PNG images with gnuplot",
     "Reads the outputs `rigidity run` wrote into RUN_DIR and draws, with gnuplot:\n"
     "  xt.png         the x-t diagram of the fronts, coloured by kind (fronts.csv), from\n"
     "                 xt_fronts.csv: the segments it can show (of two that draw the same\n"
     "                 pixels, one; at most 300000), so that a run of millions of\n"
     "                 segments draws in seconds\n"
     "  probes.png     probe histories, one panel per quantity (probes.csv); a\n"
     "                 front-tracking run's jumps as steps, the lab position x as a line\n"
     "  snapshots.png  snapshot profiles against the label X, one panel per quantity\n"
     "                 (snapshots.csv), several bodies side by side (each shifted by its\n"
     "                 initial position); a front-tracking run's states as the staircases\n"
     "                 they are, the lab position x as a continuous line\n"
     "  snapshots_lab.png  the same profiles against the lab position x, when the\n"
     "                 snapshots sample x (its data in snapshots_lab.csv)\n"
     "  animation.gif  60 frames from xt_fronts.csv: the x-t diagram drawn up to each\n"
     "                 frame's time above, every front where it is at that time below;\n"
     "                 skipped (with a note) above 20000 segments to draw\n"
     "SI axes of x and t are in prefixed units (mm, µs, ...). A plot whose CSV file is\n"
     "missing or empty is skipped. Each image is drawn by a gnuplot script written beside\n"
     "it (xt.gp, ..., animation.gp), kept so that it can be edited and rerun\n"
     "(cd DIR && gnuplot xt.gp). Without gnuplot on PATH: an error and exit 1.\n"
     "\n"
     "options:\n"
     "  --out DIR              where the images and scripts go (default RUN_DIR)\n"
     "  --no-animation         do not draw animation.gif\n"
     "  --animation            draw animation.gif however many the segments (slow)\n",
     plot_command},
    {"sweep", "rigidity sweep SWEEP.yaml [--out DIR] [-j N] [--quiet]",
     "run a parameter sweep of a scene into one table (sweep.csv)",
     "Reads SWEEP (a base scene, parameters by their --set key paths as values, linspace,\n"
     "logspace or sampled ranges, and the figures of merit to collect), runs every case\n"
     "in-process on N threads and writes DIR/sweep.csv (one row per case: case, the\n"
     "parameters, status, exit_code, message, the figures, wall_time_s) and sweep.json\n"
     "(every case's parameters). An invalid or inadmissible case is a row with its exit\n"
     "code and message. Rows are written as cases finish: Ctrl-C stops cleanly (exit 130;\n"
     "SIGTERM: 143)\n"
     "and the same command run again runs only the cases missing from sweep.csv.\n"
     "\n"
     "options:\n"
     "  --out DIR              output directory (default out/<sweep file stem>)\n"
     "  -j N                   worker threads (default: the hardware's cores)\n"
     "  --quiet                print nothing but errors (no progress or summary)\n",
     sweep_command},
};

const Command* find_command(std::string_view name) {
  for (const Command& c : kCommands)
    if (c.name == name) return &c;
  return nullptr;
}

constexpr std::string_view kExitStatus =
    "exit status: 0 done, 1 internal failure or a run stopped by a budget, 2 invalid input,\n"
    "             3 valid scene without a classical solution (physically inadmissible; a\n"
    "             run that meets one writes its outputs up to then), 130 a run interrupted\n"
    "             by Ctrl-C, 143 by SIGTERM (its outputs up to then are written)\n";

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
  load_environment_plugins();  // RIGIDITY_PLUGIN_PATH (plugins.hpp): their materials are every command's
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
