// What a front-tracking run that reached a budget tells its user.
#include "rigidity/solvers/budget.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <set>
#include <string_view>
#include <vector>

#include "characteristics/policy.hpp"
#include "rigidity/units.hpp"

namespace rigidity {

namespace {

std::string readable(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string count(long value) {
  char text[32];
  if (value >= 1000000 && value % 1000000 == 0) {
    std::snprintf(text, sizeof text, "%ld million", value / 1000000);
  } else {
    std::snprintf(text, sizeof text, "%ld", value);
  }
  return text;
}

std::string join(const std::vector<std::string>& items, std::string_view last_separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += i + 1 == items.size() ? std::string(last_separator) : std::string(", ");
    out += items[i];
  }
  return out;
}

/// What in the scene makes fronts multiply.
struct SceneTraits {
  std::vector<std::string> fanned;   ///< materials whose rarefaction fans are split into steps
  std::vector<std::string> parting;  ///< materials that cavitate (part and rejoin)
  bool interfaces = false;           ///< a body of several materials
  bool several_bodies = false;
  bool pistons = false;
  std::size_t segments = 0;  ///< initial jumps: segments beyond one per body
};

SceneTraits traits_of(const Scene& scene) {
  SceneTraits out;
  std::set<std::string> fanned, parting;
  for (const BodyDecl& body : scene.bodies) {
    out.segments += body.segments.size() - 1;
    for (const Segment& seg : body.segments) {
      const Material& m = scene.material_of(seg);
      if (!m.linearly_degenerate()) fanned.insert(seg.material);
      if (m.cavitation_pressure() > -std::numeric_limits<double>::infinity()) parting.insert(seg.material);
      if (seg.material != body.segments.front().material) out.interfaces = true;
    }
  }
  out.fanned.assign(fanned.begin(), fanned.end());
  out.parting.assign(parting.begin(), parting.end());
  out.several_bodies = scene.bodies.size() > 1;
  out.pistons = scene.left.type == BoundaryType::piston || scene.right.type == BoundaryType::piston;
  return out;
}

}  // namespace

std::string budget_stop_reason(const Scene& scene, Budget budget, double t) {
  const std::string unit(unit_symbol(Dimension::time, scene.units));
  const std::string at = readable(from_natural(t, Dimension::time, scene.units));
  const std::string end = readable(from_natural(scene.t_end, Dimension::time, scene.units));
  const SceneTraits traits = traits_of(scene);

  std::string out;
  if (budget == Budget::fronts) {
    out = "more than solver.max_fronts = " + count(scene.solver.max_fronts) + " fronts alive at t = " + at + " " +
          unit + " (of t_end = " + end + " " + unit + ")";
  } else {
    out = "more than solver.max_interactions = " + count(scene.solver.max_interactions) + " interactions by t = " + at +
          " " + unit + " (of t_end = " + end + " " + unit + ")";
  }
  out += "; the outputs up to t = " + at + " " + unit + " are written.";

  // Why: what makes fronts multiply in this scene.
  std::vector<std::string> why;
  if (!traits.fanned.empty())
    why.push_back("the rarefaction fans of " + join(traits.fanned, " and ") +
                  ", once something reaches them, are split into steps of " +
                  readable(characteristics::ResolutionPolicy::fan_step_for(scene.solver.wave_resolution())) +
                  " in their Riemann invariant (0.7 √solver.tolerance), and every step that reaches a contact or an "
                  "end makes new fronts");
  if (traits.interfaces || traits.several_bodies || !traits.parting.empty())
    why.push_back(std::string("every reflection and transmission at ") +
                  (traits.interfaces ? "a material interface, " : "") + (traits.several_bodies ? "a contact, " : "") +
                  "an end or a wall splits a front in two, and every piece is tracked");
  if (!traits.parting.empty())
    why.push_back(join(traits.parting, " and ") + " can cavitate and rejoin, again and again");
  if (budget == Budget::interactions && traits.fanned.empty() && !traits.interfaces && !traits.several_bodies &&
      traits.parting.empty())
    why.push_back("the fronts of " + std::to_string(traits.segments + 1) +
                  " initial segments cross each other and reflect at the ends, about (segments)^2 interactions "
                  "per crossing time");
  if (!why.empty()) out += " Here " + join(why, "; ") + ".";

  // What to change, the likeliest help first.
  std::vector<std::string> advice;
  if (!traits.fanned.empty())
    advice.push_back("coarsen solver.tolerance (e.g. " + readable(std::max(scene.solver.tolerance * 100.0, 1e-6)) +
                     "): fewer fan steps");
  advice.push_back("shorten time.end to about " + at + " " + unit);
  if (!traits.fanned.empty() || traits.interfaces || traits.several_bodies || !traits.parting.empty() || traits.pistons)
    advice.push_back("use solver.method: finite_volume, whose cost grows only linearly with time.end");
  if (budget == Budget::fronts) {
    // A front costs about 210 bytes of memory (its node with what its region remembers, 184
    // bytes; its queue entry and place in the queue).
    advice.push_back("raise solver.max_fronts (" + count(scene.solver.max_fronts) + " fronts take about " +
                     readable(210.0 * static_cast<double>(scene.solver.max_fronts) / 1e6) + " MB)");
  } else {
    advice.push_back("raise solver.max_interactions if the run is worth the time");
  }
  out += " To go further: " + join(advice, ", or ") + ".";
  return out;
}

}  // namespace rigidity
