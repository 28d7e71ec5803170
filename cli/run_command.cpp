// rigidity run [SCENE.yaml]: load, solve while the outputs stream to disk, and say
// in a few lines what happened; for the default scene, also what it found against
// the paper. A long run shows a progress line on a terminal; Ctrl-C stops it cleanly.
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "hdf5_output.hpp"
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

/// `value` with the fewest significant digits (at least `digits`) that print it above
/// `limit` as `limit` prints, so that a number said to be above another never reads as
/// equal to it.
std::string number_above(double value, double limit, int digits = 3) {
  const std::string limit_text = number(limit);
  for (int d = digits; d <= 17; ++d) {
    const std::string text = number(value, d);
    if (std::stod(text) > std::stod(limit_text)) return text;
  }
  return number(value, 17);
}

/// The terminal's account of the solver: what it was asked (tolerance, or cells and
/// order), what it guarantees (the error bound) and what it cost. Every other number the
/// solver reports (the bound's parts, thresholds, counts) is in summary.json's `solver`.
std::string solver_line(const RunResult& result) {
  const std::string method = result.solver.empty() ? std::string("?") : result.solver;
  std::vector<std::string> asked;
  const double tolerance = result.solver_number("tolerance");
  const double bound = result.solver_number("error_bound");
  const double resolution = result.solver_number("resolution");
  const double cells = result.solver_number("cells");
  const double order = result.solver_number("order");
  if (!std::isnan(tolerance)) asked.push_back("tolerance " + number(tolerance, 6));
  if (!std::isnan(resolution) && bound > 0.0) asked.push_back("resolved at " + number(resolution, 3));
  if (!std::isnan(bound))
    asked.push_back("error bound " +
                    (!std::isnan(tolerance) && bound > tolerance ? number_above(bound, tolerance) : number(bound, 3)));
  if (!std::isnan(cells)) asked.push_back(number(cells, 10) + " cells per body");
  if (!std::isnan(order)) asked.push_back("order " + number(order, 1));

  std::vector<std::string> cost;
  const double steps = result.solver_number("steps");
  if (!std::isnan(steps)) {
    cost.push_back(number(steps, 15) + " steps");
  } else {
    cost.push_back(std::to_string(result.stats.fronts) + " fronts");
    cost.push_back(std::to_string(result.stats.interactions) + " interactions");
    if (result.stats.crossings_unvisited > 0)
      cost.push_back(std::to_string(result.stats.crossings_unvisited) + " crossings known without a visit");
  }
  std::string line = "solver: " + method + (asked.empty() ? "" : " (" + join(asked, ", ") + ")") + "; " +
                     join(cost, ", ") + ", solved in " + number(result.stats.wall_time_s, 3) + " s";
  if (result.stats.sampling_time_s >= 0.001)
    line += " (outputs sampled in " + number(result.stats.sampling_time_s, 3) + " s)";
  return line;
}

/// Events the terminal summary lists one by one (summary.json has more, events.csv all).
constexpr std::size_t kEventsShown = 20;
/// Seconds between two progress lines when stderr is a log, not a terminal.
constexpr double kLogInterval_s = 30.0;

void print_summary(std::ostream& out, const Scene& scene, const RunResult& result, const std::string& dir) {
  const SceneUnits units(scene.units);
  const std::string time_unit(unit_symbol(Dimension::time, scene.units));
  out << scene.name << " (" << scene.source << "): " << result.status;
  if (result.status == to_string(RunStatus::ok)) {
    out << " at t_end = " << units(scene.t_end, Dimension::time) << " " << time_unit << "\n";
  } else {
    out << " at t = " << units(result.t_reached, Dimension::time) << " " << time_unit
        << " of t_end = " << units(scene.t_end, Dimension::time) << " " << time_unit << "\n";
  }

  out << solver_line(result) << "\n";

  long total_events = 0;
  std::vector<std::string> counts;
  for (const auto& [kind, count] : result.event_counts) {
    total_events += count;
    counts.push_back(std::to_string(count) + " " + kind);
  }
  if (result.events.empty()) {
    out << "events: none\n";
  } else {
    out << "events:\n";
    Table events({units.label("t", Dimension::time), "kind", units.label("x", Dimension::length), "bodies"});
    for (std::size_t i = 0; i < std::min(result.events.size(), kEventsShown); ++i) {
      const RunEvent& e = result.events[i];
      events.add({units(e.t, Dimension::time), e.kind, units(e.x, Dimension::length), join(e.bodies, ", ")});
    }
    events.print(out);
    if (total_events > static_cast<long>(kEventsShown))
      out << "  ... " << total_events << " events in all (" << join(counts, ", ") << "), every one in events.csv\n";
  }

  out << (result.status == to_string(RunStatus::ok) ? "bodies at t_end:\n" : "bodies at the time reached:\n");
  Table bodies({"name", units.label("x_left", Dimension::length), units.label("x_right", Dimension::length),
                units.label("velocity_mean", Dimension::velocity),
                units.label("momentum", Dimension::momentum_per_area),
                units.label("kinetic", Dimension::energy_per_area), units.label("internal", Dimension::energy_per_area),
                units.label("rest", Dimension::energy_per_area)});
  for (const BodyResult& b : result.bodies)
    bodies.add({b.name, units(b.x_left, Dimension::length), units(b.x_right, Dimension::length),
                units(b.velocity_mean, Dimension::velocity), units(b.momentum, Dimension::momentum_per_area),
                units(b.kinetic_energy, Dimension::energy_per_area),
                units(b.internal_energy, Dimension::energy_per_area),
                units(b.rest_energy, Dimension::energy_per_area)});
  bodies.print(out);

  // energy_final = energy_initial + wall_work - energy_dissipated (+ the droplets' and the
  // waves' parts), momentum_final = momentum_initial + wall_impulse (+ theirs).
  const Conservation& c = result.conservation;
  const double energy_residual = c.energy_residual();
  const double momentum_residual = c.momentum_residual();
  const bool droplets = c.energy_droplets != 0.0 || c.momentum_droplets != 0.0;
  const bool waves = c.energy_waves != 0.0 || c.momentum_waves != 0.0;
  const double energy_scale = std::max(std::abs(c.energy_initial), std::abs(c.energy_final));
  const double momentum_scale =
      std::max({std::abs(c.momentum_initial), std::abs(c.momentum_final), std::abs(c.wall_impulse)});
  const Dimension E = Dimension::energy_per_area;
  const Dimension P = Dimension::momentum_per_area;
  out << "conservation:\n";
  std::vector<std::string> head{"", "initial", "final", "walls", "dissipated", "residual", "relative"};
  std::vector<std::string> energy{units.label("energy", E),
                                  units(c.energy_initial, E),
                                  units(c.energy_final, E),
                                  units(c.wall_work, E),
                                  units(c.energy_dissipated, E),
                                  number(from_natural(energy_residual, E, scene.units), 3),
                                  energy_scale > 0.0 ? number(std::abs(energy_residual) / energy_scale, 2) : "-"};
  std::vector<std::string> momentum{
      units.label("momentum", P),
      units(c.momentum_initial, P),
      units(c.momentum_final, P),
      units(c.wall_impulse, P),
      "",
      number(from_natural(momentum_residual, P, scene.units), 3),
      momentum_scale > 0.0 ? number(std::abs(momentum_residual) / momentum_scale, 2) : "-"};
  if (waves) {  // what smooth steps and weak waves held back made, before the residual
    head.insert(head.begin() + 5, "waves");
    energy.insert(energy.begin() + 5, units(c.energy_waves, E));
    momentum.insert(momentum.begin() + 5, units(c.momentum_waves, P));
  }
  if (droplets) {  // the droplet model's change, before the residual
    head.insert(head.begin() + 5, "droplets");
    energy.insert(energy.begin() + 5, units(c.energy_droplets, E));
    momentum.insert(momentum.begin() + 5, units(c.momentum_droplets, P));
  }
  Table balance(head);
  balance.add(energy);
  balance.add(momentum);
  balance.print(out);

  std::vector<std::string> files{"summary.json", "events.csv"};
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

/// The extremes of the paper's quantities at the 'wall' probe, kept as the samples stream past.
struct WallProbeExtremes {
  std::optional<double> p_max, s_min;
};

void print_paper_comparison(std::ostream& out, const Scene& scene, const RunResult& result,
                            const WallProbeExtremes& wall_probe) {
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
  const std::optional<double> p_max = wall_probe.p_max, s_min = wall_probe.s_min;
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

// ---- watching a run ---------------------------------------------------------------------

/// Passes everything on to the run directory, keeping on the way the extremes of the
/// 'wall' probe that the comparison with the paper needs.
class WatchingRecorder final : public RunRecorder {
 public:
  WatchingRecorder(const Scene& scene, RunRecorder& files) : files_(files) {
    const auto& probes = scene.outputs.probes;
    const auto wall = std::find_if(probes.begin(), probes.end(), [](const ProbeDecl& p) { return p.name == "wall"; });
    wall_index_ = wall == probes.end() ? -1 : static_cast<int>(wall - probes.begin());
  }
  [[nodiscard]] const WallProbeExtremes& wall_probe() const { return wall_; }

 private:
  void record_front(const FrontSegment& segment) override { files_.front(segment); }
  void record_probe(const ProbeSample& sample) override {
    if (sample.probe == wall_index_) {
      if (sample.quantity == Quantity::p) wall_.p_max = std::max(wall_.p_max.value_or(sample.value), sample.value);
      if (sample.quantity == Quantity::s) wall_.s_min = std::min(wall_.s_min.value_or(sample.value), sample.value);
    }
    files_.probe(sample);
  }
  void record_snapshot(const SnapshotSample& sample) override { files_.snapshot(sample); }
  void record_event(const RunEvent& event) override { files_.event(event); }

  RunRecorder& files_;
  int wall_index_ = -1;
  WallProbeExtremes wall_;
};

/// One line on stderr, rewritten in place ('\r'): where the run is, how fast it goes
/// and when it should end. Cleared when the run ends.
class ProgressLine {
 public:
  explicit ProgressLine(const Scene& scene) : scene_(scene) {}
  ~ProgressLine() { clear(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// On a terminal: the line, rewritten in place.
  void show(const RunProgress& progress) {
    std::string line = describe(progress) + " | Ctrl-C stops";
    // A line wider than the terminal would wrap, and '\r' would no longer return to its start.
    if (const std::size_t columns = terminal_columns(); columns > 1 && line.size() > columns - 1)
      line.resize(columns - 1);
    const std::size_t width = line.size();
    if (line.size() < width_) line.append(width_ - line.size(), ' ');  // cover the longer line before
    width_ = width;
    std::cerr << '\r' << line << std::flush;
    shown_ = true;
  }

  /// Into a log (stderr not a terminal, as on a batch system): one line each time.
  void log(const RunProgress& progress) {
    std::cerr << "progress: " << describe(progress) << " (" << duration(progress.elapsed_s) << " so far)" << std::endl;
  }

  void clear() {
    if (!shown_) return;
    std::cerr << '\r' << std::string(width_, ' ') << '\r' << std::flush;
    shown_ = false;
  }

 private:
  /// Where the run is and how fast it goes: rates over the last interval, smoothed (a run's
  /// pace changes as fronts multiply).
  std::string describe(const RunProgress& progress) {
    const double dt_wall = progress.elapsed_s - last_.elapsed_s;
    if (dt_wall > 0.0) {
      const double sim_rate = (progress.t - last_.t) / dt_wall;
      const double interaction_rate = static_cast<double>(progress.interactions - last_.interactions) / dt_wall;
      const double weight = shown_ ? 0.3 : 1.0;
      sim_rate_ = weight * sim_rate + (1.0 - weight) * sim_rate_;
      interaction_rate_ = weight * interaction_rate + (1.0 - weight) * interaction_rate_;
    }
    last_ = progress;

    const std::string unit(unit_symbol(Dimension::time, scene_.units));
    std::string line = "t " + number(from_natural(progress.t, Dimension::time, scene_.units), 4) + " / " +
                       number(from_natural(scene_.t_end, Dimension::time, scene_.units), 4) + " " + unit;
    if (progress.fronts_alive >= 0) line += " | " + count(static_cast<double>(progress.fronts_alive)) + " fronts";
    line += " | " + count(interaction_rate_) + " interactions/s";
    line += " | " + (sim_rate_ > 0.0 ? duration((scene_.t_end - progress.t) / sim_rate_) : std::string("?")) + " left";
    return line;
  }
  /// 1234567 as "1.23 M".
  static std::string count(double value) {
    if (value < 1e4) return number(std::round(value), 6);
    if (value < 1e6) return number(value / 1e3, 3) + " k";
    if (value < 1e9) return number(value / 1e6, 3) + " M";
    return number(value / 1e9, 3) + " G";
  }
  static std::size_t terminal_columns() {
    struct winsize size {};
    if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) != 0 || size.ws_col == 0) return 80;
    return size.ws_col;
  }
  static std::string duration(double seconds) {
    if (!std::isfinite(seconds) || seconds > 1e7) return "forever";
    if (seconds < 100.0) return number(seconds, 2) + " s";
    if (seconds < 6000.0) return number(seconds / 60.0, 2) + " min";
    return number(seconds / 3600.0, 2) + " h";
  }

  const Scene& scene_;
  RunProgress last_{};
  double sim_rate_ = 0.0, interaction_rate_ = 0.0;
  std::size_t width_ = 0;
  bool shown_ = false;
};

}  // namespace

int run_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--out", true}, {"--set", true, true}, {"--quiet"}, {"--print-scene"}};
  const Arguments parsed = parse_arguments("run", args, kOptions);
  if (parsed.help) {
    out << help("run");
    return kExitOk;
  }
  if (parsed.positional.size() > 1) throw usage_error("run", "run takes at most one scene file");
  if (const auto dir = parsed.value("--out"); dir && dir->empty()) throw usage_error("run", "--out needs a directory");
  const std::vector<std::string> overrides = scene_overrides(parsed, "run");
  const bool quiet = parsed.has("--quiet");

  const bool default_scene = parsed.positional.empty();
  const Scene scene = default_scene ? load_scene_string(default_scene_text(), "<default>", overrides)
                                    : load_scene_file(parsed.positional[0], overrides);
  if (!quiet)
    for (const std::string& note : scene.notes) std::cerr << "note: " << note << "\n";
  if (parsed.has("--print-scene")) {
    out << scene.resolved_yaml();  // the scene as it would run, every default filled in; nothing is run
    return kExitOk;
  }
  const std::string dir =
      parsed.value("--out").value_or("out/" + (scene.name.empty() ? std::string("scene") : scene.name));

  RunResult result;
  WallProbeExtremes wall_probe;
  std::optional<std::string> inadmissible;  // the solver's message, if the run met no classical solution
  try {
    // Outputs stream into a temporary directory, renamed into place once complete;
    // an exception leaves nothing behind.
    StreamingRecorder files(scene, dir);
    WatchingRecorder recorder(scene, files);
    const StopOnSignals stop_on_signals(quiet);
    std::optional<ProgressLine> progress;
    if (!quiet && ::isatty(STDERR_FILENO) == 1) {
      progress.emplace(scene);
      recorder.on_progress([&progress](const RunProgress& p) { progress->show(p); });
    } else if (!quiet) {
      // A log, as on a batch system: a line every kLogInterval_s once the run has taken that long.
      progress.emplace(scene);
      recorder.on_progress([&progress](const RunProgress& p) { progress->log(p); }, kLogInterval_s, kLogInterval_s);
    }
    try {
      result = solve(scene, recorder);
    } catch (const InadmissibleStop& stop) {
      // The run up to the instant it met no classical solution: its outputs are written as
      // an interrupted run's are, and the exit status is 3 all the same.
      result = stop.result();
      inadmissible = stop.what();
    }
    if (progress) progress->clear();
    files.commit(result);
    wall_probe = recorder.wall_probe();
  } catch (const OutputRefused& e) {
    throw CommandError(kExitInvalidInput, std::string(e.what()) + "; nothing was run");
  } catch (const OutputError& e) {
    throw CommandError(kExitInternal, "cannot write the outputs: " + std::string(e.what()));
  }
  // Only the HDF5 file's own failures are reported as such: whatever the solver throws (a
  // scene without a classical solution, a numerical failure) keeps its own exit status.
  if (scene.outputs.hdf5) {
    try {
      write_hdf5(dir, scene.units);
    } catch (const std::runtime_error& e) {
      throw CommandError(kExitInternal, "cannot write run.h5 (the CSV files are written): " + std::string(e.what()));
    }
  }

  if (!quiet) {
    for (const std::string& warning : result.warnings) std::cerr << "warning: " << warning << "\n";
    print_summary(out, scene, result, dir);
    if (default_scene) print_paper_comparison(out, scene, result, wall_probe);
  }
  if (inadmissible) {
    const std::string unit(unit_symbol(Dimension::time, scene.units));
    std::cerr << "error: " << *inadmissible << "\n"
              << "the run stopped there, at t = "
              << number(from_natural(result.t_reached, Dimension::time, scene.units)) << " " << unit
              << " of t_end = " << number(from_natural(scene.t_end, Dimension::time, scene.units)) << " " << unit
              << " (status inadmissible); the outputs up to then are in " << dir << "\n"
              << result.verdict << "\n";
    return kExitInadmissible;
  }
  if (result.status == to_string(RunStatus::stopped)) {
    std::cerr << "stopped: " << result.stop_reason << "\n";
    return kExitStopped;
  }
  if (result.status == to_string(RunStatus::interrupted)) {
    std::cerr << "interrupted (" << StopOnSignals::cause()
              << ") at t = " << number(from_natural(result.t_reached, Dimension::time, scene.units)) << " "
              << unit_symbol(Dimension::time, scene.units)
              << " of t_end = " << number(from_natural(scene.t_end, Dimension::time, scene.units)) << " "
              << unit_symbol(Dimension::time, scene.units) << "; the outputs up to then are in " << dir << "\n";
    return StopOnSignals::exit_status();
  }
  return kExitOk;
}

}  // namespace rigidity::cli
