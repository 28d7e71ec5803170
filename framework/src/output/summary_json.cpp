// summary.json (docs/cli.md, "What a run writes"): the run at a glance, in the scene's units.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigidity/json_writer.hpp"
#include "rigidity/output.hpp"

namespace rigidity {

namespace {

std::string_view method_name(SolverMethod method) {
  switch (method) {
    case SolverMethod::characteristics: return "characteristics";
    case SolverMethod::finite_volume: return "finite_volume";
  }
  return "?";
}

/// Writes values converted from natural units to the scene's.
class SummaryWriter {
 public:
  explicit SummaryWriter(UnitSystem units) : units_(units) {}

  void member(std::string_view key, double natural_value, Dimension d) {
    json_.key(key).number(from_natural(natural_value, d, units_));
  }

  void units() {
    constexpr std::pair<std::string_view, Dimension> kDimensions[] = {
        {"time", Dimension::time},
        {"length", Dimension::length},
        {"velocity", Dimension::velocity},
        {"density", Dimension::density},
        {"pressure", Dimension::pressure},
        {"energy_per_area", Dimension::energy_per_area},
        {"momentum_per_area", Dimension::momentum_per_area},
    };
    json_.key("units").begin_object();
    json_.key("system").text(units_ == UnitSystem::si ? "si" : "natural");
    for (const auto& [key, dimension] : kDimensions) json_.key(key).text(unit_symbol(dimension, units_));
    json_.end_object();
  }

  JsonWriter& json() { return json_; }

 private:
  UnitSystem units_;
  JsonWriter json_{"summary.json"};
};

}  // namespace

std::string summary_json(const Scene& scene, const RunResult& result) {
  SummaryWriter w(scene.units);
  JsonWriter& json = w.json();
  json.begin_object();
  json.key("scene").text(scene.name);
  json.key("status").text(result.status);
  const bool ok = result.status == to_string(RunStatus::ok);
  if (!ok) json.key("stop_reason").text(result.stop_reason);
  w.member("t_end", scene.t_end, Dimension::time);
  w.member("t_reached", ok ? scene.t_end : result.t_reached, Dimension::time);
  if (result.inadmissible) {
    // Where the run met no classical solution, how far beyond its limit the material would
    // have been taken, and whether the run's error bound there could move or remove the stop.
    const Inadmissibility& at = *result.inadmissible;
    const auto value = [&](std::string_view key, double natural_value, Dimension d) {
      if (std::isfinite(natural_value)) {
        w.member(key, natural_value, d);
      } else {
        json.key(key).null();
      }
    };
    json.key("inadmissible").begin_object();
    value("t", at.t, Dimension::time);
    value("x", at.x, Dimension::length);
    json.key("material").text(at.material);
    json.key("in_tension").boolean(at.in_tension);
    value("relative_speed", at.relative_speed, Dimension::velocity);
    value("psi_needed", at.psi_needed, Dimension::dimensionless);
    value("psi_limit", at.psi_limit, Dimension::dimensionless);
    value("margin", at.margin(), Dimension::dimensionless);
    value("error_bound", result.solver_number("error_bound"), Dimension::dimensionless);
    json.key("verdict_uncertain").boolean(result.verdict_uncertain);
    json.key("verdict").text(result.verdict);
    json.end_object();
  }

  json.key("solver").begin_object();
  json.key("method").text(result.solver.empty() ? method_name(scene.solver.method) : std::string_view(result.solver));
  for (const auto& [name, value] : result.solver_numbers) json.key(name).number(value);
  json.end_object();

  json.key("warnings").begin_array();
  for (const std::string& warning : result.warnings) json.text(warning);
  json.end_array();

  // Every event is in events.csv; here their counts by kind and the first ones.
  std::vector<std::pair<std::string, long>> counts = result.event_counts;
  if (counts.empty()) {
    for (const RunEvent& event : result.events) {
      const auto c = std::find_if(counts.begin(), counts.end(), [&](const auto& k) { return k.first == event.kind; });
      if (c == counts.end()) {
        counts.emplace_back(event.kind, 1);
      } else {
        ++c->second;
      }
    }
  }
  json.key("event_counts").begin_object(JsonLayout::line);
  for (const auto& [kind, count] : counts) json.key(kind).integer(count);
  json.end_object();

  json.key("events").begin_array();
  const std::size_t listed = std::min(result.events.size(), RunRecorder::kFirstEvents);
  for (std::size_t i = 0; i < listed; ++i) {
    const RunEvent& event = result.events[i];
    json.begin_object(JsonLayout::line);
    w.member("t", event.t, Dimension::time);
    json.key("kind").text(event.kind);
    w.member("x", event.x, Dimension::length);
    json.key("bodies").begin_array();
    for (const std::string& body : event.bodies) json.text(body);
    json.end_array();
    json.end_object();
  }
  json.end_array();

  json.key("bodies").begin_array();
  for (const BodyResult& body : result.bodies) {
    json.begin_object(JsonLayout::line);
    json.key("name").text(body.name);
    w.member("x_left", body.x_left, Dimension::length);
    w.member("x_right", body.x_right, Dimension::length);
    w.member("velocity_mean", body.velocity_mean, Dimension::velocity);
    w.member("momentum", body.momentum, Dimension::momentum_per_area);
    w.member("energy", body.energy, Dimension::energy_per_area);
    w.member("kinetic_energy", body.kinetic_energy, Dimension::energy_per_area);
    w.member("internal_energy", body.internal_energy, Dimension::energy_per_area);
    w.member("rest_energy", body.rest_energy, Dimension::energy_per_area);
    json.end_object();
  }
  json.end_array();

  const Conservation& c = result.conservation;
  json.key("conservation").begin_object();
  w.member("energy_initial", c.energy_initial, Dimension::energy_per_area);
  w.member("energy_final", c.energy_final, Dimension::energy_per_area);
  w.member("energy_dissipated", c.energy_dissipated, Dimension::energy_per_area);
  w.member("momentum_initial", c.momentum_initial, Dimension::momentum_per_area);
  w.member("momentum_final", c.momentum_final, Dimension::momentum_per_area);
  w.member("wall_impulse", c.wall_impulse, Dimension::momentum_per_area);
  // Beyond docs/cli.md, "What a run writes": the energy walls and pistons gave, so that the energy balance
  // energy_final = energy_initial + wall_work - energy_dissipated can be checked too.
  w.member("wall_work", c.wall_work, Dimension::energy_per_area);
  if (c.energy_droplets != 0.0 || c.momentum_droplets != 0.0) {
    // energy_final = energy_initial + wall_work - energy_dissipated + energy_droplets, and
    // momentum_final = momentum_initial + wall_impulse + momentum_droplets.
    w.member("energy_droplets", c.energy_droplets, Dimension::energy_per_area);
    w.member("momentum_droplets", c.momentum_droplets, Dimension::momentum_per_area);
  }
  if (c.energy_waves != 0.0 || c.momentum_waves != 0.0) {
    // What smooth steps and weak waves held back made, added to the balance as the droplets' is.
    w.member("energy_waves", c.energy_waves, Dimension::energy_per_area);
    w.member("momentum_waves", c.momentum_waves, Dimension::momentum_per_area);
  }
  json.end_object();

  json.key("stats").begin_object();
  json.key("fronts").integer(result.stats.fronts);
  json.key("interactions").integer(result.stats.interactions);
  if (result.stats.crossings_unvisited > 0) json.key("crossings_unvisited").integer(result.stats.crossings_unvisited);
  json.key("wall_time_s").number(result.stats.wall_time_s);
  json.key("sampling_time_s").number(result.stats.sampling_time_s);
  json.end_object();

  w.units();
  json.end_object();
  return json.take();
}

}  // namespace rigidity
