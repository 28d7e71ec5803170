// rigidity run [SCENE.yaml]: load, solve, write the outputs, and say in a few lines
// what happened; for the default scene, also what it found against the paper.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity::cli {

namespace {

/// `value` with `digits` significant digits, for people to read (the files keep all).
std::string number(double value, int digits = 10) {
  std::array<char, 64> text{};
  std::snprintf(text.data(), text.size(), "%.*g", digits, value);
  return text.data();
}

/// A plain text table, every column as wide as its widest cell.
class Table {
 public:
  explicit Table(std::vector<std::string> header) : rows_{std::move(header)} {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }

  void print(std::ostream& out, std::size_t indent = 2) const {
    std::vector<std::size_t> widths;
    for (const auto& row : rows_) {
      widths.resize(std::max(widths.size(), row.size()), 0);
      for (std::size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
    }
    for (const auto& row : rows_) {
      std::string line(indent, ' ');
      for (std::size_t i = 0; i < row.size(); ++i) {
        line += row[i];
        if (i + 1 < row.size()) line.append(widths[i] - row[i].size() + 2, ' ');
      }
      out << line << "\n";
    }
  }

 private:
  std::vector<std::vector<std::string>> rows_;
};

/// Values converted from natural units to the scene's, with their unit symbols.
class SceneUnits {
 public:
  explicit SceneUnits(UnitSystem system) : system_(system) {}
  [[nodiscard]] std::string operator()(double natural_value, Dimension d) const {
    return number(from_natural(natural_value, d, system_));
  }
  [[nodiscard]] std::string label(std::string_view name, Dimension d) const {
    return std::string(name) + " [" + std::string(unit_symbol(d, system_)) + "]";
  }

 private:
  UnitSystem system_;
};

std::string join(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : std::string(separator)) + item;
  return out;
}

void print_summary(std::ostream& out, const Scene& scene, const RunResult& result, const std::string& dir) {
  const SceneUnits units(scene.units);
  out << scene.name << " (" << scene.source << "): " << result.status
      << " at t_end = " << units(scene.t_end, Dimension::time) << " " << unit_symbol(Dimension::time, scene.units)
      << "\n";

  std::vector<std::string> numbers;
  for (const auto& [name, value] : result.solver_numbers) numbers.push_back(name + " " + number(value, 6));
  const std::string method = result.solver.empty() ? std::string("?") : result.solver;
  out << "solver: " << method << (numbers.empty() ? "" : " (" + join(numbers, ", ") + ")") << "; "
      << result.stats.fronts << " fronts, " << result.stats.interactions << " interactions, solved in "
      << number(result.stats.wall_time_s, 3) << " s\n";

  if (result.events.empty()) {
    out << "events: none\n";
  } else {
    out << "events:\n";
    Table events({units.label("t", Dimension::time), "kind", units.label("x", Dimension::length), "bodies"});
    for (const RunEvent& e : result.events)
      events.add({units(e.t, Dimension::time), e.kind, units(e.x, Dimension::length), join(e.bodies, ", ")});
    events.print(out);
  }

  out << "bodies at t_end:\n";
  Table bodies({"name", units.label("x_left", Dimension::length), units.label("x_right", Dimension::length),
                units.label("velocity_mean", Dimension::velocity),
                units.label("momentum", Dimension::momentum_per_area),
                units.label("energy", Dimension::energy_per_area)});
  for (const BodyResult& b : result.bodies)
    bodies.add({b.name, units(b.x_left, Dimension::length), units(b.x_right, Dimension::length),
                units(b.velocity_mean, Dimension::velocity), units(b.momentum, Dimension::momentum_per_area),
                units(b.energy, Dimension::energy_per_area)});
  bodies.print(out);

  // energy_final = energy_initial + wall_work - energy_dissipated,
  // momentum_final = momentum_initial + wall_impulse (SPEC §5).
  const Conservation& c = result.conservation;
  const double energy_residual = c.energy_final + c.energy_dissipated - c.energy_initial - c.wall_work;
  const double momentum_residual = c.momentum_final - c.momentum_initial - c.wall_impulse;
  const double energy_scale = std::max(std::abs(c.energy_initial), std::abs(c.energy_final));
  const double momentum_scale =
      std::max({std::abs(c.momentum_initial), std::abs(c.momentum_final), std::abs(c.wall_impulse)});
  const Dimension E = Dimension::energy_per_area;
  const Dimension P = Dimension::momentum_per_area;
  out << "conservation:\n";
  Table balance({"", "initial", "final", "walls", "dissipated", "residual", "relative"});
  balance.add({units.label("energy", E), units(c.energy_initial, E), units(c.energy_final, E), units(c.wall_work, E),
               units(c.energy_dissipated, E), number(from_natural(energy_residual, E, scene.units), 3),
               energy_scale > 0.0 ? number(std::abs(energy_residual) / energy_scale, 2) : "-"});
  balance.add({units.label("momentum", P), units(c.momentum_initial, P), units(c.momentum_final, P),
               units(c.wall_impulse, P), "", number(from_natural(momentum_residual, P, scene.units), 3),
               momentum_scale > 0.0 ? number(std::abs(momentum_residual) / momentum_scale, 2) : "-"});
  balance.print(out);

  for (const std::string& warning : result.warnings) out << "warning: " << warning << "\n";

  std::vector<std::string> files{"summary.json"};
  if (!scene.outputs.probes.empty()) files.emplace_back("probes.csv");
  if (!scene.outputs.snapshots.empty()) files.emplace_back("snapshots.csv");
  if (scene.outputs.fronts) files.emplace_back("fronts.csv");
  files.emplace_back("resolved_scene.yaml");
  out << "outputs in " << dir << (dir.ends_with('/') ? "" : "/") << ": " << join(files, ", ") << "\n";
}

// ---- the default scene against the paper's closed forms ----------------------------

/// Empty if the scene is the paper's setting (one unstrained rigid bar moving at a
/// uniform velocity into a wall on its right, free on its left), else why not.
std::string paper_setting_violation(const Scene& scene) {
  if (scene.bodies.size() != 1)
    return "the paper has one bar, the scene " + std::to_string(scene.bodies.size()) + " bodies";
  if (scene.left.type != BoundaryType::free || scene.right.type != BoundaryType::wall || scene.right.bonded)
    return "the paper's bar is free on the left and strikes a wall on the right";
  const BodyDecl& bar = scene.bodies.front();
  if (bar.segments.empty()) return "the bar has no segments";
  for (const Segment& seg : bar.segments) {
    const auto material = scene.materials.find(seg.material);
    if (material == scene.materials.end() || !material->second.material) return "the bar's material is not declared";
    if (material->second.material->model() != "rigid")
      return "the paper's formulas are for the rigid material, the bar is " +
             std::string(material->second.material->model());
    if (seg.rapidity != bar.segments.front().rapidity || seg.stretch != Stretch::natural() ||
        material->second.material->rest_density() != scene.material_of(bar.segments.front()).rest_density())
      return "the paper's bar is unstrained and uniform";
  }
  if (!(bar.segments.front().rapidity > 0.0)) return "the bar does not move toward the wall";
  return "";
}

std::string relative_difference(double paper, std::optional<double> found) {
  if (!found) return "-";
  const double difference = std::abs(*found - paper);
  return number(paper != 0.0 ? difference / std::abs(paper) : difference, 2);
}

void print_paper_comparison(std::ostream& out, const Scene& scene, const RunResult& result) {
  out << "\nagainst the paper (Brotas & Fernandes, physics/0307019, §3; natural units, c = 1):\n";
  if (const std::string why_not = paper_setting_violation(scene); !why_not.empty()) {
    out << "  no comparison: " << why_not << "\n";
    return;
  }
  const BodyDecl& bar = scene.bodies.front();
  const double v = std::tanh(bar.segments.front().rapidity);
  const double rest_density = scene.material_of(bar.segments.front()).rest_density();
  double l0 = 0.0;
  for (const Segment& seg : bar.segments) l0 += seg.length;

  // The paper's §3 and footnote 2: behind the front, which runs back at c, the bar is
  // at rest with stretch s and pressure p; the bar is stopped at t1 = l0 s/c and
  // leaves the wall at 2 t1 with velocity -v.
  const double s_paper = std::sqrt((1.0 - v) / (1.0 + v));
  const double p_paper = (1.0 / (s_paper * s_paper) - 1.0) * rest_density / 2.0;
  const double contact_paper = 2.0 * l0 * s_paper;  // [L/c]: the front's round trip
  const double rebound_paper = -v;

  // What rigidity found: the extremes of the wall probe, the separation event, the bar at t_end.
  std::optional<double> p_max, s_min;
  const auto& probes = scene.outputs.probes;
  const auto wall = std::find_if(probes.begin(), probes.end(), [](const ProbeDecl& p) { return p.name == "wall"; });
  const int wall_index = static_cast<int>(wall - probes.begin());
  for (const ProbeSample& sample : result.probes) {
    if (sample.probe != wall_index) continue;
    if (sample.quantity == Quantity::p) p_max = std::max(p_max.value_or(sample.value), sample.value);
    if (sample.quantity == Quantity::s) s_min = std::min(s_min.value_or(sample.value), sample.value);
  }
  const auto involves_bar = [&](const RunEvent& e) {
    return std::find(e.bodies.begin(), e.bodies.end(), bar.name) != e.bodies.end();
  };
  std::optional<double> separation, contact;
  for (const RunEvent& e : result.events) {
    if (!involves_bar(e)) continue;
    if (e.kind == "separation" && !separation) separation = e.t;
    if (e.kind == "contact" && !separation) contact = e.t;
  }
  if (!contact) {  // touching from the start, or closing the initial gap at v
    const double right_end = bar.position + l0 * std::sqrt(1.0 - v * v);
    contact = std::max(scene.right.position - right_end, 0.0) / v;
  }
  std::optional<double> contact_duration, rebound;
  if (separation) {
    contact_duration = *separation - *contact;
    for (const BodyResult& b : result.bodies)
      if (b.name == bar.name) rebound = b.velocity_mean;
  }

  out << "  v = " << number(v) << " (the bar's initial velocity), l0 = " << number(l0)
      << ", rho00 = " << number(rest_density) << "\n";
  Table table({"quantity", "paper", "rigidity", "relative difference"});
  const auto found = [](std::optional<double> value, const char* missing) {
    return value ? number(*value) : std::string(missing);
  };
  const char* no_probe = "(no 'wall' probe)";
  const char* not_reached = "(no separation by t_end)";
  table.add({"s at the wall, sqrt((1-v)/(1+v))", number(s_paper), found(s_min, no_probe),
             relative_difference(s_paper, s_min)});
  table.add({"p at the wall, (1/s^2-1) rho00/2", number(p_paper), found(p_max, no_probe),
             relative_difference(p_paper, p_max)});
  table.add({"contact duration, 2 l0 s/c", number(contact_paper), found(contact_duration, not_reached),
             relative_difference(contact_paper, contact_duration)});
  table.add({"rebound velocity, -v", number(rebound_paper), found(rebound, not_reached),
             relative_difference(rebound_paper, rebound)});
  table.print(out);
}

}  // namespace

int run_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--out", true}, {"--set", true, true}};
  const Arguments parsed = parse_arguments("run", args, kOptions);
  if (parsed.help) {
    out << help("run");
    return kExitOk;
  }
  if (parsed.positional.size() > 1) throw usage_error("run", "run takes at most one scene file");
  if (const auto dir = parsed.value("--out"); dir && dir->empty()) throw usage_error("run", "--out needs a directory");
  const std::vector<std::string> overrides = scene_overrides(parsed, "run");

  const bool default_scene = parsed.positional.empty();
  const Scene scene = default_scene ? load_scene_string(default_scene_text(), "<default>", overrides)
                                    : load_scene_file(parsed.positional[0], overrides);
  const RunResult result = solve(scene);

  const std::string dir =
      parsed.value("--out").value_or("out/" + (scene.name.empty() ? std::string("scene") : scene.name));
  try {
    write_run(scene, result, dir);
  } catch (const NumericalError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw CommandError(kExitInternal, "cannot write the outputs: " + std::string(e.what()));
  }

  print_summary(out, scene, result, dir);
  if (default_scene) print_paper_comparison(out, scene, result);
  return kExitOk;
}

}  // namespace rigidity::cli
