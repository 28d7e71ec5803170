// rigidity compare: the materials side by side. For each: the stress–strain law p(s)
// in compression and traction (the paper's Fig. 3, every material on one chart), the
// sound speed c_s(s), and the exact wall impact of an unstrained bar at speeds v,
// with the limits (maximum pressure, maximum tension, the speed that crushes it)
// marked. Tables as CSV, charts with gnuplot, a markdown summary on stdout.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/json_writer.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/wall_impact.hpp"
#include "rigidity/spelling.hpp"

namespace rigidity::cli {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kDefaultOut = "out/compare";
/// The speed of the wall impact reported in materials.csv and the summary.
constexpr double kDefaultImpactSpeed = 0.5;
/// impact.csv by default: v = k/100, k = 1..99 (0.2 and 0.6, the reference speeds of docs/materials.md, among them).
constexpr int kDefaultSpeedSteps = 100;
/// stress_strain.csv: ln s uniform on [−ln 50, ln 50], 2·200 steps, s = 1 included.
constexpr double kStretchSpan = 50.0;
constexpr int kStretchStepsPerSide = 200;
/// The stress–strain and sound-speed charts show s in [0, 4], as the paper's Fig. 3.
constexpr double kChartStretchMax = 4.0;

constexpr std::string_view kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                         "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};

// ---- numbers as text --------------------------------------------------------------------

/// The shortest text that reads back to the same double (CSV); ±inf as "inf"/"-inf". \pre not NaN
std::string exact(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::string out;
  append_shortest(out, value);
  return out;
}

/// A natural-unit value in `units`: the shortest text of the value that reads back to it, at 15
/// significant digits where one does (a speed given as 100 m/s is written 100).
double value_in(double natural, Dimension dimension, UnitSystem units) {
  const double value = from_natural(natural, dimension, units);
  if (!std::isfinite(value)) return value;
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.15g", value);
  const double rounded = std::strtod(text.data(), nullptr);
  return to_natural(rounded, dimension, units) == natural ? rounded : value;
}
std::string number_in(double natural, Dimension dimension, UnitSystem units) {
  return exact(value_in(natural, dimension, units));
}

/// `value` with 6 significant digits, for people (the CSV files keep every digit); ±inf as ±∞.
std::string readable(double value) {
  if (std::isinf(value)) return value > 0 ? "∞" : "-∞";
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.6g", value == 0.0 ? 0.0 : value);
  return text.data();
}

/// A CSV field: quoted (RFC 4180) only if it holds a comma, a quote or a line break.
std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + '"';
}

// ---- the command line -------------------------------------------------------------------

/// The items of a comma-separated list, blanks trimmed. \throws usage error on an empty item
std::vector<std::string> split_list(const std::string& text, std::string_view option) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    std::string item = text.substr(start, end - start);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (item.empty())
      throw usage_error("compare", std::string(option) + " expects a comma-separated list, got '" + text + "'");
    items.push_back(std::move(item));
    if (end == text.size()) return items;
    start = end + 1;
  }
}

/// An impact speed from `option`'s value, in the units of the scene (m/s in an SI scene, else
/// units of c), returned in natural units.
double impact_speed(const std::string& text, std::string_view option, UnitSystem units) {
  const std::optional<double> v = parse_number(text);
  const double c = from_natural(1.0, Dimension::velocity, units);
  if (!v || !(*v > 0.0 && *v < c))
    throw usage_error("compare", std::string(option) + ": an impact speed must be a number in (0, " + exact(c) + ") (" +
                                     (units == UnitSystem::si ? "m/s: the scene is in SI units" : "units of c") +
                                     "), got '" + text + "'");
  return to_natural(*v, Dimension::velocity, units);
}

/// The materials to compare: those --materials names (an unknown name exits 2 with the
/// closest match), else every registered one.
std::vector<const MaterialInfo*> selected_materials(const Arguments& args) {
  const MaterialRegistry& registry = MaterialRegistry::instance();
  const std::optional<std::string> named = args.value("--materials");
  std::vector<const MaterialInfo*> selected;
  for (const std::string& name : named ? split_list(*named, "--materials") : registry.names()) {
    try {
      const MaterialInfo* info = &registry.at(name);
      if (std::find(selected.begin(), selected.end(), info) == selected.end()) selected.push_back(info);
    } catch (const std::invalid_argument& e) {  // names the closest match and lists the registered ones
      throw CommandError(kExitInvalidInput, std::string("--materials: ") + e.what());
    }
  }
  return selected;
}

/// The speeds of impact.csv (natural units): --speeds, else v = k/100, k = 1..99.
std::vector<double> impact_speeds(const Arguments& args, UnitSystem units) {
  std::vector<double> speeds;
  if (const std::optional<std::string> given = args.value("--speeds")) {
    for (const std::string& v : split_list(*given, "--speeds")) speeds.push_back(impact_speed(v, "--speeds", units));
  } else {
    for (int k = 1; k < kDefaultSpeedSteps; ++k) speeds.push_back(static_cast<double>(k) / kDefaultSpeedSteps);
  }
  return speeds;
}

/// `--param model.name=value`.
struct ParameterOverride {
  std::string model;
  std::string name;
  std::string value;
};

std::vector<ParameterOverride> parameter_overrides(const Arguments& args) {
  std::vector<ParameterOverride> overrides;
  for (const std::string& text : args.values("--param")) {
    const std::size_t dot = text.find('.'), equals = text.find('=');
    if (dot == std::string::npos || equals == std::string::npos || dot == 0 || dot + 1 >= equals)
      throw usage_error("compare", "--param expects model.name=value (e.g. hooke.wave_speed=0.3), got '" + text + "'");
    overrides.push_back({text.substr(0, dot), text.substr(dot + 1, equals - dot - 1), text.substr(equals + 1)});
  }
  return overrides;
}

/// Checks that each --param names a compared material and one of its declared parameters,
/// once. \throws CommandError (exit 2) naming the closest match
void check_overrides(const std::vector<ParameterOverride>& overrides,
                     const std::vector<const MaterialInfo*>& selected) {
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    const ParameterOverride& o = overrides[i];
    const std::string option = "--param " + o.model + "." + o.name;
    for (std::size_t j = 0; j < i; ++j)
      if (overrides[j].model == o.model && overrides[j].name == o.name)
        throw usage_error("compare", option + " is given twice");

    const auto info =
        std::find_if(selected.begin(), selected.end(), [&](const MaterialInfo* m) { return m->name == o.model; });
    if (info == selected.end()) {
      std::vector<std::string> names;
      for (const MaterialInfo* m : selected) names.push_back(m->name);
      const std::string near = closest_match(o.model, names);
      throw CommandError(kExitInvalidInput, option + ": '" + o.model + "' is not among the materials compared" +
                                                (near.empty() ? std::string() : " (did you mean '" + near + "'?)"));
    }
    std::vector<std::string> declared;
    for (const ParameterSpec& p : (*info)->parameters) declared.push_back(p.name);
    if (std::find(declared.begin(), declared.end(), o.name) == declared.end()) {
      const std::string near = closest_match(o.name, declared);
      std::string message = option + ": " + o.model + " has no parameter '" + o.name + "'";
      if (!near.empty()) message += " (did you mean '" + near + "'?)";
      message += "; its parameters:";
      for (const std::string& d : declared) message += " " + d;
      throw CommandError(kExitInvalidInput, message);
    }
  }
}

// ---- the materials and their parameters ---------------------------------------------------

/// A material set up for the comparison.
struct Candidate {
  const MaterialInfo* info = nullptr;
  std::string name;  ///< the model, or the scene's name for the material (--scene)
  std::shared_ptr<const Material> material;
  std::string parameters;          ///< "wave_speed=0.5;..." (rest_density has its own column)
  std::vector<std::string> notes;  ///< values chosen where the material declares no default
};

/// A value for a required number that has no default: the midpoint of a bounded range,
/// else 1 if the range allows it, else one unit inside its bound. With the reason.
std::pair<double, std::string> representative_value(const ParameterSpec& p) {
  if (p.lower && p.upper) return {0.5 * (p.lower->value + p.upper->value), "the midpoint of " + p.range_text()};
  if (p.range_violation(1.0).empty())
    return {1.0, "1, inside " + (p.range_text().empty() ? "any range" : p.range_text())};
  if (p.lower) return {p.lower->value + 1.0, "one unit above the bound " + p.range_text()};
  return {p.upper->value - 1.0, "one unit below the bound " + p.range_text()};
}

/// Builds `info`'s material with the given, declared, or representative parameter values.
/// \throws CommandError (exit 2) on an invalid --param; std::invalid_argument (message
/// ready for a user) if the material cannot be built.
Candidate set_up(const MaterialInfo& info, const std::vector<ParameterOverride>& overrides) {
  Candidate c;
  c.info = &info;
  c.name = info.name;
  ParameterValues values;
  for (const ParameterSpec& spec : info.parameters) {
    const auto given = std::find_if(overrides.begin(), overrides.end(), [&](const ParameterOverride& o) {
      return o.model == info.name && o.name == spec.name;
    });
    std::string text;
    if (given != overrides.end()) {
      if (spec.type == ParameterType::text) {
        values.set(spec.name, given->value);
        text = given->value;
      } else {
        const std::optional<double> v = parse_number(given->value);
        const std::string rule = v ? spec.range_violation(*v) : std::string("must be a number");
        if (!rule.empty())
          throw CommandError(kExitInvalidInput, "--param " + info.name + "." + spec.name + "=" + given->value + ": " +
                                                    spec.name + " " + rule);
        values.set(spec.name, *v);
        text = exact(*v);
      }
    } else if (spec.default_number) {
      values.set(spec.name, *spec.default_number);
      text = exact(*spec.default_number);
    } else if (spec.default_text) {
      values.set(spec.name, *spec.default_text);
      text = *spec.default_text;
    } else if (spec.required && spec.type == ParameterType::number) {
      const auto [v, why] = representative_value(spec);
      values.set(spec.name, v);
      text = exact(v);
      c.notes.push_back(info.name + "." + spec.name + " = " + text + ": required, no default; " + why +
                        " (set it with --param " + info.name + "." + spec.name + "=...)");
    } else if (spec.required) {
      throw std::invalid_argument(info.name + ": the text parameter '" + spec.name +
                                  "' is required and has no default; give it with --param " + info.name + "." +
                                  spec.name + "=...");
    } else {
      continue;  // optional, no default: left out, as a scene may leave it out
    }
    if (spec.name != "rest_density") c.parameters += (c.parameters.empty() ? "" : ";") + spec.name + "=" + text;
  }
  try {
    c.material = build_material(info, values);
  } catch (const std::exception& e) {
    throw std::invalid_argument(info.name + " cannot be built with " +
                                (c.parameters.empty() ? std::string("its defaults") : c.parameters) + ": " + e.what());
  }
  if (!c.material) throw std::invalid_argument(info.name + ": the registry's factory returned no material");
  return c;
}

/// A material's parameters ("wave_speed=1.7e-05;...", natural units) in `units`, each number
/// by its declared dimension: the value that reads back to the same natural one, at 15
/// significant digits where one does ("wave_speed=5100", not 5100.000000000001).
std::string parameters_in(const MaterialInfo& info, const std::string& natural, UnitSystem units) {
  if (units == UnitSystem::natural) return natural;
  std::string out;
  std::size_t start = 0;
  while (start <= natural.size() && !natural.empty()) {
    const std::size_t end = std::min(natural.find(';', start), natural.size());
    std::string item = natural.substr(start, end - start);
    const std::size_t eq = item.find('=');
    if (eq != std::string::npos) {
      const std::string key = item.substr(0, eq);
      const auto spec = std::find_if(info.parameters.begin(), info.parameters.end(),
                                     [&key](const ParameterSpec& p) { return p.name == key; });
      const std::optional<double> value = parse_number(item.substr(eq + 1));
      if (spec != info.parameters.end() && value) item = key + "=" + number_in(*value, spec->dimension, units);
    }
    out += (out.empty() ? "" : ";") + item;
    start = end + 1;
  }
  return out;
}

/// The materials a scene file declares, as it builds them (its parameters, checked as a run
/// checks them), under the scene's names; --materials picks some of them by those names.
/// `units` becomes the scene's.
std::vector<Candidate> scene_candidates(const std::string& path, const Arguments& args, UnitSystem& units) {
  const Scene scene = load_scene_file(path);  // an invalid scene: InputError, file/line/key
  units = scene.units;
  std::vector<std::string> wanted;
  if (const std::optional<std::string> named = args.value("--materials")) wanted = split_list(*named, "--materials");
  std::vector<std::string> declared;
  for (const auto& [name, decl] : scene.materials) declared.push_back(name);
  for (const std::string& name : wanted)
    if (scene.materials.count(name) == 0) {
      const std::string near = closest_match(name, declared);
      throw CommandError(
          kExitInvalidInput, "--materials: " + path + " declares no material '" + name + "'" +
                                 (near.empty() ? "" : " (did you mean '" + near + "'?)") + "; it declares:" + [&] {
                                   std::string list;
                                   for (const std::string& d : declared) list += " " + d;
                                   return list;
                                 }());
    }
  std::vector<Candidate> out;
  for (const auto& [name, decl] : scene.materials) {
    if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), name) == wanted.end()) continue;
    Candidate c;
    c.info = &MaterialRegistry::instance().at(decl.model);
    c.name = name;
    c.material = decl.material;
    c.parameters =
        "model=" + decl.model + (decl.parameters.empty() ? "" : ";" + parameters_in(*c.info, decl.parameters, units));
    out.push_back(std::move(c));
  }
  return out;
}

// ---- the physics --------------------------------------------------------------------------

struct CurvePoint {
  double s = 1.0, p = 0.0, e = 0.0, cs = 0.0;
};

/// A compression from the unstrained bar at rest to stretch s (pressure p): the speed the
/// material behind takes through a shock (its Hugoniot) and through a smooth compression wave
/// (its isentrope).
struct WavePoint {
  double s = 1.0, p = 0.0, v_shock = 0.0, v_smooth = 0.0;
};

/// Everything compare reports about one material.
struct Comparison {
  const Candidate* candidate = nullptr;
  double cs_unstrained = 0.0;  ///< c_s at s = 1
  double max_pressure = 0.0;
  double max_tension = 0.0;
  bool parts_at_max_tension = false;  ///< the maximum tension is the cavitation pressure
  bool linearly_degenerate = false;
  std::optional<Impact> impact;       ///< at the --impact-speed; none if crushed
  std::optional<double> crush_speed;  ///< none if no impact speed crushes it
  std::vector<CurvePoint> curve;      ///< admissible stretches of the grid only
  std::vector<WavePoint> waves;       ///< the compressions of the grid (s < 1) a shock reaches
  std::vector<Impact> impacts;        ///< the speeds with a classical solution only
  std::vector<std::string> warnings;
};

/// p, e and c_s at s, or nullopt if s is not admissible or the material fails there.
std::optional<CurvePoint> curve_point(const Material& material, Stretch s) {
  if (!material.admissible().contains(s)) return std::nullopt;
  try {
    const CurvePoint point{s.value(), material.pressure(s), material.energy_density(s), material.sound_speed(s)};
    if (std::isfinite(point.s) && std::isfinite(point.p) && std::isfinite(point.e) && std::isfinite(point.cs))
      return point;
  } catch (const std::exception&) {  // a numeric material whose quadrature failed
  }
  return std::nullopt;
}

Comparison compare(const Candidate& c, double impact_speed, const std::vector<double>& speeds) {
  const Material& m = *c.material;
  Comparison out;
  out.candidate = &c;
  out.max_pressure = m.max_pressure();
  out.max_tension = m.max_tension();
  out.parts_at_max_tension = out.max_tension == m.cavitation_pressure();
  out.linearly_degenerate = m.linearly_degenerate();
  const std::optional<CurvePoint> natural = curve_point(m, Stretch::natural());
  if (!natural) throw NumericalError(c.name + ": the natural state s = 1 is not admissible or not finite");
  out.cs_unstrained = natural->cs;

  const double step = std::log(kStretchSpan) / kStretchStepsPerSide;
  int skipped = 0;
  for (int k = -kStretchStepsPerSide; k <= kStretchStepsPerSide; ++k) {
    const Stretch s = Stretch::from_log(k * step);
    if (const std::optional<CurvePoint> point = curve_point(m, s)) {
      out.curve.push_back(*point);
    } else if (m.admissible().contains(s)) {
      ++skipped;
    }
  }
  if (skipped > 0)
    out.warnings.push_back(c.name + ": " + std::to_string(skipped) +
                           " admissible stretches of the grid left out: p, e or c_s failed there");

  // From rest to each compression of the grid, through a shock and through a smooth wave.
  for (const CurvePoint& q : out.curve) {
    if (q.s >= 1.0) continue;
    const Stretch s = Stretch::from_value(q.s);
    if (const std::optional<double> shock = hugoniot_speed(m, s))
      out.waves.push_back(WavePoint{q.s, q.p, *shock, isentrope_speed(m, s)});
  }

  const auto impact_at = [&](double v) -> std::optional<Impact> {
    const ImpactOutcome outcome = wall_impact(m, v);
    if (outcome.status == Status::ok) return outcome.impact;
    if (outcome.status != Status::out_of_range)
      out.warnings.push_back(c.name + ": wall impact at v = " + exact(v) + " left out: the Riemann solver " +
                             "reported '" + std::string(to_string(outcome.status)) + "'");
    return std::nullopt;
  };
  out.impact = impact_at(impact_speed);
  for (const double v : speeds)
    if (const std::optional<Impact> impact = impact_at(v)) out.impacts.push_back(*impact);
  out.crush_speed = crush_speed(m);
  return out;
}

/// `r` with every speed, pressure and energy density in `units` (the tables, charts and
/// summary print what they are given).
Comparison in_units(Comparison r, UnitSystem units) {
  const auto v = [units](double& x) { x = value_in(x, Dimension::velocity, units); };
  const auto p = [units](double& x) { x = value_in(x, Dimension::pressure, units); };
  v(r.cs_unstrained);
  p(r.max_pressure);
  p(r.max_tension);
  if (r.impact) {
    v(r.impact->v);
    p(r.impact->p);
    v(r.impact->front_speed);
  }
  for (Impact& i : r.impacts) {
    v(i.v);
    p(i.p);
    v(i.front_speed);
  }
  if (r.crush_speed) v(*r.crush_speed);
  for (CurvePoint& q : r.curve) {
    p(q.p);
    p(q.e);
    v(q.cs);
  }
  for (WavePoint& w : r.waves) {
    p(w.p);
    v(w.v_shock);
    v(w.v_smooth);
  }
  return r;
}

// ---- the tables ----------------------------------------------------------------------------

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw CommandError(kExitInternal, "cannot write " + path.string());
}

/// materials.csv: one row per material. Empty cells: no classical solution at the impact
/// speed (impact_s, impact_p, impact_front_speed), or no speed that crushes it
/// (crush_speed); unbounded limits are ±inf.
std::string materials_csv(const std::vector<Comparison>& rows, double impact_speed, UnitSystem units) {
  std::string out =
      "material,parameters,rest_density,cs_unstrained,max_pressure,max_tension,linearly_degenerate,"
      "impact_v,impact_s,impact_p,impact_front_speed,crush_speed\n";
  for (const Comparison& r : rows) {
    const Candidate& c = *r.candidate;
    out += csv_field(c.name) + "," + csv_field(c.parameters) + "," + exact(c.material->rest_density()) + "," +
           exact(r.cs_unstrained) + "," + exact(r.max_pressure) + "," + exact(r.max_tension) + "," +
           (r.linearly_degenerate ? "true" : "false") + "," + number_in(impact_speed, Dimension::velocity, units) + ",";
    out += r.impact ? exact(r.impact->s) + "," + exact(r.impact->p) + "," + exact(r.impact->front_speed)
                    : std::string(",,");
    out += "," + (r.crush_speed ? exact(*r.crush_speed) : std::string()) + "\n";
  }
  return out;
}

std::string stress_strain_csv(const std::vector<Comparison>& rows) {
  std::string out = "material,s,p,e,cs\n";
  for (const Comparison& r : rows)
    for (const CurvePoint& q : r.curve)
      out += csv_field(r.candidate->name) + "," + exact(q.s) + "," + exact(q.p) + "," + exact(q.e) + "," + exact(q.cs) +
             "\n";
  return out;
}

/// hugoniot.csv: the compressions from rest, by a shock and by a smooth wave.
std::string hugoniot_csv(const std::vector<Comparison>& rows) {
  std::string out = "material,s,p,v_shock,v_smooth\n";
  for (const Comparison& r : rows)
    for (const WavePoint& w : r.waves)
      out += csv_field(r.candidate->name) + "," + exact(w.s) + "," + exact(w.p) + "," + exact(w.v_shock) + "," +
             exact(w.v_smooth) + "\n";
  return out;
}

std::string impact_csv(const std::vector<Comparison>& rows) {
  std::string out = "material,v,s,p,front_speed\n";
  for (const Comparison& r : rows)
    for (const Impact& i : r.impacts)
      out += csv_field(r.candidate->name) + "," + exact(i.v) + "," + exact(i.s) + "," + exact(i.p) + "," +
             exact(i.front_speed) + "\n";
  return out;
}

// ---- the charts ----------------------------------------------------------------------------

std::string colour(std::size_t i) { return std::string(kColours[i % std::size(kColours)]); }

/// The key entry of a material: its name and parameters.
std::string legend(const Comparison& r) {
  const Candidate& c = *r.candidate;
  return c.parameters.empty() ? c.name : c.name + " (" + c.parameters + ")";
}

std::string chart_header(std::string_view what, std::string_view name, int width, int height) {
  std::string out = gnuplot_comment(what);
  out += "# Written by `rigidity compare`; edit and rerun from this directory: gnuplot " + std::string(name) + ".gp\n";
  out += "set terminal pngcairo size " + std::to_string(width) + "," + std::to_string(height) +
         " font 'Sans,11' noenhanced\n";
  out += "set encoding utf8\n";
  out += "set output " + gnuplot_quote(std::string(name) + ".png") + "\n";
  out += "set datafile separator ','\n";
  out += "set datafile missing NaN  # rows of other materials, filtered out as NaN, do not break a line\n";
  out += "set grid lc rgb '#dddddd'\n";
  return out;
}

/// A horizontal dotted line at y (first axis) across the graph, with a label at its left or right end.
std::string limit_line(double y, const std::string& colour_code, const std::string& label, bool at_right) {
  std::string out = "set arrow from graph 0, first " + exact(y) + " to graph 1, first " + exact(y) +
                    " nohead dt (3,4) lw 1.5 lc rgb '" + colour_code + "'\n";
  out += "set label " + gnuplot_quote(label) + " at graph " + (at_right ? "0.98" : "0.02") + ", first " + exact(y) +
         (at_right ? " right offset 0,-0.8" : " left offset 0,0.8") + " front tc rgb '" + colour_code + "'\n";
  return out;
}

/// A vertical dotted line at x (first axis) with a label along it.
std::string limit_line_vertical(double x, const std::string& colour_code, const std::string& label) {
  return "set arrow from first " + exact(x) + ", graph 0 to first " + exact(x) +
         ", graph 1 nohead dt (3,4) lw 1.5 lc rgb '" + colour_code + "'\nset label " + gnuplot_quote(label) +
         " at first " + exact(x) + ", graph 0.5 rotate by 90 center offset 1.2,0 tc rgb '" + colour_code + "'\n";
}

std::string plot_lines(const std::vector<std::string>& elements) {
  std::string out = "plot ";
  for (std::size_t i = 0; i < elements.size(); ++i) out += (i == 0 ? "" : ", \\\n     ") + elements[i];
  return out + "\n";
}

/// One material's rows of a long-form CSV, `using x:(material ? y : NaN)`, in the material's
/// colour; every other material dashed, so that coinciding laws (rigid and rigid_fluid in
/// compression) both show.
std::string material_curve(const std::string& file, const Comparison& r, std::size_t i, int x_column, int y_column) {
  return gnuplot_quote(file) + " skip 1 using " + std::to_string(x_column) + ":(strcol(1) eq " +
         gnuplot_quote(r.candidate->name) + " ? $" + std::to_string(y_column) + " : NaN) with lines lw 2 dt " +
         (i % 2 == 0 ? "1" : "(10,6)") + " lc rgb '" + colour(i) + "' title " + gnuplot_quote(legend(r));
}

std::string stress_strain_chart(const std::vector<Comparison>& rows, UnitSystem units) {
  // The traction side sets the scale: the lowest p on the chart (or the lowest maximum
  // tension), with the compression side shown to three times that depth.
  double depth = 0.0, top_limit = 0.0;
  for (const Comparison& r : rows) {
    for (const CurvePoint& q : r.curve)
      if (q.s <= kChartStretchMax) depth = std::max(depth, -q.p);
    if (std::isfinite(r.max_tension)) depth = std::max(depth, -r.max_tension);
    if (std::isfinite(r.max_pressure)) top_limit = std::max(top_limit, r.max_pressure);
  }
  if (depth == 0.0) depth = from_natural(0.5, Dimension::pressure, units);
  const double y_min = -1.25 * depth, y_max = std::max(3.0 * depth, 1.25 * top_limit);

  std::string out = chart_header(
      "The stress-strain law p(s) of every material, compression (s < 1, p > 0) and traction (s > 1, p < 0), "
      "after Fig. 3 of Brotas & Fernandes (physics/0307019); dotted: each material's maximum pressure and tension.",
      "stress_strain", 1000, 700);
  out += "set title 'Stress-strain law p(s), compression s < 1 and traction s > 1 (after Fig. 3 of physics/0307019)'\n";
  out += "set xlabel 's = proper length / natural length'\n";
  out += units == UnitSystem::si ? "set ylabel 'p  [Pa; compression > 0]'\n"
                                 : "set ylabel 'p  [natural units, c = 1; compression > 0]'\n";
  out += "set xrange [0:" + exact(kChartStretchMax) + "]\n";
  out += "set yrange [" + exact(y_min) + ":" + exact(y_max) + "]\n";
  out += "set xzeroaxis lt -1\n";
  out += "set arrow from 1, graph 0 to 1, graph 1 nohead dt 3 lc rgb '#888888'  # the natural state s = 1\n";
  out += "set key top right box opaque\n";
  std::vector<std::string> elements;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Comparison& r = rows[i];
    const std::string& name = r.candidate->name;
    if (std::isfinite(r.max_pressure) && r.max_pressure <= y_max)
      out += limit_line(r.max_pressure, colour(i), name + ": maximum pressure " + readable(r.max_pressure), false);
    if (std::isfinite(r.max_tension) && r.max_tension >= y_min)
      out += limit_line(
          r.max_tension, colour(i),
          name + (r.parts_at_max_tension ? ": carries no tension below p = " + readable(r.max_tension) + " (it parts)"
                                         : ": maximum tension " + readable(r.max_tension)),
          true);
    elements.push_back(material_curve("stress_strain.csv", r, i, 2, 3));
  }
  return out + plot_lines(elements);
}

std::string sound_speed_chart(const std::vector<Comparison>& rows, UnitSystem units) {
  const std::string c = exact(from_natural(1.0, Dimension::velocity, units));
  std::string out = chart_header("The sound speed c_s(s) = sqrt(dp/de) of every material.", "sound_speed", 1000, 650);
  out += "set title 'Sound speed c_s(s)'\n";
  out += "set xlabel 's = proper length / natural length'\n";
  out += "set ylabel 'c_s  [" + std::string(units == UnitSystem::si ? "m/s" : "c") + "]'\n";
  out += "set xrange [0:" + exact(kChartStretchMax) + "]\n";
  out += "set yrange [0:" + exact(1.1 * from_natural(1.0, Dimension::velocity, units)) + "]\n";
  out += "set arrow from graph 0, first " + c + " to graph 1, first " + c + " nohead lw 1.5 lc rgb '#444444'\n";
  out += "set label 'c' at graph 0.01, first " + c + " offset 0,0.6 tc rgb '#444444'\n";
  out += "set arrow from 1, graph 0 to 1, graph 1 nohead dt 3 lc rgb '#888888'  # the natural state s = 1\n";
  out += "set key bottom right box opaque\n";
  std::vector<std::string> elements;
  for (std::size_t i = 0; i < rows.size(); ++i)
    elements.push_back(material_curve("stress_strain.csv", rows[i], i, 2, 5));
  return out + plot_lines(elements);
}

/// The speed of light in `units` and the unit speeds are printed in.
struct SpeedAxis {
  double c = 1.0;
  std::string unit;
};
SpeedAxis speed_axis(UnitSystem units) {
  return {from_natural(1.0, Dimension::velocity, units), units == UnitSystem::si ? "m/s" : "c"};
}

std::string impact_chart(const std::vector<Comparison>& rows, UnitSystem units) {
  const auto [c, speed_unit] = speed_axis(units);
  std::string out = chart_header(
      "Wall impacts: an unstrained bar at speed v strikes a fixed wall. Pressure and stretch behind the reflected "
      "front and the front's speed relative to the unstrained bar (exact Riemann solver); dotted: maximum pressure "
      "and the speed that crushes the bar.",
      "impact", 1000, 1250);
  out += "set multiplot layout 3,1 title 'Wall impact of an unstrained bar at speed v'\n";
  out += "set xlabel 'v  [" + speed_unit + "]'\n";
  out += "set xrange [0:" + exact(c) + "]\n";
  out += "set key top left box opaque  # in the first panel only: the colours hold for all three\n";
  std::string crush_lines;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].crush_speed)
      crush_lines += limit_line_vertical(*rows[i].crush_speed, colour(i),
                                         rows[i].candidate->name + " crushed at v = " + readable(*rows[i].crush_speed));

  std::vector<std::string> pressure, stretch, front;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].impacts.empty()) continue;
    pressure.push_back(material_curve("impact.csv", rows[i], i, 2, 4));
    stretch.push_back(material_curve("impact.csv", rows[i], i, 2, 3));
    front.push_back(material_curve("impact.csv", rows[i], i, 2, 5));
  }
  if (pressure.empty()) return out + "unset multiplot\n";  // no speed has a solution: empty panels are not drawn

  out += "set title 'Pressure behind the front'\nset ylabel 'p  [" +
         std::string(units == UnitSystem::si ? "Pa" : "rho00 c^2") + "]'\nset logscale y\n" + crush_lines;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (std::isfinite(rows[i].max_pressure))
      out += limit_line(rows[i].max_pressure, colour(i),
                        rows[i].candidate->name + ": maximum pressure " + readable(rows[i].max_pressure), true);
  out += plot_lines(pressure);
  out += "unset logscale y\nunset label\nunset arrow\nunset key\n";
  out += "set title 'Stretch behind the front'\nset ylabel 's'\nset yrange [0:1.05]\n" + crush_lines;
  out += plot_lines(stretch);
  out += "unset label\nunset arrow\n";
  out += "set title 'Front speed relative to the unstrained bar'\nset ylabel 'u  [" + speed_unit +
         "]'\nset yrange [0:" + exact(1.05 * c) + "]\n" + crush_lines;
  out += plot_lines(front);
  return out + "unset multiplot\n";
}

std::string hugoniot_chart(const std::vector<Comparison>& rows, UnitSystem units) {
  const auto [c, speed_unit] = speed_axis(units);
  std::string out = chart_header(
      "The Hugoniot against the isentrope: the pressure a bar at rest is compressed to, against the speed its "
      "material takes, through a shock (solid) and through a smooth compression wave (dashed). They coincide for "
      "laws whose every wave is a jump (linearly degenerate: rigid, hooke, rigid_fluid).",
      "hugoniot", 1000, 700);
  out += "set title 'Hugoniot (shock, solid) against isentrope (smooth wave, dashed): compression from rest'\n";
  out += "set xlabel 'speed of the material behind the wave  [" + speed_unit + "]'\n";
  out += "set ylabel 'p  [" + std::string(units == UnitSystem::si ? "Pa" : "rho00 c^2") + "]'\n";
  out += "set xrange [0:" + exact(c) + "]\nset logscale y\nset key top left box opaque\n";
  std::vector<std::string> elements;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].waves.empty()) continue;
    const std::string name = gnuplot_quote(rows[i].candidate->name);
    const std::string data = gnuplot_quote("hugoniot.csv") + " skip 1 using ";
    elements.push_back(data + "4:(strcol(1) eq " + name + " ? $3 : NaN) with lines lw 2 lc rgb '" + colour(i) +
                       "' title " + gnuplot_quote(legend(rows[i])));
    elements.push_back(data + "5:(strcol(1) eq " + name + " ? $3 : NaN) with lines lw 2 dt (6,5) lc rgb '" + colour(i) +
                       "' notitle");
  }
  return out + plot_lines(elements);
}

// ---- the summary ------------------------------------------------------------------------------

void print_summary(std::ostream& out, const std::vector<Comparison>& rows, double impact_speed, UnitSystem units,
                   const std::vector<std::string>& notes, const fs::path& dir, const std::vector<std::string>& files) {
  const std::string at = " at v = " + readable(value_in(impact_speed, Dimension::velocity, units));
  out << "## rigidity compare: " << rows.size() << (rows.size() == 1 ? " material" : " materials") << "\n\n";
  out << (units == UnitSystem::si ? "SI units (speeds in m/s, pressures in Pa, densities in kg/m^3)"
                                  : "Natural units (c = 1)")
      << ". Wall impact: an unstrained bar at speed v strikes a fixed wall; s and p behind the\n"
         "reflected front (exact Riemann solver), u its speed relative to the unstrained bar; crushed: no classical\n"
         "solution.\n\n";
  out << "| material | parameters | rest density | c_s(1) | max pressure | max tension | linearly degenerate | s" << at
      << " | p" << at << " | u" << at << " | crushed from v |\n";
  out << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Comparison& r : rows) {
    const Candidate& c = *r.candidate;
    out << "| " << c.name << " | " << (c.parameters.empty() ? "-" : c.parameters) << " | "
        << readable(c.material->rest_density()) << " | " << readable(r.cs_unstrained) << " | "
        << readable(r.max_pressure) << " | " << readable(r.max_tension) << " | "
        << (r.linearly_degenerate ? "yes" : "no") << " | ";
    if (r.impact) {
      out << readable(r.impact->s) << " | " << readable(r.impact->p) << " | " << readable(r.impact->front_speed);
    } else {
      out << "crushed | crushed | crushed";
    }
    out << " | " << (r.crush_speed ? readable(*r.crush_speed) : std::string("-")) << " |\n";
  }
  if (!notes.empty()) {
    out << "\nNotes:\n";
    for (const std::string& note : notes) out << "- " << note << "\n";
  }
  out << "\nFiles in " << dir.string() << (dir.string().ends_with('/') ? "" : "/") << ":";
  for (std::size_t i = 0; i < files.size(); ++i) out << (i == 0 ? " " : ", ") << files[i];
  out << "\n";
}

}  // namespace

int compare_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--materials", true},    {"--out", true},         {"--speeds", true},
                                            {"--impact-speed", true}, {"--param", true, true}, {"--scene", true}};
  const Arguments parsed = parse_arguments("compare", args, kOptions);
  if (parsed.help) {
    out << help("compare");
    return kExitOk;
  }
  if (!parsed.positional.empty())
    throw usage_error("compare", "compare takes no positional argument, got '" + parsed.positional[0] + "'");

  // Everything on the command line is checked before anything is computed or written.
  const bool named = parsed.has("--materials");
  const std::optional<std::string> scene_file = parsed.value("--scene");
  if (scene_file && parsed.has("--param"))
    throw usage_error("compare", "--param and --scene exclude each other: the scene file gives the parameters");
  const std::vector<const MaterialInfo*> selected =
      scene_file ? std::vector<const MaterialInfo*>{} : selected_materials(parsed);
  // The speeds are in the scene's units: m/s for an SI scene.
  UnitSystem units = UnitSystem::natural;
  std::vector<Candidate> candidates;
  if (scene_file) candidates = scene_candidates(*scene_file, parsed, units);
  const double impact_v = parsed.has("--impact-speed")
                              ? impact_speed(*parsed.value("--impact-speed"), "--impact-speed", units)
                              : kDefaultImpactSpeed;
  const std::vector<double> speeds = impact_speeds(parsed, units);
  const std::vector<ParameterOverride> overrides = parameter_overrides(parsed);
  check_overrides(overrides, selected);

  // A material named on the command line must be set up; one found in the registry is
  // skipped, with a note, if it cannot be (say, a required text parameter without default).
  std::vector<std::string> notes;
  const auto warn = [&notes](const std::string& warning) {
    notes.push_back(warning);
    std::cerr << "warning: " << warning << "\n";
  };
  for (const MaterialInfo* info : selected) {
    try {
      candidates.push_back(set_up(*info, overrides));
      notes.insert(notes.end(), candidates.back().notes.begin(), candidates.back().notes.end());
    } catch (const std::invalid_argument& e) {
      if (named) throw CommandError(kExitInvalidInput, e.what());
      warn("skipped " + std::string(e.what()));
    }
  }
  if (candidates.empty()) throw CommandError(kExitInvalidInput, "no material to compare");

  std::vector<Comparison> rows;
  for (const Candidate& c : candidates) {
    rows.push_back(in_units(compare(c, impact_v, speeds), units));
    for (const std::string& warning : rows.back().warnings) warn(warning);
  }

  const fs::path dir = parsed.value("--out").value_or(std::string(kDefaultOut));
  std::error_code error;
  fs::create_directories(dir, error);
  if (!fs::is_directory(dir, error))
    throw CommandError(kExitInvalidInput, "cannot create the output directory " + dir.string());
  write_file(dir / "materials.csv", materials_csv(rows, impact_v, units));
  write_file(dir / "stress_strain.csv", stress_strain_csv(rows));
  write_file(dir / "impact.csv", impact_csv(rows));
  write_file(dir / "hugoniot.csv", hugoniot_csv(rows));
  std::vector<std::string> files{"materials.csv", "stress_strain.csv", "impact.csv", "hugoniot.csv"};

  std::vector<std::pair<std::string, std::string>> charts{{"stress_strain", stress_strain_chart(rows, units)},
                                                          {"sound_speed", sound_speed_chart(rows, units)}};
  if (std::any_of(rows.begin(), rows.end(), [](const Comparison& r) { return !r.waves.empty(); }))
    charts.emplace_back("hugoniot", hugoniot_chart(rows, units));
  if (std::any_of(rows.begin(), rows.end(), [](const Comparison& r) { return !r.impacts.empty(); })) {
    charts.emplace_back("impact", impact_chart(rows, units));
  } else {
    notes.push_back("no impact chart: no material has a classical solution at the speeds asked for");
  }
  const fs::path gnuplot = find_gnuplot();
  if (gnuplot.empty()) {
    for (const auto& [name, script] : charts) write_file(dir / (name + ".gp"), script);
    warn(
        "gnuplot not found on PATH: the charts were not drawn, only their scripts written; install gnuplot "
        "(Debian: apt-get install gnuplot-nox) and run them in " +
        dir.string() + " (gnuplot NAME.gp)");
  } else {
    for (const auto& [name, script] : charts) {
      render_gnuplot(gnuplot, dir, name, script);
      files.push_back(name + ".png");
    }
  }
  for (const auto& chart : charts) files.push_back(chart.first + ".gp");

  print_summary(out, rows, impact_v, units, notes, dir, files);
  return kExitOk;
}

}  // namespace rigidity::cli
