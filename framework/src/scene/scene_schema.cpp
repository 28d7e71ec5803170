// The scene schema (docs/scenes.md): every key of a scene file, declared once.

#include "rigidity/scene_schema.hpp"

#include <sstream>

#include "rigidity/quantity.hpp"
#include "rigidity/registry.hpp"
#include "scene_text.hpp"

namespace rigidity::schema {

// ---- builders ---------------------------------------------------------------------

namespace {
Key make(std::string name, Kind kind, std::string doc) {
  Key k;
  k.name = std::move(name);
  k.kind = kind;
  k.doc = std::move(doc);
  return k;
}
}  // namespace

Key Key::text(std::string name, std::string doc) { return make(std::move(name), Kind::text, std::move(doc)); }
Key Key::number(std::string name, std::string doc) { return make(std::move(name), Kind::number, std::move(doc)); }
Key Key::integer(std::string name, std::string doc) { return make(std::move(name), Kind::integer, std::move(doc)); }
Key Key::boolean(std::string name, std::string doc) { return make(std::move(name), Kind::boolean, std::move(doc)); }

Key Key::choice(std::string name, std::vector<std::string> words, std::string doc) {
  Key k = make(std::move(name), Kind::choice, std::move(doc));
  k.words = std::move(words);
  return k;
}

Key Key::list(std::string name, Key entry, std::string doc) {
  Key k = make(std::move(name), Kind::list, std::move(doc));
  k.fields.push_back(std::move(entry));
  return k;
}

Key Key::tuple(std::string name, std::vector<Key> positions, std::string doc) {
  Key k = make(std::move(name), Kind::tuple, std::move(doc));
  k.fields = std::move(positions);
  return k;
}

Key Key::map(std::string name, std::vector<Key> keys, std::string doc) {
  Key k = make(std::move(name), Kind::map, std::move(doc));
  k.fields = std::move(keys);
  return k;
}

Key Key::dictionary(std::string name, Key entry, std::string doc) {
  Key k = make(std::move(name), Kind::dictionary, std::move(doc));
  k.fields.push_back(std::move(entry));
  return k;
}

Key Key::parameter(const ParameterSpec& spec) {
  if (spec.type == ParameterType::numbers) {  // a formula's parameters: names the scene chooses, each a number
    std::vector<std::string> units;
    for (const Dimension d : {Dimension::dimensionless, Dimension::length, Dimension::time, Dimension::velocity,
                              Dimension::density, Dimension::pressure})
      units.emplace_back(dimension_name(d));
    Key declared =
        Key::number("", "the value of the parameter of this name, or its declaration {value, unit, min, max, doc}")
            .or_map_of({Key::number("value", "the value, in the scene's unit of `unit`").require(),
                        Key::choice("unit", units,
                                    "the dimension of the value: in the scene's units (Pa, m/s, kg/m^3, m, s in an "
                                    "SI scene; rho c^2, c, rho, L, L/c in a natural one)")
                            .defaults_to(std::string("dimensionless")),
                        Key::number("min", "the smallest admissible value (inclusive), in the same unit"),
                        Key::number("max", "the largest admissible value (inclusive), in the same unit"),
                        Key::text("doc", "what the parameter is")});
    return Key::dictionary(spec.name, std::move(declared), spec.doc);
  }
  Key k = make(spec.name, spec.type == ParameterType::number ? Kind::number : Kind::text, spec.doc);
  k.dimension = spec.dimension;
  k.required = spec.required;
  k.lower = spec.lower;
  k.upper = spec.upper;
  if (spec.default_number) k.fallback = *spec.default_number;
  if (spec.default_text) k.fallback = *spec.default_text;
  return k;
}

// One builder per line reads as a table.
// clang-format off
Key& Key::require() { required = true; return *this; }
Key& Key::defaults_to(double v) { fallback = v; return *this; }
Key& Key::defaults_to(bool v) { fallback = v; return *this; }
Key& Key::defaults_to(std::string word) { fallback = std::move(word); return *this; }
Key& Key::defaults_to_derived(std::string description) { derived_default = std::move(description); return *this; }
Key& Key::in(Dimension d) { dimension = d; return *this; }
Key& Key::above(double v) { lower = Bound{v, false}; return *this; }
Key& Key::at_least(double v) { lower = Bound{v, true}; return *this; }
Key& Key::below(double v) { upper = Bound{v, false}; return *this; }
Key& Key::at_most(double v) { upper = Bound{v, true}; return *this; }
Key& Key::because(std::string why) { note = std::move(why); return *this; }
Key& Key::one_of_values(std::vector<double> values) { allowed = std::move(values); return *this; }
Key& Key::or_words(std::vector<std::string> alternatives) { words = std::move(alternatives); return *this; }
Key& Key::as_identifier() { identifier = true; return *this; }
Key& Key::items(std::size_t min, std::size_t max) { min_items = min; max_items = max; return *this; }
Key& Key::distinct() { unique = true; return *this; }
Key& Key::only_with(std::string sibling) { only_if = Condition{std::move(sibling), {}}; return *this; }
Key& Key::only_when(std::string sibling, std::vector<std::string> values) {
  only_if = Condition{std::move(sibling), std::move(values)};
  return *this;
}
Key& Key::exclusive(std::vector<std::string> keys, bool is_required, std::optional<Condition> when) {
  one_of.push_back(OneOf{std::move(keys), is_required, std::move(when)});
  return *this;
}
// clang-format on
Key& Key::extended_by(std::string selector, std::function<std::vector<Key>(const std::string&)> more) {
  extension = Extension{std::move(selector), std::move(more)};
  return *this;
}

Key& Key::or_map_of(std::vector<Key> keys) {
  number_or_map = true;
  fields = std::move(keys);
  return *this;
}

const Key* Key::field(const std::string& key_name) const {
  for (const Key& f : fields)
    if (f.name == key_name) return &f;
  return nullptr;
}

std::string Key::range_text(UnitSystem units) const {
  auto bound = [&](const Bound& b) { return detail::format_number(from_natural(b.value, dimension, units)); };
  std::string out;
  if (lower && upper)
    out = std::string(lower->inclusive ? "[" : "(") + bound(*lower) + ", " + bound(*upper) +
          (upper->inclusive ? "]" : ")");
  else if (lower)
    out = std::string(lower->inclusive ? ">= " : "> ") + bound(*lower);
  else if (upper)
    out = std::string(upper->inclusive ? "<= " : "< ") + bound(*upper);
  if (!out.empty() && units == UnitSystem::si && dimension != Dimension::dimensionless)
    out += " " + std::string(unit_symbol(dimension, units));
  return out;
}

// ---- the scene ----------------------------------------------------------------------

namespace {

std::vector<std::string> quantity_names() {
  std::vector<std::string> names;
  for (Quantity q : kAllQuantities) names.emplace_back(to_string(q));
  return names;
}

/// A velocity |v| < c.
Key velocity(std::string name, std::string doc) {
  return Key::number(std::move(name), std::move(doc)).in(Dimension::velocity).above(-1.0).below(1.0).because("|v| < c");
}

/// velocity | rapidity | gamma (+ direction), stretch: the uniform state of a body or segment.
std::vector<Key> uniform_state_keys(const std::string& requires_key) {
  auto applies = [&](Key k) {
    if (!requires_key.empty()) k.only_with(requires_key);
    return k;
  };
  return {
      applies(velocity("velocity", "uniform initial velocity (lab frame, +x to the right)").defaults_to(0.0)),
      // Pressures behind an impact grow as γ² (the rigid law: p = ρ00 v/(1 − v) ≈ 2 ρ00 γ²), so
      // γ ≤ 1e150 keeps them within double precision (1.8e308); softer materials that would
      // still overflow are stopped by the solver with that reason (exit 3).
      applies(Key::number("rapidity", "uniform initial rapidity phi = artanh v, for ultra-relativistic bodies")
                  .at_least(-345.0)
                  .at_most(345.0)
                  .because("gamma = cosh(phi) <= 1e150: pressures behind an impact grow as gamma^2 and must "
                           "stay within double precision")),
      applies(Key::number("gamma", "uniform initial Lorentz factor, moving in `direction`")
                  .at_least(1.0)
                  .at_most(1.0e150)
                  .because("pressures behind an impact grow as gamma^2 and must stay within double precision")),
      Key::number("direction", "direction of motion for `gamma`: +1 (to +x) or -1")
          .one_of_values({-1.0, 1.0})
          .defaults_to(1.0)
          .only_with("gamma"),
      applies(Key::number("stretch", "uniform initial stretch s = proper length / natural length")
                  .above(0.0)
                  .defaults_to(1.0)),
  };
}

Key segment_key() {
  std::vector<Key> keys{
      Key::number("length", "natural length of the segment").in(Dimension::length).above(0.0).require()};
  for (Key& k : uniform_state_keys("")) keys.push_back(std::move(k));
  keys.push_back(Key::text("material", "scene material of the segment")
                     .as_identifier()
                     .defaults_to_derived("the body's material"));
  Key segment = Key::map("", std::move(keys), "a piece of the body with uniform initial state");
  segment.exclusive({"velocity", "rapidity", "gamma"});
  return segment;
}

Key body_key() {
  std::vector<Key> keys{
      Key::text("name", "unique name of the body").as_identifier().require(),
      Key::text("material", "a material declared under `materials`").as_identifier().require(),
      Key::number("position", "lab x of the left end at t = 0").in(Dimension::length).defaults_to(0.0),
      Key::number("length", "natural length l0 (or give `segments`)").in(Dimension::length).above(0.0),
  };
  for (Key& k : uniform_state_keys("length")) keys.push_back(std::move(k));
  keys.push_back(Key::text("velocity_profile",
                           "v(X): the initial velocity as an expression of the label X (and l0, the natural length; "
                           "muparser's functions and _pi), in the scene's units, instead of a uniform velocity")
                     .only_with("length"));
  keys.push_back(Key::text("stretch_profile", "s(X): the initial stretch as an expression of X, instead of `stretch`")
                     .only_with("length"));
  keys.push_back(Key::integer("profile_segments",
                              "a profile runs as the staircase of its values at the middles of this many equal "
                              "segments (100 if not given)")
                     .at_least(1.0)
                     .at_most(1.0e5)
                     .only_with("length"));
  keys.push_back(Key::list("segments", segment_key(), "piecewise-constant initial data, left to right").items(1));
  Key body = Key::map("", std::move(keys), "a bar; bodies are listed left to right and may touch but not overlap");
  body.exclusive({"length", "segments"}, true)
      .exclusive({"velocity", "rapidity", "gamma", "velocity_profile"})
      .exclusive({"stretch", "stretch_profile"});
  return body;
}

Key boundary_key(const std::string& side) {
  const std::vector<std::string> held{"wall", "piston"};
  const Key row = Key::tuple("",
                             {Key::number("t", "from this time on").in(Dimension::time).at_least(0.0),
                              velocity("v", "the piston moves at this velocity")},
                             "[t, v]");
  const Key pressure_row =
      Key::tuple("",
                 {Key::number("t", "from this time on").in(Dimension::time).at_least(0.0),
                  Key::number("p", "the pressure applied to the end (> 0 pushes, < 0 pulls)").in(Dimension::pressure)},
                 "[t, p]");
  Key end = Key::map(side,
                     {
                         Key::choice("type", {"free", "wall", "piston", "traction"},
                                     "free end (p = 0), fixed wall, moving piston, end held at a given pressure")
                             .defaults_to(std::string("free")),
                         Key::number("pressure", "constant pressure applied to the end (> 0 pushes, < 0 pulls)")
                             .in(Dimension::pressure)
                             .only_when("type", {"traction"}),
                         Key::list("pressure_table", pressure_row,
                                   "history of the pressure applied to the end, t increasing from 0; each row's "
                                   "pressure holds until the next row")
                             .items(1)
                             .only_when("type", {"traction"}),
                         Key::boolean("bonded", "the wall or piston pulls as well as pushes")
                             .defaults_to(false)
                             .only_when("type", held),
                         Key::number("position", "lab x of the wall or piston at t = 0")
                             .in(Dimension::length)
                             .defaults_to_derived("the adjacent body's end")
                             .only_when("type", held),
                         velocity("velocity", "constant piston velocity").only_when("type", {"piston"}),
                         Key::list("table", row, "piston velocity history, t increasing from 0")
                             .items(1)
                             .only_when("type", {"piston"}),
                         Key::choice("interpolation", {"step", "linear"},
                                     "table: step (each row's velocity holds until the next row) or linear (the "
                                     "velocity ramps between rows, run as steps of at most solver.tolerance in "
                                     "rapidity, at most 1000 per row; the last row's velocity holds)")
                             .defaults_to(std::string("step"))
                             .only_when("type", {"piston"}),
                     },
                     side + " end of the row of bodies");
  end.exclusive({"velocity", "table"}, true, Condition{"type", {"piston"}});
  end.exclusive({"pressure", "pressure_table"}, true, Condition{"type", {"traction"}});
  return end;
}

Key material_key() {
  Key entry =
      Key::map("", {Key::choice("model", MaterialRegistry::instance().names(), "registered material model").require()},
               "a material: its model and the parameters that model declares");
  entry.extended_by("model", [](const std::string& model) {
    std::vector<Key> parameters;
    if (const MaterialInfo* info = MaterialRegistry::instance().find(model))
      for (const ParameterSpec& spec : info->parameters) parameters.push_back(Key::parameter(spec));
    return parameters;
  });
  return entry;
}

Key solver_key() {
  return Key::map(
      "solver",
      {
          Key::choice("method", {"characteristics", "finite_volume"}, "front tracking, or a finite-volume scheme")
              .defaults_to(std::string("characteristics")),
          Key::number("tolerance",
                      "characteristics: the error the run may make (docs/solvers.md, What the tolerance means); "
                      "by default 1e-12 where every body is linearly degenerate (exact: every wave a jump), "
                      "and 1e-4 where a body is genuinely nonlinear (fans and what they cross resolved to about "
                      "that, at a cost any scene can afford)")
              .above(0.0)
              .defaults_to(1.0e-12),
          Key::choice("resolution", {"tolerance", "auto"},
                      "characteristics: how finely waves are resolved: `auto` aims the error bound at the "
                      "tolerance (a pilot run at 10 x tolerance measures it, runs at the resolution it points to "
                      "follow, finer than the tolerance where the scene books more than it, all within "
                      "solver.budget; the coarsest run within the tolerance, else the one with the least bound, is "
                      "kept), or `tolerance`: to the tolerance itself, one run")
              .defaults_to(std::string("auto")),
          Key::integer("budget",
                       "characteristics with `resolution: auto`: the most interactions the aim spends over all its "
                       "runs (the default is a few seconds of solving); where resolving the waves to the tolerance "
                       "would take more, they are resolved as finely as it affords and a warning says so (a run at "
                       "the coarsest resolution the aim takes, 0.01, is stopped only by max_interactions)")
              .at_least(1.0)
              .at_most(1.0e15)
              .defaults_to(1.0e7),
          Key::integer("max_fronts",
                       "characteristics: most fronts alive at once, about 210 bytes each (the default is about "
                       "210 MB); beyond it the run stops cleanly with status `stopped` and the outputs up to then")
              .at_least(1.0)
              .at_most(1.0e12)
              .defaults_to(1.0e6),
          Key::integer("max_interactions",
                       "characteristics: most interactions (Riemann problems) of a run; the default is tens of seconds "
                       "to minutes of solving (0.2 to 2 million interactions/s); beyond it the run stops cleanly "
                       "with status `stopped` and the outputs up to then")
              .at_least(1.0)
              .at_most(1.0e15)
              .defaults_to(1.0e8),
          Key::integer("cells", "finite_volume: number of cells").at_least(2.0).at_most(1.0e8).defaults_to(400.0),
          Key::integer("order", "finite_volume: spatial order, 1 or 2").one_of_values({1.0, 2.0}).defaults_to(2.0),
          Key::number("cfl", "finite_volume: Courant number").above(0.0).at_most(1.0).defaults_to(0.5),
          Key::choice("flux", {"hll", "exact"}, "finite_volume: numerical flux").defaults_to(std::string("hll")),
      },
      "the integration method; keys of the other method are accepted, checked and ignored, "
      "so that `--set solver.method=...` switches method without editing the file");
}

Key outputs_key() {
  const Key quantity = Key::choice("", quantity_names(), "an output quantity");
  Key probe =
      Key::map("",
               {
                   Key::text("name", "unique name of the probe (a column of probes.csv)").as_identifier().require(),
                   Key::text("body", "the body probed").as_identifier().require(),
                   Key::number("at", "material label X probed, or `left` / `right` (X = 0 / l0)")
                       .in(Dimension::length)
                       .or_words({"left", "right"}),
                   Key::number("at_x",
                               "lab position x probed instead: the body's state wherever it covers x (no sample "
                               "while it does not)")
                       .in(Dimension::length),
                   Key::list("quantities", quantity, "quantities sampled").items(1).distinct().require(),
                   Key::number("every", "sampling interval").in(Dimension::time).above(0.0).require(),
               },
               "samples quantities at one material point (or lab position) at regular times");
  probe.exclusive({"at", "at_x"}, true);
  Key snapshot = Key::map(
      "",
      {
          Key::list("times", Key::number("", "a time in [0, end]").in(Dimension::time).at_least(0.0),
                    "times of the snapshots")
              .items(1),
          Key::number("every", "a snapshot every this long from t = 0 to time.end (instead of times)")
              .in(Dimension::time)
              .above(0.0),
          Key::list("quantities", quantity, "quantities written").items(1).distinct().require(),
          Key::integer("samples", "points per body, uniform in X, both ends included")
              .at_least(2.0)
              .at_most(1.0e6)
              .defaults_to(101.0),
          Key::list("bodies", Key::text("", "a body").as_identifier(), "bodies written (empty: every body)").distinct(),
      },
      "quantities along the bodies at given times");
  snapshot.exclusive({"times", "every"}, true);
  return Key::map("outputs",
                  {
                      Key::list("probes", std::move(probe), "probes.csv"),
                      Key::list("snapshots", std::move(snapshot), "snapshots.csv"),
                      Key::boolean("fronts", "fronts.csv: the x-t diagram of every front").defaults_to(false),
                      Key::boolean("hdf5",
                                   "run.h5 (the command line): every output of the run in one HDF5 file beside the CSV "
                                   "files, with the units of each dataset")
                          .defaults_to(false),
                  },
                  "what the run writes besides summary.json and resolved_scene.yaml");
}

}  // namespace

Key scene_schema() {
  return Key::map(
      "",
      {
          Key::text("name", "scene name; the default output folder is out/<name>").as_identifier().require(),
          Key::choice("units", {"natural", "si"}, "natural (c = 1) or si (m, s, kg/m^3, Pa, m/s)")
              .defaults_to(std::string("natural")),
          Key::list("plugins", Key::text("", "path of a shared library"),
                    "shared libraries of extra materials (also found on RIGIDITY_PLUGIN_PATH)"),
          Key::dictionary("materials", material_key(), "materials by the name bodies use").items(1).require(),
          Key::list("bodies", body_key(), "the bodies, left to right").items(1, 10000).require(),
          Key::map("boundaries", {boundary_key("left"), boundary_key("right")}, "the two outer ends"),
          solver_key(),
          Key::map("time", {Key::number("end", "end time of the run").in(Dimension::time).above(0.0).require()},
                   "time span [0, end]")
              .require(),
          outputs_key(),
      },
      "a rigidity scene");
}

// ---- documentation ------------------------------------------------------------------

namespace {

std::string kind_text(const Key& k) {
  switch (k.kind) {
    case Kind::text: return "string";
    case Kind::choice: {
      std::string out;
      for (const std::string& w : k.words) out += (out.empty() ? "" : "|") + w;
      return out;
    }
    case Kind::number: {
      std::string out = "number";
      for (const std::string& w : k.words) out += "|" + w;
      if (k.number_or_map) out += "|map";
      return out;
    }
    case Kind::integer: return "integer";
    case Kind::boolean: return "true|false";
    case Kind::list: return "list";
    case Kind::tuple: return "[" + std::to_string(k.fields.size()) + " values]";
    case Kind::map: return "map";
    case Kind::dictionary: return "map of names";
  }
  return "?";
}

std::string default_text(const Key& k, UnitSystem units) {
  if (const auto* d = std::get_if<double>(&k.fallback))
    return detail::format_number(from_natural(*d, k.dimension, units));
  if (const auto* b = std::get_if<bool>(&k.fallback)) return *b ? "true" : "false";
  if (const auto* w = std::get_if<std::string>(&k.fallback)) return *w;
  return k.derived_default;
}

/// Rows for k (whose path is `path`) and everything under it.
void flatten_into(std::vector<KeyRow>& rows, const Key& k, UnitSystem units, const std::string& path,
                  const std::string& model) {
  KeyRow row;
  row.path = path;
  row.type = kind_text(k);
  row.required = k.required;
  row.default_value = default_text(k, units);
  if (k.dimension != Dimension::dimensionless) row.unit = std::string(unit_symbol(k.dimension, units));
  row.range = k.range_text(units);
  row.model = model;
  row.doc = k.doc;
  rows.push_back(row);
  const auto child_path = [&](const Key& f) {
    if (!f.name.empty()) return path + "." + f.name;
    return path + (k.kind == Kind::dictionary ? ".<name>" : ".*");  // a list's entries, a dictionary's names
  };
  for (const Key& f : k.fields) flatten_into(rows, f, units, child_path(f), model);
  if (k.extension) {
    for (const std::string& m : MaterialRegistry::instance().names())
      for (const Key& f : k.extension->fields(m)) flatten_into(rows, f, units, child_path(f), m);
  }
}

void describe_into(std::ostringstream& out, const Key& k, UnitSystem units, int depth) {
  out << std::string(static_cast<std::size_t>(2 * depth), ' ') << (k.name.empty() ? "-" : k.name) << ": "
      << kind_text(k);
  if (k.required) out << ", required";
  if (const auto* d = std::get_if<double>(&k.fallback))
    out << ", default " << detail::format_number(from_natural(*d, k.dimension, units));
  if (const auto* b = std::get_if<bool>(&k.fallback)) out << ", default " << (*b ? "true" : "false");
  if (const auto* w = std::get_if<std::string>(&k.fallback)) out << ", default " << *w;
  if (!k.derived_default.empty()) out << ", default " << k.derived_default;
  if (k.dimension != Dimension::dimensionless) out << ", [" << unit_symbol(k.dimension, units) << "]";
  if (const std::string range = k.range_text(units); !range.empty()) out << ", " << range;
  if (!k.allowed.empty()) {
    out << ", one of";
    for (double v : k.allowed) out << " " << detail::format_number(v);
  }
  if (k.only_if) out << ", only with " << k.only_if->sibling;
  out << "  # " << k.doc << "\n";
  for (const Key& f : k.fields) describe_into(out, f, units, depth + 1);
  if (k.extension) {
    for (const std::string& m : MaterialRegistry::instance().names()) {
      const std::vector<Key> more = k.extension->fields(m);
      if (more.empty()) continue;
      out << std::string(static_cast<std::size_t>(2 * (depth + 1)), ' ') << "# with " << k.extension->selector << ": "
          << m << "\n";
      for (const Key& f : more) describe_into(out, f, units, depth + 1);
    }
  }
}

}  // namespace

std::string describe(const Key& key, UnitSystem units) {
  std::ostringstream out;
  describe_into(out, key, units, 0);
  return out.str();
}

std::vector<KeyRow> flatten(const Key& key, UnitSystem units) {
  std::vector<KeyRow> rows;
  for (const Key& f : key.fields) flatten_into(rows, f, units, f.name, "");
  return rows;
}

}  // namespace rigidity::schema
