// The strict scene loader (docs/scenes.md): text → one compact tree in one pass (scene_tree; the
// guards and --set overrides in scene_input) → values checked against the schema
// (scene_checker, scene_schema) → the Scene, after the rules that relate keys to each other
// (this file): references between names, bodies in order and not overlapping, walls outside
// the bodies, admissible initial states, outputs within the bodies and the time span.

#include "rigidity/scene_loader.hpp"

#include <muParser.h>
#include <yaml-cpp/exceptions.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "rigidity/default_scene.hpp"
#include "rigidity/number_text.hpp"
#include "rigidity/plugins.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/scene_schema.hpp"
#include "rigidity/spelling.hpp"
#include "scene_checker.hpp"
#include "scene_text.hpp"

namespace rigidity {

namespace {

using detail::Checked;
using detail::Checker;
using detail::format_number;
using detail::NumberLiteral;
using detail::NumberSyntax;
using detail::parse_number;
using detail::SceneTree;
using detail::Sources;
using detail::TreeValue;

/// Most samples a probe may take over the run (t_end / every).
constexpr double kMaxProbeSamples = 1.0e7;
/// Segments a body's profile is run as unless it says (profile_segments).
constexpr int kProfileSegments = 100;
/// Most snapshot times `every` may give (each a full sampling of the bodies).
constexpr double kMaxSnapshotTimes = 1.0e5;

/// Ends that differ by rounding only (relative 1e-12) touch: a body written to start
/// where the previous one ends, at x = l·s/γ computed by hand, is in contact with it.
/// The loader then moves the later end onto the earlier one, so that the Scene's
/// bodies never overlap, not even by an ulp.
bool within_rounding(double a, double b, double scale) {
  return std::abs(a - b) <= 1.0e-12 * std::max({std::abs(a), std::abs(b), scale});
}

class SceneBuilder {
 public:
  SceneBuilder(Checker& checker, const Sources& sources, UnitSystem units, std::filesystem::path directory)
      : checker_(checker), sources_(sources), units_(units), directory_(std::move(directory)) {}

  Scene build(Checked& root) {
    Scene scene;
    scene.name = root["name"].word;
    scene.source = sources_.file();
    scene.units = units_;
    for (const Checked& plugin : root["plugins"].entries) scene.plugins.push_back(plugin.word);
    // First: the front tracker refuses laws with an inflection, and a linear piston ramp is
    // stepped at the tolerance.
    read_solver(root["solver"], scene.solver);
    read_materials(root["materials"], scene);
    read_bodies(root["bodies"], scene);
    scene.t_end = root["time"]["end"].number;
    if (!scene.solver.tolerance_given && !scene.linearly_degenerate())
      scene.solver.tolerance = kNonlinearDefaultTolerance;
    read_boundary(root["boundaries"]["left"], true, scene, scene.left);
    read_boundary(root["boundaries"]["right"], false, scene, scene.right);
    read_outputs(root["outputs"], root["time"]["end"], scene);
    return scene;
  }

 private:
  [[nodiscard]] SourceLocation where(const Checked& c) const { return sources_.locate(c.path(), c.mark); }

  /// `ref` names one of `names`; else an error with the closest one.
  void require_reference(const Checked& ref, const std::set<std::string>& names, const std::string& what) const {
    if (names.count(ref.word) != 0) return;
    const std::vector<std::string> candidates(names.begin(), names.end());
    const std::string near = closest_match(ref.word, candidates);
    checker_.fail(ref, "unknown " + what + " '" + ref.word + "'" +
                           (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                           "; declared: " + detail::join(candidates));
  }

  void read_materials(const Checked& materials, Scene& scene) {
    for (const Checked& entry : materials.entries) {
      const std::string& model = entry["model"].word;
      const MaterialInfo& info = MaterialRegistry::instance().at(model);  // the schema admits registered models only
      ParameterValues values;
      values.set_directory(directory_.string());  // a relative file name (a table) is the scene's
      values.set_units(units_);                   // and so are the units of its numbers
      std::string text;
      for (const ParameterSpec& spec : info.parameters) {
        const Checked* value = entry.find(spec.name);
        if (value == nullptr) continue;             // optional and without default: the material decides
        if (spec.type == ParameterType::numbers) {  // a formula's parameters, "KEY.NAME"
          for (const Checked& named : value->entries) {
            const double number = declared_parameter(named);
            values.set(spec.name + "." + named.name, number);
            text += (text.empty() ? "" : ";") + spec.name + "." + named.name + "=" + shortest(number);
          }
          continue;
        }
        if (spec.type == ParameterType::number)
          values.set(spec.name, value->number);
        else
          values.set(spec.name, value->word);
        if (spec.name != "rest_density")
          text += (text.empty() ? "" : ";") + spec.name + "=" +
                  (spec.type == ParameterType::number ? shortest(value->number) : value->word);
      }
      std::shared_ptr<const Material> material;
      try {
        material = build_material(info, values);  // hyperbolic and causal with these parameters
      } catch (const ParameterError& e) {         // at the key it names: "pressure", "parameters.rho"
        const Checked* at = &entry;
        std::string_view rest = e.parameter();
        while (at != nullptr && !rest.empty()) {
          const std::size_t dot = rest.find('.');
          const Checked* next = at->find(rest.substr(0, dot));
          if (next == nullptr) break;
          at = next;
          rest = dot == std::string_view::npos ? std::string_view() : rest.substr(dot + 1);
        }
        checker_.fail(*at, "material '" + entry.name + "' (" + model + "): " + e.what());
      } catch (const std::invalid_argument& e) {
        checker_.fail(entry, "material '" + entry.name + "' (" + model + "): " + e.what());
      }
      scene.materials.emplace(entry.name, MaterialDecl{entry.name, model, std::move(material), where(entry), text});
      material_names_.insert(entry.name);
    }
  }

  /// The value of a formula's parameter, `k: 2.0` or `k: {value: 2.0e9, unit: pressure, min: 0}`, as
  /// written (the expression is evaluated in the scene's units); a declared one is first compared
  /// with its range in natural units, an error naming its value, its bounds and their unit.
  [[nodiscard]] double declared_parameter(const Checked& named) const {
    if (named.kind != schema::Kind::map) return named.number;
    const Checked& value = named["value"];
    const Dimension dimension = dimension_named(named["unit"].word);
    const auto natural = [&](const Checked& c) { return to_natural(c.as_written, dimension, units_); };
    const auto with_unit = [&](const Checked& c) {
      const std::string_view symbol = unit_symbol(dimension, units_);
      return format_number(c.as_written) + (dimension == Dimension::dimensionless ? "" : " " + std::string(symbol));
    };
    const Checked* min = named.find("min");
    const Checked* max = named.find("max");
    if (min != nullptr && max != nullptr && !(natural(*min) <= natural(*max)))
      checker_.fail(*max,
                    "parameter '" + named.name + "': max = " + with_unit(*max) + " is below min = " + with_unit(*min));
    if (min != nullptr && !(natural(value) >= natural(*min)))
      checker_.fail(value, "parameter '" + named.name + "' = " + with_unit(value) +
                               " is below its declared min = " + with_unit(*min));
    if (max != nullptr && !(natural(value) <= natural(*max)))
      checker_.fail(value, "parameter '" + named.name + "' = " + with_unit(value) +
                               " is above its declared max = " + with_unit(*max));
    return value.as_written;
  }

  /// φ of a uniform state given by velocity, rapidity or gamma (+ direction).
  static double rapidity_of(const Checked& state) {
    if (const Checked* gamma = state.find("gamma")) return state["direction"].number * std::acosh(gamma->number);
    if (const Checked* rapidity = state.find("rapidity")) return rapidity->number;
    return std::atanh(state["velocity"].number);
  }

  Segment read_segment(const Checked& state, const std::string& material, const Scene& scene) const {
    Segment segment;
    segment.length = state["length"].number;
    segment.rapidity = rapidity_of(state);
    segment.stretch = Stretch::from_value(state["stretch"].number);
    segment.material = material;
    const std::string violation = scene.materials.at(material).material->admissibility_violation(segment.stretch);
    if (!violation.empty()) checker_.fail(state["stretch"], "inadmissible initial state: " + violation);
    return segment;
  }

  /// A body's initial data as expressions of its label X (velocity_profile, stretch_profile;
  /// what is not a profile is uniform as written): the staircase of their values at the
  /// middles of profile_segments equal segments of `length`. Each expression is evaluated in
  /// the scene's units (X and l0 lengths, v a velocity); an error names the key, and the label
  /// where a value is not admissible.
  void read_profile(const Checked& b, const Scene& scene, BodyDecl& body) const {
    const std::string& material = b["material"].word;
    const double l0 = b["length"].number;
    const Checked* segments = b.find("profile_segments");
    const int count = segments != nullptr ? static_cast<int>(segments->number) : kProfileSegments;
    const Checked* velocity_text = b.find("velocity_profile");
    const Checked* stretch_text = b.find("stretch_profile");
    double X = 0.0;
    double l0_written = from_natural(l0, Dimension::length, scene.units);
    mu::Parser velocity, stretch;
    const std::pair<mu::Parser*, const Checked*> expressions[] = {{&velocity, velocity_text}, {&stretch, stretch_text}};
    for (const auto& [parser, text] : expressions) {
      if (text == nullptr) continue;
      try {
        parser->DefineVar("X", &X);
        parser->DefineVar("l0", &l0_written);
        parser->SetExpr(text->word);
        static_cast<void>(parser->Eval());  // parses it
      } catch (const mu::Parser::exception_type& e) {
        checker_.fail(*text, "the expression \"" + text->word + "\": " + e.GetMsg() +
                                 " (an expression of X and l0, with muparser's functions and _pi)");
      }
    }
    const Segment uniform = velocity_text != nullptr && stretch_text != nullptr ? Segment{}
                            : velocity_text != nullptr ? Segment{0.0, 0.0, Stretch::from_value(b["stretch"].number), ""}
                                                       : Segment{0.0, rapidity_of(b), Stretch::natural(), ""};
    for (int k = 0; k < count; ++k) {
      const double middle = l0 * (k + 0.5) / count;
      X = from_natural(middle, Dimension::length, scene.units);
      const std::string at = " at X = " + written(middle, Dimension::length);
      Segment segment{l0 / count, uniform.rapidity, uniform.stretch, material};
      try {
        if (velocity_text != nullptr) {
          const double v = to_natural(velocity.Eval(), Dimension::velocity, scene.units);
          if (!(std::abs(v) < 1.0))
            checker_.fail(*velocity_text, "gives v = " + written(v, Dimension::velocity) + at + "; |v| < c");
          segment.rapidity = std::atanh(v);
        }
        if (stretch_text != nullptr) {
          const double s = stretch.Eval();
          if (!(s > 0.0) || !std::isfinite(s))
            checker_.fail(*stretch_text, "gives s = " + format_number(s) + at + "; a stretch is positive");
          segment.stretch = Stretch::from_value(s);
        }
      } catch (const mu::Parser::exception_type& e) {
        checker_.fail(velocity_text != nullptr ? *velocity_text : *stretch_text,
                      "cannot be evaluated" + at + ": " + e.GetMsg());
      }
      const std::string violation = scene.materials.at(material).material->admissibility_violation(segment.stretch);
      if (!violation.empty())
        checker_.fail(stretch_text != nullptr ? *stretch_text : b["stretch"],
                      "inadmissible initial state" + at + ": " + violation);
      body.segments.push_back(segment);
    }
  }

  /// Lab length of a segment at t = 0: l·s/γ.
  static double lab_length(const Segment& segment) {
    return segment.length * segment.stretch.value() / std::cosh(segment.rapidity);
  }

  void read_bodies(Checked& bodies, Scene& scene) {
    for (std::size_t i = 0; i < bodies.entries.size(); ++i) {
      Checked& b = bodies.entries[i];
      const Checked& name = b["name"];
      if (const auto [first, inserted] = body_index_.emplace(name.word, i); !inserted)
        checker_.fail(name,
                      "duplicate body name '" + name.word + "' (body " + std::to_string(first->second) + " has it)");
      require_reference(b["material"], material_names_, "material");

      BodyDecl body;
      body.name = name.word;
      body.position = b["position"].number;
      body.where = where(b);
      if (b.has("segments")) {
        for (Checked& s : b["segments"].entries) {
          if (s["material"].given)
            require_reference(s["material"], material_names_, "material");
          else
            s.put(checker_.derived_text(s, "material", b["material"].word));
          body.segments.push_back(read_segment(s, s["material"].word, scene));
        }
      } else if (b.has("velocity_profile") || b.has("stretch_profile")) {
        read_profile(b, scene, body);
      } else {
        if (const Checked* count = b.find("profile_segments"))
          checker_.fail(*count, "'profile_segments' needs a profile: velocity_profile or stretch_profile");
        body.segments.push_back(read_segment(b, b["material"].word, scene));
      }

      double length = 0.0;
      for (const Segment& segment : body.segments) length += lab_length(segment);
      if (!scene.bodies.empty()) {
        const BodyDecl& previous = scene.bodies.back();
        const double previous_end = right_ends_.back();
        if (body.position < previous_end) {
          if (!within_rounding(body.position, previous_end, length)) {
            const std::string start =
                "body '" + body.name + "' starts at x = " + written(body.position, Dimension::length);
            const std::string span = "[" + written(previous.position, Dimension::length) + ", " +
                                     written(previous_end, Dimension::length) + "]";
            checker_.fail(b["position"],
                          (body.position >= previous.position
                               ? start + ", inside body '" + previous.name + "' which spans " + span
                               : start + ", left of body '" + previous.name + "' (" + span + ") listed before it") +
                              "; bodies are listed left to right and may touch but not overlap");
          }
          body.position = previous_end;
        }
      }
      right_ends_.push_back(body.position + length);
      scene.bodies.push_back(std::move(body));
    }
  }

  /// A history [[t0, value0], [t1, value1], ...] from t0 = 0, times strictly increasing: its
  /// times and its values, each through `value_of`, in `times` and `values`.
  template <class ValueOf>
  void read_history(const Checked& table, const std::string& whose, std::vector<double>& times,
                    std::vector<double>& values, ValueOf value_of) const {
    for (std::size_t i = 0; i < table.entries.size(); ++i) {
      const Checked& t = table.entries[i].entries[0];
      if (i == 0 && t.number != 0.0)
        checker_.fail(t, "the " + whose + "'s history must start at t = 0, got " + written(t.number, Dimension::time));
      if (i > 0 && !(t.number > times.back()))
        checker_.fail(t, "times must increase strictly: " + written(t.number, Dimension::time) + " follows " +
                             written(times.back(), Dimension::time));
      times.push_back(t.number);
      values.push_back(value_of(table.entries[i].entries[1].number));
    }
  }

  void read_boundary(Checked& side, bool left, const Scene& scene, BoundaryDecl& out) const {
    const std::string& type = side["type"].word;
    out.type = type == "wall"       ? BoundaryType::wall
               : type == "piston"   ? BoundaryType::piston
               : type == "traction" ? BoundaryType::traction
                                    : BoundaryType::free;
    out.where = where(side);
    if (out.type == BoundaryType::free) return;
    if (out.type == BoundaryType::traction) {
      if (const Checked* pressure = side.find("pressure")) {
        out.traction_times = {0.0};
        out.traction_pressures = {pressure->number};
        return;
      }
      read_history(side["pressure_table"], "pressure", out.traction_times, out.traction_pressures,
                   [](double p) { return p; });
      return;
    }
    out.bonded = side["bonded"].flag;

    const double end = left ? scene.bodies.front().position : right_ends_.back();
    if (const Checked* position = &side["position"]; position->given) {
      const double x = position->number;
      const bool outside = left ? x <= end : x >= end;
      if (!outside && !within_rounding(x, end, std::abs(right_ends_.back() - scene.bodies.front().position)))
        checker_.fail(*position, "the " + type + " must stand " + (left ? "at or left of" : "at or right of") +
                                     " the " + (left ? "left end of the leftmost" : "right end of the rightmost") +
                                     " body, x = " + written(end, Dimension::length) + ", not inside it; got " +
                                     written(x, Dimension::length));
      out.position = outside ? x : end;
    } else {
      out.position = end;
      side.put(checker_.derived_number(side, "position", end, Dimension::length));
    }

    if (out.type != BoundaryType::piston) return;
    if (const Checked* velocity = side.find("velocity")) {
      out.piston.times = {0.0};
      out.piston.rapidities = {std::atanh(velocity->number)};
      return;
    }
    read_history(side["table"], "piston", out.piston.times, out.piston.rapidities,
                 [](double v) { return std::atanh(v); });
    // Both solvers run a linear table as a staircase of steps of the tolerance in rapidity;
    // the front tracker steps it as its smooth waves (see Tracker::build_walls).
    if (side["interpolation"].word == "linear")
      out.piston = linear_piston(out.piston.times, out.piston.rapidities, scene.solver.tolerance);
  }

  static void read_solver(const Checked& solver, SolverDecl& out) {
    out.method = solver["method"].word == "finite_volume" ? SolverMethod::finite_volume : SolverMethod::characteristics;
    out.tolerance = solver["tolerance"].number;
    out.tolerance_given = solver["tolerance"].given;
    out.auto_resolution = solver["resolution"].word == "auto";
    out.budget = static_cast<long>(solver["budget"].number);
    out.max_fronts = static_cast<long>(solver["max_fronts"].number);
    out.max_interactions = static_cast<long>(solver["max_interactions"].number);
    out.cells = static_cast<int>(solver["cells"].number);
    out.order = static_cast<int>(solver["order"].number);
    out.cfl = solver["cfl"].number;
    out.flux = solver["flux"].word == "exact" ? FluxType::exact : FluxType::hll;
  }

  static std::vector<Quantity> quantities(const Checked& list) {
    std::vector<Quantity> out;
    for (const Checked& q : list.entries) out.push_back(*quantity_from_string(q.word));  // the schema admits names only
    return out;
  }

  void read_outputs(const Checked& outputs, const Checked& end, Scene& scene) const {
    std::set<std::string> body_names;
    for (const BodyDecl& b : scene.bodies) body_names.insert(b.name);

    std::set<std::string> probe_names;
    for (const Checked& p : outputs["probes"].entries) {
      ProbeDecl probe;
      probe.name = p["name"].word;
      if (!probe_names.insert(probe.name).second) checker_.fail(p["name"], "duplicate probe name '" + probe.name + "'");
      require_reference(p["body"], body_names, "body");
      probe.body = p["body"].word;
      const double l0 = scene.bodies[body_index_.at(probe.body)].natural_length();
      if (const Checked* lab = p.find("at_x")) {
        probe.lab_x = lab->number;
      } else if (const Checked& at = p["at"]; at.is_word()) {
        probe.X = at.word == "left" ? 0.0 : l0;
      } else {
        if (at.number < 0.0 || at.number > l0)
          checker_.fail(at, "must be in [0, " + written(l0, Dimension::length) + "] (a material label X of body '" +
                                probe.body + "', whose natural length is l0 = " + written(l0, Dimension::length) +
                                "), got " + written(at.number, Dimension::length));
        probe.X = at.number;
      }
      probe.quantities = quantities(p["quantities"]);
      probe.every = p["every"].number;
      if (scene.t_end / probe.every > kMaxProbeSamples)
        checker_.fail(p["every"], "gives more than " + format_number(kMaxProbeSamples) +
                                      " samples over the run (end = " + format_number(end.as_written) +
                                      "); sample less often");
      probe.where = where(p);
      scene.outputs.probes.push_back(std::move(probe));
    }

    for (const Checked& s : outputs["snapshots"].entries) {
      SnapshotDecl snapshot;
      if (const Checked* every = s.find("every")) {
        // Times k × every up to time.end (its last within the rounding of the product), each
        // to 15 significant digits in the scene's unit, so that 3 × 0.1 is written 0.3 as a
        // person would.
        const double count = std::floor(scene.t_end / every->number * (1.0 + 1e-12));
        const auto decimal = [](double t) {
          char text[32];
          std::snprintf(text, sizeof text, "%.15g", t);
          return std::strtod(text, nullptr);
        };
        if (count + 1.0 > kMaxSnapshotTimes)
          checker_.fail(*every, "gives " + format_number(count + 1.0) + " snapshots up to time.end; at most " +
                                    format_number(kMaxSnapshotTimes) + " (a larger `every`, or `times`)");
        for (double k = 0.0; k <= count; k += 1.0) {
          const double written = decimal(k * every->as_written);  // in the scene's unit of time
          snapshot.times.push_back(std::min(to_natural(written, Dimension::time, scene.units), scene.t_end));
        }
      }
      const Checked* times = s.find("times");
      for (const Checked& t : times != nullptr ? times->entries : std::span<const Checked>{}) {
        if (t.number > scene.t_end)
          checker_.fail(t, "must be in [0, end = " + format_number(end.as_written) + "] (time.end), got " +
                               format_number(t.as_written));
        snapshot.times.push_back(t.number);
      }
      snapshot.quantities = quantities(s["quantities"]);
      snapshot.samples = static_cast<int>(s["samples"].number);
      for (const Checked& b : s["bodies"].entries) {
        require_reference(b, body_names, "body");
        snapshot.bodies.push_back(b.word);
      }
      snapshot.where = where(s);
      scene.outputs.snapshots.push_back(std::move(snapshot));
    }
    scene.outputs.fronts = outputs["fronts"].flag;
    scene.outputs.hdf5 = outputs["hdf5"].flag;
  }

  /// A natural-unit value as the scene writes it.
  [[nodiscard]] std::string written(double natural, Dimension d) const {
    return format_number(from_natural(natural, d, units_));
  }

  Checker& checker_;
  const Sources& sources_;
  UnitSystem units_;
  std::filesystem::path directory_;  ///< of the scene file: relative paths in it start there
  std::set<std::string> material_names_;
  std::map<std::string, std::size_t> body_index_;  ///< body name → index
  std::vector<double> right_ends_;                 ///< lab x of each body's right end at t = 0
};

/// The unit system the scene declares, read before any dimensional value.
UnitSystem read_units(const TreeValue& root, const schema::Key& schema, const Sources& sources) {
  for (std::size_t e = 0; e < root.size(); ++e) {
    if (!root.key(e).is_scalar() || root.key(e).text() != "units") continue;
    Checker checker(sources, UnitSystem::natural);
    const Checked units = checker.check(root.value(e), *schema.field("units"), nullptr, "units", root.key(e).mark());
    return units.word == "si" ? UnitSystem::si : UnitSystem::natural;
  }
  return UnitSystem::natural;
}

/// Loads the plugins the scene lists (plugins.hpp), relative paths from `directory`, before
/// its materials are checked: a scene may use the materials of the plugins it lists. True if
/// it lists any.
bool load_listed_plugins(const TreeValue& root, const schema::Key& schema, const Sources& sources,
                         const std::filesystem::path& directory) {
  for (std::size_t e = 0; e < root.size(); ++e) {
    if (!root.key(e).is_scalar() || root.key(e).text() != "plugins") continue;
    Checker checker(sources, UnitSystem::natural);
    const Checked plugins =
        checker.check(root.value(e), *schema.field("plugins"), nullptr, "plugins", root.key(e).mark());
    std::vector<PluginReference> references;
    for (const Checked& p : plugins.entries) references.push_back({p.word, p.path(), sources.locate(p.path(), p.mark)});
    load_scene_plugins(references, directory);
    return !references.empty();
  }
  return false;
}

/// True if an override sets time.end (or the whole time map).
bool overrides_time_end(const std::vector<std::string>& overrides) {
  for (const std::string& assignment : overrides) {
    const std::string key = assignment.substr(0, assignment.find('='));
    if (key == "time" || key == "time.end") return true;
  }
  return false;
}

/// An override that ends the run earlier than the scene file does drops the snapshot times
/// beyond the new end (a snapshot left without times goes), in the tree, so that
/// resolved_scene.yaml is the scene as run; what went is said in the returned notes. A
/// scene file that itself asks for a time beyond its end stays an error.
std::vector<std::string> clip_snapshots_to_end(SceneTree& tree) {
  std::vector<std::string> notes;
  const TreeValue end_node = tree.root()["time"]["end"];
  if (!end_node.is_scalar()) return notes;  // the checker says why
  const NumberLiteral end_literal = parse_number(end_node.text());
  if (end_literal.syntax != NumberSyntax::finite) return notes;
  const double end = end_literal.value;
  const TreeValue outputs = tree.root()["outputs"];
  const TreeValue snapshots = outputs["snapshots"];
  if (!snapshots.is_list()) return notes;
  std::vector<int> kept_snapshots;
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    const TreeValue snapshot = snapshots.item(i);
    const TreeValue times = snapshot.is_map() ? snapshot["times"] : TreeValue();
    if (!times.is_list()) {
      kept_snapshots.push_back(snapshot.index());
      continue;
    }
    std::vector<int> kept_times;
    std::string dropped;
    for (std::size_t k = 0; k < times.size(); ++k) {
      const TreeValue t = times.item(k);
      const NumberLiteral value = t.is_scalar() ? parse_number(t.text()) : NumberLiteral{};
      if (value.syntax == NumberSyntax::finite && value.value > end) {
        dropped += (dropped.empty() ? "" : ", ") + std::string(t.text());
      } else {
        kept_times.push_back(t.index());
      }
    }
    if (dropped.empty()) {
      kept_snapshots.push_back(snapshot.index());
      continue;
    }
    const std::string which = "outputs.snapshots." + std::to_string(i);
    const std::string end_text(end_node.text());
    if (kept_times.empty()) {
      notes.push_back(which + " dropped: all its times (" + dropped + ") are beyond time.end = " + end_text +
                      " set on the command line");
      continue;
    }
    tree.set_items(times.index(), kept_times);
    kept_snapshots.push_back(snapshot.index());
    notes.push_back(which + ": times " + dropped + " dropped, beyond time.end = " + end_text +
                    " set on the command line");
  }
  tree.set_items(snapshots.index(), kept_snapshots);
  return notes;
}

Scene load(std::string_view text, const std::string& source, const std::vector<std::string>& overrides,
           const std::filesystem::path& directory) {
  Sources sources(source);
  std::vector<std::string> notes;
  schema::Key schema;
  UnitSystem units = UnitSystem::natural;
  // The tree lives only as long as the checking: what the Scene is built from (and
  // resolved_scene.yaml written from) are the checked values.
  const auto check = [&] {
    SceneTree tree = detail::parse_scene_text(text, source);
    for (const std::string& assignment : overrides) sources.apply_override(tree, assignment);
    const TreeValue root = tree.root();
    if (overrides_time_end(overrides) && root.is_map() && root["outputs"].is_map() && root["time"].is_map())
      notes = clip_snapshots_to_end(tree);
    load_environment_plugins();  // RIGIDITY_PLUGIN_PATH, before the schema lists the registered models
    schema = schema::scene_schema();
    units = read_units(tree.root(), schema, sources);
    if (load_listed_plugins(tree.root(), schema, sources, directory))
      schema = schema::scene_schema();  // with their models
    Checker checker(sources, units);
    return checker.check(tree.root(), schema, nullptr, "", tree.root().mark());
  };
  Checked checked;
  try {
    checked = check();
  } catch (const YAML::Exception& e) {
    // The parser's errors are reported where the text is read; any other is the input's too.
    throw InputError(SourceLocation{source, e.mark.line + 1, e.mark.column + 1}, "", "YAML error: " + e.msg);
  }
  Checker checker(sources, units);
  Scene scene = SceneBuilder(checker, sources, units, directory).build(checked);
  scene.resolver = [tree = std::make_shared<const Checked>(std::move(checked)), units] {
    return detail::emit_resolved(*tree, units);
  };
  scene.notes = std::move(notes);
  return scene;
}

}  // namespace

Scene load_scene_string(std::string_view text, const std::string& source, const std::vector<std::string>& overrides) {
  return load(text, source, overrides, {});  // relative paths from the working directory
}

Scene load_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  const bool is_file = std::filesystem::is_regular_file(path, ec);
  if (ec || !is_file) {
    const bool exists = std::filesystem::exists(path, ec);
    throw InputError(SourceLocation{path, 0, 0}, "", exists ? "not a regular file" : "no such file");
  }
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > schema::kMaxInputBytes)
    throw InputError(SourceLocation{path, 1, 1}, "",
                     "the file is " + std::to_string(size) + " bytes; a scene file is at most " +
                         std::to_string(schema::kMaxInputBytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{path, 0, 0}, "", "cannot open the file for reading");
  std::string text;
  text.reserve(schema::kMaxInputBytes / 16);
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > schema::kMaxInputBytes) break;  // grew while we read; parse_scene_text refuses it
  }
  if (in.bad()) throw InputError(SourceLocation{path, 0, 0}, "", "error while reading the file");
  return load(text, path, overrides, std::filesystem::path(path).parent_path());
}

std::string_view default_scene_text() { return detail::kDefaultSceneText; }

}  // namespace rigidity
