// Sweeps (docs/sweeps.md): the sweep file, its cases, one case run in-process, and the table.
#include "rigidity/sweep.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "rigidity/errors.hpp"
#include "rigidity/number_text.hpp"
#include "rigidity/output.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"
#include "rigidity/spelling.hpp"

namespace rigidity {

namespace {

namespace fs = std::filesystem;

// ---- reading the sweep file -------------------------------------------------------------

class SweepReader {
 public:
  explicit SweepReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& message) const {
    const YAML::Mark mark = node.Mark();
    throw InputError(SourceLocation{file_, mark.is_null() ? 0 : mark.line + 1, mark.is_null() ? 0 : mark.column + 1},
                     key, message);
  }

  /// Every key of `map` must be one of `allowed`.
  void check_keys(const YAML::Node& map, const std::string& where, const std::vector<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, where, "must be a mapping");
    for (const auto& entry : map) {
      const std::string key = entry.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        const std::string name = where.empty() ? key : where + "." + key;
        const std::string nearest = closest_match(key, allowed);
        fail(entry.first, name,
             "unknown key" + (nearest.empty() ? std::string() : "; did you mean '" + nearest + "'?"));
      }
    }
  }

  [[nodiscard]] double number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "must be a number");
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(node, key, "must be a number, not '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) fail(node, key, "must be a finite number");
    return value;
  }

  [[nodiscard]] long integer(const YAML::Node& node, const std::string& key, long min) const {
    if (!node.IsScalar()) fail(node, key, "must be an integer");
    long value = 0;
    try {
      value = node.as<long>();
    } catch (const YAML::Exception&) {
      fail(node, key, "must be an integer, not '" + node.Scalar() + "'");
    }
    if (value < min) fail(node, key, "must be at least " + std::to_string(min) + ", not " + std::to_string(value));
    return value;
  }

  [[nodiscard]] std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "must be a scalar");
    return node.Scalar();
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

/// One parameter as declared: a grid of values, or a range to sample.
struct ParameterDecl {
  std::string key;
  YAML::Node node;
  std::vector<std::string> values;  ///< grid
  bool ranged = false;
  double low = 0.0, high = 0.0;
};

/// A grid value rounded to 15 significant digits: the round-off of its arithmetic (a few ulps)
/// goes, so 0.05 + 2 (0.95 − 0.05)/18 is 0.15, not 0.15000000000000002, and 1e-6·100 is 0.0001.
double to_15_digits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return std::strtod(text, nullptr);
}

std::vector<double> spaced(const SweepReader& reader, const YAML::Node& node, const std::string& key, bool log) {
  if (!node.IsSequence() || node.size() != 3) reader.fail(node, key, "must be [a, b, n]");
  const double a = reader.number(node[0], key), b = reader.number(node[1], key);
  const long n = reader.integer(node[2], key, 1);
  if (log && !(a > 0.0 && b > 0.0)) reader.fail(node, key, "logspace ends must both be positive");
  std::vector<double> values;
  for (long i = 0; i < n; ++i) {
    const double f = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    const double v =
        log      ? a * std::pow(b / a, f)
        : n == 1 ? a
                 : (a * static_cast<double>(n - 1 - i) + b * static_cast<double>(i)) / static_cast<double>(n - 1);
    values.push_back(i == 0 ? a : i == n - 1 ? b : to_15_digits(v));
  }
  return values;
}

/// The event kinds the solvers report (docs/cli.md, "What a run writes").
const std::vector<std::string> kEventKinds = {"contact", "separation", "cavitation", "rejoin"};

/// The names in summary.json's "solver" block, by method: the characteristics solver's
/// (resolution, pilot_error_bound, resolution_runs and aim_interactions with
/// solver.resolution: auto), the finite-volume scheme's.
const std::vector<std::string> kCharacteristicsNumbers = {
    "tolerance",         "error_bound",      "weak_wave_threshold", "waves_held_back", "fronts_merged",
    "error_defects",     "error_fans",       "error_merges",        "error_carried",   "droplets",
    "error_droplets",    "fronts_alive_max", "wave_resolution",     "fan_step_max",    "resolution",
    "pilot_error_bound", "resolution_runs",  "aim_interactions"};
const std::vector<std::string> kFiniteVolumeNumbers = {"cells", "cells_total", "order", "cfl", "steps"};

std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text.empty() ? "none" : text;
}

/// Every collect path names what the base scene has: its probes and their quantities, its
/// bodies, the solver numbers of its method (of both methods when solver.method is swept),
/// an event kind the solvers report. A name only a case's parameters bring in is not
/// foreseen; a base scene that does not load leaves the check to the cases, which report it.
void check_collect_names(const SweepReader& reader, const Sweep& sweep, const std::vector<YAML::Node>& nodes) {
  if (sweep.collect.empty()) return;
  std::optional<Scene> loaded;
  try {
    loaded.emplace(sweep.scene_path.empty() ? load_scene_string(default_scene_text(), "<default>")
                                            : load_scene_file(sweep.scene_path));
  } catch (const std::exception&) {
    return;
  }
  const Scene& scene = *loaded;
  const std::string scene_name = sweep.scene_path.empty() ? "the default scene" : "the scene " + sweep.scene_path;
  const bool method_swept =
      std::find(sweep.parameters.begin(), sweep.parameters.end(), "solver.method") != sweep.parameters.end();
  std::vector<std::string> solver_numbers;
  if (method_swept || scene.solver.method == SolverMethod::characteristics)
    solver_numbers.insert(solver_numbers.end(), kCharacteristicsNumbers.begin(), kCharacteristicsNumbers.end());
  if (method_swept || scene.solver.method == SolverMethod::finite_volume)
    solver_numbers.insert(solver_numbers.end(), kFiniteVolumeNumbers.begin(), kFiniteVolumeNumbers.end());

  for (std::size_t c = 0; c < sweep.collect.size(); ++c) {
    const std::string& p = sweep.collect[c].path;
    std::vector<std::string> parts;
    std::stringstream split(p);
    for (std::string part; std::getline(split, part, '.');) parts.push_back(part);
    const auto bad = [&](const std::string& what, const std::string& name, const std::vector<std::string>& known) {
      const std::string nearest = closest_match(name, known);
      reader.fail(nodes[c], "collect." + sweep.collect[c].name,
                  "'" + p + "': " + what + " '" + name + "'" +
                      (nearest.empty() ? "" : "; did you mean '" + nearest + "'?") + " (" + scene_name +
                      " has: " + listed(known) + ")");
    };
    if (parts[0] == "probe") {
      std::vector<std::string> names;
      const ProbeDecl* probe = nullptr;
      for (const ProbeDecl& d : scene.outputs.probes) {
        names.push_back(d.name);
        if (d.name == parts[1]) probe = &d;
      }
      if (probe == nullptr) {
        bad("no probe", parts[1], names);
      } else {
        std::vector<std::string> quantities;
        for (Quantity q : probe->quantities) quantities.emplace_back(to_string(q));
        if (std::find(quantities.begin(), quantities.end(), parts[2]) == quantities.end())
          bad("probe '" + parts[1] + "' does not record", parts[2], quantities);
      }
    } else if (parts[0] == "body") {
      std::vector<std::string> names;
      for (const BodyDecl& b : scene.bodies) names.push_back(b.name);
      if (std::find(names.begin(), names.end(), parts[1]) == names.end()) bad("no body", parts[1], names);
    } else if (parts[0] == "event") {
      if (std::find(kEventKinds.begin(), kEventKinds.end(), parts[1]) == kEventKinds.end())
        bad("no event kind", parts[1], kEventKinds);
    } else if (parts[0] == "solver") {
      if (std::find(solver_numbers.begin(), solver_numbers.end(), parts[1]) == solver_numbers.end())
        bad("no solver number", parts[1], solver_numbers);
    }
  }
}

/// A uniform double in [0, 1) from 53 bits of the generator: the same on every platform.
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

Sweep load_sweep_file(const std::string& path) {
  const SweepReader reader(path);
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(SourceLocation{path, 0, 0}, "", "cannot read the sweep file");
  } catch (const YAML::ParserException& e) {
    throw InputError(SourceLocation{path, e.mark.line + 1, e.mark.column + 1}, "", e.msg);
  }
  if (!root.IsMap()) throw InputError(SourceLocation{path, 1, 1}, "", "a sweep file is a mapping");
  reader.check_keys(root, "", {"scene", "parameters", "zip", "sample", "collect", "keep_outputs"});

  Sweep sweep;
  sweep.source = path;
  if (root["scene"]) {
    const std::string scene = reader.text(root["scene"], "scene");
    const fs::path p(scene);
    sweep.scene_path = p.is_absolute() ? scene : (fs::path(path).parent_path() / p).lexically_normal().string();
    if (!fs::exists(sweep.scene_path)) reader.fail(root["scene"], "scene", "no such file: " + sweep.scene_path);
  }
  if (root["keep_outputs"]) {
    try {
      sweep.keep_outputs = root["keep_outputs"].as<bool>();
    } catch (const YAML::Exception&) {
      reader.fail(root["keep_outputs"], "keep_outputs", "must be true or false");
    }
  }

  // Parameters.
  const YAML::Node params = root["parameters"];
  if (!params) throw InputError(SourceLocation{path, 1, 1}, "parameters", "required key missing");
  if (!params.IsMap() || params.size() == 0) reader.fail(params, "parameters", "must be a non-empty mapping");
  std::vector<ParameterDecl> decls;
  for (const auto& entry : params) {
    ParameterDecl d;
    d.key = entry.first.as<std::string>();
    d.node = entry.second;
    const std::string where = "parameters." + d.key;
    if (d.key.empty() || d.key.find('=') != std::string::npos)
      reader.fail(entry.first, where, "a parameter is a --set key path such as bodies.0.velocity");
    for (const ParameterDecl& other : decls)
      if (other.key == d.key) reader.fail(entry.first, where, "declared twice");
    reader.check_keys(d.node, where, {"values", "linspace", "logspace", "range"});
    if (d.node.size() != 1) reader.fail(d.node, where, "give exactly one of values, linspace, logspace, range");
    if (const YAML::Node v = d.node["values"]) {
      if (!v.IsSequence() || v.size() == 0) reader.fail(v, where + ".values", "must be a non-empty list");
      for (const auto& item : v) {
        if (!item.IsScalar()) reader.fail(item, where + ".values", "every value must be a scalar");
        d.values.push_back(item.Scalar());
      }
    } else if (const YAML::Node l = d.node["linspace"]) {
      for (double x : spaced(reader, l, where + ".linspace", false)) d.values.push_back(shortest(x));
    } else if (const YAML::Node g = d.node["logspace"]) {
      for (double x : spaced(reader, g, where + ".logspace", true)) d.values.push_back(shortest(x));
    } else {
      const YAML::Node r = d.node["range"];
      if (!r.IsSequence() || r.size() != 2) reader.fail(r, where + ".range", "must be [a, b]");
      d.ranged = true;
      d.low = reader.number(r[0], where + ".range");
      d.high = reader.number(r[1], where + ".range");
      if (!(d.low < d.high)) reader.fail(r, where + ".range", "needs a < b");
    }
    sweep.parameters.push_back(d.key);
    decls.push_back(d);
  }
  const auto index_of = [&decls](const std::string& key) {
    for (std::size_t k = 0; k < decls.size(); ++k)
      if (decls[k].key == key) return static_cast<long>(k);
    return -1L;
  };

  // Dimensions of the product: a lone grid parameter, a zip group, or the sample block.
  std::vector<std::vector<std::size_t>> groups;  // parameter indices of each dimension
  std::vector<long> group_of(decls.size(), -1);
  if (const YAML::Node zip = root["zip"]) {
    if (!zip.IsSequence()) reader.fail(zip, "zip", "must be a list of lists of parameter keys");
    for (const auto& group : zip) {
      if (!group.IsSequence() || group.size() < 2) reader.fail(group, "zip", "each group lists two keys or more");
      std::vector<std::size_t> members;
      for (const auto& item : group) {
        const std::string key = reader.text(item, "zip");
        const long k = index_of(key);
        if (k < 0) reader.fail(item, "zip", "'" + key + "' is not a parameter");
        if (decls[k].ranged) reader.fail(item, "zip", "'" + key + "' is sampled, not a list");
        if (group_of[k] >= 0) reader.fail(item, "zip", "'" + key + "' is in two zip groups");
        if (decls[k].values.size() != decls[members.empty() ? k : members.front()].values.size())
          reader.fail(item, "zip",
                      "'" + key + "' has " + std::to_string(decls[k].values.size()) + " values, '" +
                          decls[members.front()].key + "' " + std::to_string(decls[members.front()].values.size()) +
                          "; zipped lists must be as long");
        group_of[k] = static_cast<long>(groups.size());
        members.push_back(static_cast<std::size_t>(k));
      }
      groups.push_back(members);
    }
  }

  std::size_t sample_n = 0;
  std::vector<std::vector<std::string>> samples;  // samples[i][j]: ranged parameter j of sample i
  std::vector<std::size_t> ranged;
  for (std::size_t k = 0; k < decls.size(); ++k)
    if (decls[k].ranged) ranged.push_back(k);
  if (const YAML::Node sample = root["sample"]) {
    reader.check_keys(sample, "sample", {"n", "seed", "method"});
    if (!sample["n"]) reader.fail(sample, "sample.n", "required key missing");
    sample_n = static_cast<std::size_t>(reader.integer(sample["n"], "sample.n", 1));
    const auto seed = sample["seed"] ? static_cast<std::uint64_t>(reader.integer(sample["seed"], "sample.seed", 0)) : 0;
    const std::string method = sample["method"] ? reader.text(sample["method"], "sample.method") : "uniform";
    if (method != "uniform" && method != "log_uniform" && method != "latin")
      reader.fail(sample["method"], "sample.method", "must be uniform, log_uniform or latin, not '" + method + "'");
    if (ranged.empty()) reader.fail(sample, "sample", "no parameter has a range: to sample");
    for (std::size_t k : ranged)
      if (method == "log_uniform" && !(decls[k].low > 0.0))
        reader.fail(decls[k].node, "parameters." + decls[k].key + ".range", "log_uniform needs a positive range");
    std::mt19937_64 rng(seed);
    // Latin hypercube: each parameter's range cut into n strata, each stratum used once.
    std::vector<std::vector<std::size_t>> strata(ranged.size());
    if (method == "latin")
      for (auto& perm : strata) {
        perm.resize(sample_n);
        for (std::size_t i = 0; i < sample_n; ++i) perm[i] = i;
        for (std::size_t i = sample_n; i > 1; --i)
          std::swap(perm[i - 1], perm[static_cast<std::size_t>(unit(rng) * static_cast<double>(i))]);
      }
    for (std::size_t i = 0; i < sample_n; ++i) {
      std::vector<std::string> row;
      for (std::size_t j = 0; j < ranged.size(); ++j) {
        const ParameterDecl& d = decls[ranged[j]];
        double u = unit(rng);
        if (method == "latin") u = (static_cast<double>(strata[j][i]) + u) / static_cast<double>(sample_n);
        const double x = method == "log_uniform" ? d.low * std::pow(d.high / d.low, u) : d.low + (d.high - d.low) * u;
        row.push_back(shortest(x));
      }
      samples.push_back(row);
    }
  } else if (!ranged.empty()) {
    reader.fail(decls[ranged.front()].node, "parameters." + decls[ranged.front()].key,
                "a range: needs a sample: block (n, seed, method)");
  }

  // Dimensions in the order their first parameter appears; the first varies slowest.
  struct Axis {
    std::vector<std::size_t> members;
    bool sample = false;
    std::size_t size = 0;
  };
  std::vector<Axis> dims;
  bool sample_placed = false;
  std::set<long> groups_placed;
  for (std::size_t k = 0; k < decls.size(); ++k) {
    if (decls[k].ranged) {
      if (!sample_placed) dims.push_back(Axis{ranged, true, sample_n});
      sample_placed = true;
    } else if (group_of[k] >= 0) {
      if (groups_placed.insert(group_of[k]).second)
        dims.push_back(Axis{groups[static_cast<std::size_t>(group_of[k])], false, decls[k].values.size()});
    } else {
      dims.push_back(Axis{{k}, false, decls[k].values.size()});
    }
  }
  std::size_t total = 1;
  for (const Axis& d : dims) total *= d.size;
  constexpr std::size_t kMaxCases = 100'000'000;
  if (total > kMaxCases)
    reader.fail(params, "parameters",
                "the sweep has " + std::to_string(total) + " cases, more than " + std::to_string(kMaxCases));
  sweep.cases.assign(total, std::vector<std::string>(decls.size()));
  for (std::size_t i = 0; i < total; ++i) {
    std::size_t rest = i;
    for (std::size_t d = dims.size(); d-- > 0;) {
      const std::size_t at = rest % dims[d].size;
      rest /= dims[d].size;
      for (std::size_t m = 0; m < dims[d].members.size(); ++m) {
        const std::size_t k = dims[d].members[m];
        sweep.cases[i][k] = dims[d].sample ? samples[at][m] : decls[k].values[at];
      }
    }
  }

  // Figures of merit: checked for their form here, for their names against the scene below.
  std::vector<YAML::Node> collect_nodes;  // where each collect entry's path is written
  if (const YAML::Node collect = root["collect"]) {
    if (!collect.IsMap()) reader.fail(collect, "collect", "must be a mapping name: path");
    for (const auto& entry : collect) {
      const std::string name = entry.first.as<std::string>();
      const std::string where = "collect." + name;
      const std::string p = reader.text(entry.second, where);
      std::vector<std::string> parts;
      std::stringstream split(p);
      for (std::string part; std::getline(split, part, '.');) parts.push_back(part);
      const auto bad = [&](const std::string& rule) { reader.fail(entry.second, where, "'" + p + "': " + rule); };
      if (parts.empty()) bad("empty");
      if (parts[0] == "probe") {
        if (parts.size() != 4) bad("a probe figure is probe.NAME.QUANTITY.(max|min|final|mean)");
        if (!quantity_from_string(parts[2])) bad("unknown quantity '" + parts[2] + "'");
        if (parts[3] != "max" && parts[3] != "min" && parts[3] != "final" && parts[3] != "mean")
          bad("a probe statistic is max, min, final or mean, not '" + parts[3] + "'");
      } else if (parts[0] == "event") {
        if (parts.size() < 3 || parts.size() > 4 ||
            (parts[2] != "first" && parts[2] != "last" && parts[2] != "count") ||
            (parts.size() == 4 && (parts[2] == "count" || (parts[3] != "t" && parts[3] != "x"))))
          bad("an event figure is event.KIND.(first|last)[.t|.x] or event.KIND.count");
      } else if (parts[0] == "body") {
        static const std::vector<std::string> fields = {"x_left", "x_right",        "velocity_mean",   "momentum",
                                                        "energy", "kinetic_energy", "internal_energy", "rest_energy"};
        if (parts.size() != 3) bad("a body figure is body.NAME.FIELD");
        if (std::find(fields.begin(), fields.end(), parts[2]) == fields.end())
          bad("unknown body field '" + parts[2] + "'; did you mean '" + closest_match(parts[2], fields) + "'?");
      } else {
        static const std::vector<std::string> scalars = {"t_end", "solver", "conservation", "stats"};
        if (std::find(scalars.begin(), scalars.end(), parts[0]) == scalars.end())
          bad("a figure is probe..., event..., body... or a scalar of summary.json (t_end, solver.X, "
              "conservation.X, stats.X)");
        if ((parts[0] == "t_end") != (parts.size() == 1)) bad("not a scalar of summary.json");
        if (parts[0] != "t_end" && parts.size() != 2) bad("not a scalar of summary.json");
        // stats and conservation have fixed fields; the solver's depend on its method.
        static const std::vector<std::string> stats = {"fronts", "interactions", "crossings_unvisited", "wall_time_s",
                                                       "sampling_time_s"};
        static const std::vector<std::string> conservation = {"energy_initial", "energy_final",     "energy_dissipated",
                                                              "wall_work",      "momentum_initial", "momentum_final",
                                                              "wall_impulse",   "energy_droplets",  "momentum_droplets",
                                                              "energy_waves",   "momentum_waves"};
        const std::vector<std::string>* fields = parts[0] == "stats"          ? &stats
                                                 : parts[0] == "conservation" ? &conservation
                                                                              : nullptr;
        if (fields != nullptr && std::find(fields->begin(), fields->end(), parts[1]) == fields->end())
          bad("unknown " + parts[0] + " field '" + parts[1] + "'; did you mean '" + closest_match(parts[1], *fields) +
              "'?");
      }
      sweep.collect.push_back(SweepCollect{name, p});
      collect_nodes.push_back(entry.second);
    }
  }
  check_collect_names(reader, sweep, collect_nodes);
  return sweep;
}

// ---- one case -----------------------------------------------------------------------------

namespace {

/// Keeps what the figures of merit need and drops the rest.
class CollectRecorder final : public RunRecorder {
 public:
  struct ProbeStat {
    int probe = -1;
    Quantity quantity = Quantity::p;
    double max = -INFINITY, min = INFINITY, final = 0.0, sum = 0.0;
    long count = 0;
  };
  struct EventStat {
    double first_t = 0.0, first_x = 0.0, last_t = 0.0, last_x = 0.0;
    long count = 0;
  };

  CollectRecorder(const Scene& scene, const Sweep& sweep, RunRecorder* files) : files_(files) {
    for (const SweepCollect& c : sweep.collect) {
      if (!c.path.starts_with("probe.")) continue;
      const auto second = c.path.find('.', 6);
      const std::string name = c.path.substr(6, second - 6);
      const auto third = c.path.find('.', second + 1);
      const Quantity q = *quantity_from_string(c.path.substr(second + 1, third - second - 1));
      const auto& probes = scene.outputs.probes;
      for (std::size_t i = 0; i < probes.size(); ++i)
        if (probes[i].name == name) probe_stats_[name + "." + std::string(to_string(q))] = {static_cast<int>(i), q};
    }
  }
  const ProbeStat* probe(const std::string& name_quantity) const {
    const auto it = probe_stats_.find(name_quantity);
    return it == probe_stats_.end() || it->second.count == 0 ? nullptr : &it->second;
  }
  const EventStat* event(const std::string& kind) const {
    const auto it = events_.find(kind);
    return it == events_.end() ? nullptr : &it->second;
  }

 private:
  void record_front(const FrontSegment& segment) override {
    if (files_) files_->front(segment);
  }
  void record_probe(const ProbeSample& sample) override {
    for (auto& [key, stat] : probe_stats_) {
      if (stat.probe != sample.probe || stat.quantity != sample.quantity) continue;
      stat.max = std::max(stat.max, sample.value);
      stat.min = std::min(stat.min, sample.value);
      stat.final = sample.value;
      stat.sum += sample.value;
      ++stat.count;
    }
    if (files_) files_->probe(sample);
  }
  void record_snapshot(const SnapshotSample& sample) override {
    if (files_) files_->snapshot(sample);
  }
  void record_event(const RunEvent& e) override {
    EventStat& stat = events_[e.kind];
    if (stat.count == 0) {
      stat.first_t = e.t;
      stat.first_x = e.x;
    }
    stat.last_t = e.t;
    stat.last_x = e.x;
    ++stat.count;
    if (files_) files_->event(e);
  }

  RunRecorder* files_;
  std::map<std::string, ProbeStat> probe_stats_;
  std::map<std::string, EventStat> events_;
};

std::optional<double> figure(const std::string& path, const Scene& scene, const RunResult& result,
                             const CollectRecorder& recorder) {
  const UnitSystem u = scene.units;
  std::vector<std::string> parts;
  std::stringstream split(path);
  for (std::string part; std::getline(split, part, '.');) parts.push_back(part);
  std::optional<double> value;
  if (parts[0] == "probe") {
    const Quantity q = *quantity_from_string(parts[2]);
    if (const auto* stat = recorder.probe(parts[1] + "." + parts[2])) {
      const double natural = parts[3] == "max"     ? stat->max
                             : parts[3] == "min"   ? stat->min
                             : parts[3] == "final" ? stat->final
                                                   : stat->sum / static_cast<double>(stat->count);
      value = from_natural(natural, dimension_of(q), u);
    }
  } else if (parts[0] == "event") {
    const auto* stat = recorder.event(parts[1]);
    if (parts[2] == "count") return stat ? static_cast<double>(stat->count) : 0.0;
    if (!stat) return std::nullopt;
    const bool x = parts.size() == 4 && parts[3] == "x";
    const double natural =
        parts[2] == "first" ? (x ? stat->first_x : stat->first_t) : (x ? stat->last_x : stat->last_t);
    value = from_natural(natural, x ? Dimension::length : Dimension::time, u);
  } else if (parts[0] == "body") {
    for (const BodyResult& b : result.bodies) {
      if (b.name != parts[1]) continue;
      const std::string& f = parts[2];
      if (f == "x_left") value = from_natural(b.x_left, Dimension::length, u);
      if (f == "x_right") value = from_natural(b.x_right, Dimension::length, u);
      if (f == "velocity_mean") value = from_natural(b.velocity_mean, Dimension::velocity, u);
      if (f == "momentum") value = from_natural(b.momentum, Dimension::momentum_per_area, u);
      if (f == "energy") value = from_natural(b.energy, Dimension::energy_per_area, u);
      if (f == "kinetic_energy") value = from_natural(b.kinetic_energy, Dimension::energy_per_area, u);
      if (f == "internal_energy") value = from_natural(b.internal_energy, Dimension::energy_per_area, u);
      if (f == "rest_energy") value = from_natural(b.rest_energy, Dimension::energy_per_area, u);
    }
  } else if (parts[0] == "t_end") {
    value = from_natural(result.t_reached, Dimension::time, u);
  } else if (parts[0] == "solver") {
    for (const auto& [name, number] : result.solver_numbers)
      if (name == parts[1]) value = number;
  } else if (parts[0] == "stats") {
    if (parts[1] == "fronts") value = static_cast<double>(result.stats.fronts);
    if (parts[1] == "interactions") value = static_cast<double>(result.stats.interactions);
    if (parts[1] == "crossings_unvisited") value = static_cast<double>(result.stats.crossings_unvisited);
    if (parts[1] == "wall_time_s") value = result.stats.wall_time_s;
    if (parts[1] == "sampling_time_s") value = result.stats.sampling_time_s;
  } else if (parts[0] == "conservation") {
    const Conservation& c = result.conservation;
    const Dimension E = Dimension::energy_per_area, P = Dimension::momentum_per_area;
    if (parts[1] == "energy_initial") value = from_natural(c.energy_initial, E, u);
    if (parts[1] == "energy_final") value = from_natural(c.energy_final, E, u);
    if (parts[1] == "energy_dissipated") value = from_natural(c.energy_dissipated, E, u);
    if (parts[1] == "wall_work") value = from_natural(c.wall_work, E, u);
    if (parts[1] == "momentum_initial") value = from_natural(c.momentum_initial, P, u);
    if (parts[1] == "momentum_final") value = from_natural(c.momentum_final, P, u);
    if (parts[1] == "wall_impulse") value = from_natural(c.wall_impulse, P, u);
    if (parts[1] == "energy_droplets") value = from_natural(c.energy_droplets, E, u);
    if (parts[1] == "momentum_droplets") value = from_natural(c.momentum_droplets, P, u);
    if (parts[1] == "energy_waves") value = from_natural(c.energy_waves, E, u);
    if (parts[1] == "momentum_waves") value = from_natural(c.momentum_waves, P, u);
  }
  if (value && !std::isfinite(*value)) return std::nullopt;  // never a NaN in the table
  return value;
}

std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

}  // namespace

SweepRow run_sweep_case(const Sweep& sweep, std::size_t index, const std::string& case_dir) {
  SweepRow row;
  row.index = index;
  row.figures.assign(sweep.collect.size(), std::nullopt);
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> overrides;
  for (std::size_t k = 0; k < sweep.parameters.size(); ++k)
    overrides.push_back(sweep.parameters[k] + "=" + sweep.cases[index][k]);
  try {
    // A material key the case's model lacks (wave_speed swept beside model: [rigid, hooke])
    // is dropped for that case, with a note in its message (docs/sweeps.md).
    std::string notes;
    const auto load = [&sweep, &overrides, &notes]() {
      for (;;) {
        try {
          return sweep.scene_path.empty() ? load_scene_string(default_scene_text(), "<default>", overrides)
                                          : load_scene_file(sweep.scene_path, overrides);
        } catch (const InputError& e) {
          const auto lacked = std::find_if(overrides.begin(), overrides.end(), [&e](const std::string& o) {
            return o.starts_with("materials.") && o.starts_with(e.key() + "=");
          });
          if (lacked == overrides.end() || !e.message().starts_with("unknown key")) throw;
          notes += (notes.empty() ? "" : "; ") + e.key() + " ignored: the case's model has no such parameter";
          overrides.erase(lacked);
        }
      }
    };
    const Scene scene = load();
    std::optional<StreamingRecorder> files;
    if (!case_dir.empty()) files.emplace(scene, case_dir);
    CollectRecorder recorder(scene, sweep, files ? &*files : nullptr);
    RunResult result;
    try {
      result = solve(scene, recorder);
    } catch (const InadmissibleStop& stop) {
      // No classical solution from some instant on: the case's outputs up to then are kept
      // (its figures are not taken from a run cut short by its physics).
      if (files) files->commit(stop.result());
      throw;
    }
    if (files) files->commit(result);
    row.status = result.status;
    row.exit_code = result.status == to_string(RunStatus::ok)        ? kExitOk
                    : result.status == to_string(RunStatus::stopped) ? kExitStopped
                                                                     : kExitInterrupted;
    row.message = one_line(result.stop_reason.empty() ? notes
                           : notes.empty()            ? result.stop_reason
                                                      : result.stop_reason + "; " + notes);
    for (std::size_t c = 0; c < sweep.collect.size(); ++c)
      row.figures[c] = figure(sweep.collect[c].path, scene, result, recorder);
  } catch (const InputError& e) {
    row.status = "invalid";
    row.exit_code = kExitInvalidInput;
    row.message = one_line(e.what());
  } catch (const InadmissibleStop& e) {
    row.status = "inadmissible";
    row.exit_code = kExitInadmissible;
    row.message = one_line(std::string(e.what()) + "; " + e.result().verdict);
  } catch (const InadmissibleError& e) {
    row.status = "inadmissible";
    row.exit_code = kExitInadmissible;
    row.message = one_line(e.what());
  } catch (const std::exception& e) {
    row.status = "failed";
    row.exit_code = kExitInternal;
    row.message = one_line(e.what());
  }
  row.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

// ---- the table ------------------------------------------------------------------------------

namespace {

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

/// A parameter value in JSON: a number if it reads as one, else a string.
std::string json_value(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (!text.empty() && end == text.c_str() + text.size() && std::isfinite(value)) return shortest(value);
  return json_string(text);
}

std::string row_prefix(const Sweep& sweep, std::size_t index) {
  std::string line = std::to_string(index);
  for (const std::string& value : sweep.cases[index]) line += "," + csv_cell(value);
  return line + ",";
}

std::string join_header(const Sweep& sweep) {
  std::string line;
  for (const std::string& h : sweep_header(sweep)) line += (line.empty() ? "" : ",") + csv_cell(h);
  return line;
}

void write_json(const Sweep& sweep, const fs::path& file) {
  std::ofstream out(file);
  out << "{\n  \"source\": " << json_string(sweep.source)
      << ",\n  \"scene\": " << (sweep.scene_path.empty() ? std::string("\"<default>\"") : json_string(sweep.scene_path))
      << ",\n  \"parameters\": [";
  for (std::size_t k = 0; k < sweep.parameters.size(); ++k) out << (k ? ", " : "") << json_string(sweep.parameters[k]);
  out << "],\n  \"collect\": {";
  for (std::size_t c = 0; c < sweep.collect.size(); ++c)
    out << (c ? ", " : "") << json_string(sweep.collect[c].name) << ": " << json_string(sweep.collect[c].path);
  out << "},\n  \"keep_outputs\": " << (sweep.keep_outputs ? "true" : "false") << ",\n  \"cases\": [\n";
  for (std::size_t i = 0; i < sweep.cases.size(); ++i) {
    out << "    {\"case\": " << i;
    for (std::size_t k = 0; k < sweep.parameters.size(); ++k)
      out << ", " << json_string(sweep.parameters[k]) << ": " << json_value(sweep.cases[i][k]);
    out << "}" << (i + 1 < sweep.cases.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
  if (!out) throw OutputError("cannot write " + file.string());
}

/// The complete rows of sweep.csv for this sweep, by case index (a row cut short by a kill is dropped).
std::map<std::size_t, std::string> read_rows(const Sweep& sweep, const fs::path& file) {
  std::map<std::size_t, std::string> rows;
  std::ifstream in(file, std::ios::binary);
  if (!in) return rows;
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::size_t start = 0;
  bool header = true;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // no line end: cut short
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    if (header) {
      if (line != join_header(sweep))
        throw OutputRefused(file.string() + " holds another sweep's table (its header differs); give another --out");
      header = false;
      continue;
    }
    std::size_t index = 0;
    const auto comma = line.find(',');
    try {
      index = std::stoul(line.substr(0, comma));
    } catch (const std::exception&) {
      continue;
    }
    if (index < sweep.cases.size() && line.starts_with(row_prefix(sweep, index))) rows[index] = line;
  }
  return rows;
}

}  // namespace

std::vector<std::string> sweep_header(const Sweep& sweep) {
  std::vector<std::string> header{"case"};
  header.insert(header.end(), sweep.parameters.begin(), sweep.parameters.end());
  header.insert(header.end(), {"status", "exit_code", "message"});
  for (const SweepCollect& c : sweep.collect) header.push_back(c.name);
  header.emplace_back("wall_time_s");
  return header;
}

std::string sweep_csv_row(const Sweep& sweep, const SweepRow& row) {
  std::string line = row_prefix(sweep, row.index);
  line += csv_cell(row.status) + "," + std::to_string(row.exit_code) + "," + csv_cell(row.message);
  for (const auto& f : row.figures) line += "," + (f ? shortest(*f) : std::string());
  line += "," + shortest(row.wall_time_s);
  return line;
}

SweepOutcome run_sweep(const Sweep& sweep, const SweepOptions& options, const SweepExecutor& executor) {
  const fs::path dir(options.out_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw OutputError("cannot make " + dir.string() + ": " + ec.message());
  const fs::path csv = dir / "sweep.csv";
  std::map<std::size_t, std::string> rows = read_rows(sweep, csv);
  write_json(sweep, dir / "sweep.json");

  SweepOutcome outcome;
  outcome.skipped = rows.size();
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < sweep.cases.size(); ++i)
    if (!rows.contains(i)) pending.push_back(i);

  // Rewrite what was kept (dropping a line cut short), then append rows as cases finish.
  {
    std::ofstream out(csv, std::ios::binary | std::ios::trunc);
    out << join_header(sweep) << "\n";
    for (const auto& entry : rows) out << entry.second << "\n";
    if (!out) throw OutputError("cannot write " + csv.string());
  }
  std::ofstream append(csv, std::ios::binary | std::ios::app);
  const SweepRowSink done = [&](std::size_t index, int exit_code, const std::string& line) {
    append << line << "\n" << std::flush;
    rows[index] = line;
    ++outcome.run;
    if (exit_code != 0) ++outcome.failed;
    if (options.progress) options.progress(rows.size(), sweep.cases.size());
  };
  if (!pending.empty()) executor(pending, done);
  append.close();
  if (!append) throw OutputError("cannot write " + csv.string());
  outcome.interrupted = rows.size() < sweep.cases.size();

  // Complete: the table in case order.
  if (!outcome.interrupted) {
    const fs::path partial = dir / "sweep.csv.partial";
    {
      std::ofstream out(partial, std::ios::binary | std::ios::trunc);
      out << join_header(sweep) << "\n";
      for (const auto& entry : rows) out << entry.second << "\n";
      if (!out) throw OutputError("cannot write " + partial.string());
    }
    fs::rename(partial, csv, ec);
    if (ec) throw OutputError("cannot write " + csv.string() + ": " + ec.message());
  }
  return outcome;
}

SweepOutcome run_sweep(const Sweep& sweep, const SweepOptions& options) {
  const SweepExecutor threads = [&sweep, &options](const std::vector<std::size_t>& pending, const SweepRowSink& done) {
    std::mutex lock;
    std::atomic<std::size_t> next{0};
    const auto worker = [&]() {
      for (;;) {
        if (interrupt_requested()) return;
        const std::size_t at = next.fetch_add(1);
        if (at >= pending.size()) return;
        const std::size_t index = pending[at];
        const SweepRow row = run_sweep_case(sweep, index, sweep_case_dir(sweep, options.out_dir, index));
        if (row.status == "interrupted") return;  // cut short: run again next time
        const std::string line = sweep_csv_row(sweep, row);
        const std::lock_guard<std::mutex> guard(lock);
        done(index, row.exit_code, line);
      }
    };
    const unsigned jobs = std::max(1u, std::min<unsigned>(options.jobs, static_cast<unsigned>(pending.size())));
    // Plugins (the scene's, RIGIDITY_PLUGIN_PATH's) are loaded into the material registry as a
    // scene is read; the registry is read without a lock, so load them once before the
    // threads start, and the cases only read it.
    if (jobs > 1) warm_up(sweep);
    if (jobs == 1) {
      worker();
    } else {
      std::vector<std::thread> workers;
      for (unsigned j = 0; j < jobs; ++j) workers.emplace_back(worker);
      for (std::thread& t : workers) t.join();
    }
  };
  return run_sweep(sweep, options, threads);
}

std::string sweep_case_dir(const Sweep& sweep, const std::string& out_dir, std::size_t index) {
  if (!sweep.keep_outputs) return "";
  char name[32];
  std::snprintf(name, sizeof name, "%04zu", index);
  return (fs::path(out_dir) / "cases" / name).string();
}

void warm_up(const Sweep& sweep) {
  try {
    static_cast<void>(sweep.scene_path.empty() ? load_scene_string(default_scene_text(), "<default>")
                                               : load_scene_file(sweep.scene_path));
  } catch (const std::exception&) {
    // The cases report their own errors.
  }
}

}  // namespace rigidity
