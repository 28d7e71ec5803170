// Material evaluations per material — p, e, c_s, Ψ and the inverses s(p), s(Ψ) —
// closed forms of the built-ins against the generic numeric path (GSL), and one
// exact Riemann solve per material pair.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rigidity/numeric_material.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace {

/// A required number with a bounded range: the middle of it (hooke's and
/// constant_sound_speed's wave speeds: 0.5).
std::optional<double> middle_of_range(const rigidity::ParameterSpec& p) {
  if (p.type != rigidity::ParameterType::number || !p.lower || !p.upper) return std::nullopt;
  return 0.5 * (p.lower->value + p.upper->value);
}

/// Every registered material, by name, built from its declared defaults and the middle of the
/// range of each required number (a required text, such as a table, leaves it out).
std::vector<std::pair<std::string, std::shared_ptr<const rigidity::Material>>> registered_materials() {
  std::vector<std::pair<std::string, std::shared_ptr<const rigidity::Material>>> out;
  for (const std::string& name : rigidity::MaterialRegistry::instance().names()) {
    const rigidity::MaterialInfo* info = rigidity::MaterialRegistry::instance().find(name);
    rigidity::ParameterValues given;
    bool buildable = true;
    for (const rigidity::ParameterSpec& p : info->parameters) {
      if (!p.required) continue;
      const std::optional<double> v = middle_of_range(p);
      if (v) {
        given.set(p.name, *v);
      } else {
        buildable = false;  // needs a parameter only a scene can give
      }
    }
    if (!buildable) continue;
    try {
      out.emplace_back(name, rigidity::build_material(*info, given));
    } catch (const std::invalid_argument&) {
      // its parameters at the middle of their ranges are refused: left out
    }
  }
  return out;
}

/// The rigid law given only as p(s): everything else comes from GSL quadrature,
/// differentiation and root finding (the generic path a plugin author gets).
class RigidPressureLaw final : public rigidity::PressureLawMaterial {
 public:
  RigidPressureLaw() : PressureLawMaterial(1.0) {}
  [[nodiscard]] std::string_view model() const override { return "rigid_as_pressure_law"; }
  [[nodiscard]] double pressure_law(double s) const override { return 0.5 * (1.0 / (s * s) - 1.0); }
};

/// Stretches spread over compression and traction, as ln s.
std::vector<rigidity::Stretch> stretches(const rigidity::Material& m) {
  std::vector<rigidity::Stretch> out;
  const double hi = std::min(m.admissible().log_max, 1.0);
  for (int i = 0; i < 64; ++i) out.push_back(rigidity::Stretch::from_log(-1.0 + (hi + 1.0) * i / 63.0));
  return out;
}

template <class Eval>
void evaluate(benchmark::State& state, const rigidity::Material& m, Eval eval) {
  const std::vector<rigidity::Stretch> grid = stretches(m);
  for (auto _ : state)
    for (rigidity::Stretch s : grid) benchmark::DoNotOptimize(eval(m, s));
  state.SetItemsProcessed(static_cast<long>(state.iterations()) * static_cast<long>(grid.size()));
}

void register_material(const std::string& label, std::shared_ptr<const rigidity::Material> m) {
  using rigidity::Material;
  using rigidity::Stretch;
  benchmark::RegisterBenchmark(("pressure/" + label).c_str(), [m](benchmark::State& st) {
    evaluate(st, *m, [](const Material& mm, Stretch s) { return mm.pressure(s); });
  });
  benchmark::RegisterBenchmark(("energy_density/" + label).c_str(), [m](benchmark::State& st) {
    evaluate(st, *m, [](const Material& mm, Stretch s) { return mm.energy_density(s); });
  });
  benchmark::RegisterBenchmark(("sound_speed/" + label).c_str(), [m](benchmark::State& st) {
    evaluate(st, *m, [](const Material& mm, Stretch s) { return mm.sound_speed(s); });
  });
  benchmark::RegisterBenchmark(("riemann_psi/" + label).c_str(), [m](benchmark::State& st) {
    evaluate(st, *m, [](const Material& mm, Stretch s) { return mm.riemann_psi(s); });
  });
  benchmark::RegisterBenchmark(("stretch_at_pressure/" + label).c_str(), [m](benchmark::State& st) {
    evaluate(st, *m, [](const Material& mm, Stretch s) { return mm.stretch_at_pressure(mm.pressure(s)).value.log(); });
  });
  benchmark::RegisterBenchmark(("stretch_at_psi/" + label).c_str(), [m](benchmark::State& st) {
    evaluate(st, *m, [](const Material& mm, Stretch s) { return mm.stretch_at_psi(mm.riemann_psi(s)).value.log(); });
  });
}

/// One exact Riemann problem: two bars at ±0.3 c of materials a and b colliding.
void register_riemann(const std::string& a, const std::shared_ptr<const rigidity::Material>& ma, const std::string& b,
                      const std::shared_ptr<const rigidity::Material>& mb) {
  benchmark::RegisterBenchmark(("riemann/" + a + "|" + b).c_str(), [ma, mb](benchmark::State& st) {
    const rigidity::State left{std::atanh(0.3), rigidity::Stretch::natural()};
    const rigidity::State right{-std::atanh(0.3), rigidity::Stretch::from_value(0.95)};
    for (auto _ : st) benchmark::DoNotOptimize(rigidity::solve_riemann(*ma, left, *mb, right, 0.0).pressure);
    st.SetItemsProcessed(static_cast<long>(st.iterations()));
  });
}

const bool registered = [] {
  const auto materials = registered_materials();
  for (const auto& [name, material] : materials) register_material(name, material);
  register_material("rigid_as_pressure_law(numeric)", std::make_shared<const RigidPressureLaw>());
  for (const auto& a : materials)
    for (const auto& b : materials) register_riemann(a.first, a.second, b.first, b.second);
  return true;
}();

}  // namespace
