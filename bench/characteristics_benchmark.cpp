// Front-tracking throughput: interactions per second for a bar of many segments
// ringing between bonded walls, and the paper's scene end to end.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace {

/// A bar of `segments` pieces with alternating small velocities and stretches,
/// between bonded walls: every segment boundary launches a front of each family,
/// and the fronts cross each other about segments² times per light-crossing time.
std::string ringing_bar(const char* material, int segments, double t_end) {
  std::string yaml = "name: ringing_bar\nmaterials:\n  m: " + std::string(material) +
                     "\nbodies:\n  - name: bar\n    material: m\n    segments:\n";
  const double length = 1.0 / segments;
  char line[160];
  for (int i = 0; i < segments; ++i) {
    std::snprintf(line, sizeof line, "      - {length: %.17g, velocity: %g, stretch: %g}\n", length,
                  (i % 2 == 0 ? 0.01 : -0.01), (i % 3 == 0 ? 1.001 : 0.999));
    yaml += line;
  }
  std::snprintf(line, sizeof line,
                "boundaries:\n  left: {type: wall, bonded: true}\n  right: {type: wall, bonded: true}\n"
                "time: {end: %g}\n",
                t_end);
  return yaml + line;
}

void run_ringing_bar(benchmark::State& state, const char* material) {
  const int segments = static_cast<int>(state.range(0));
  const rigidity::Scene scene = rigidity::load_scene_string(ringing_bar(material, segments, 0.5), "<bench>");
  long interactions = 0;
  long fronts = 0;
  for (auto _ : state) {
    const rigidity::RunResult r = rigidity::solve(scene);
    if (r.status != "ok") {
      state.SkipWithError(("the run stopped early: " + r.stop_reason).c_str());
      break;
    }
    interactions += r.stats.interactions;
    fronts = r.stats.fronts;
    benchmark::DoNotOptimize(r.conservation.energy_final);
  }
  state.SetItemsProcessed(interactions);
  state.counters["interactions"] = static_cast<double>(interactions) / static_cast<double>(state.iterations());
  state.counters["fronts"] = static_cast<double>(fronts);
}

void BM_RingingBarRigid(benchmark::State& state) { run_ringing_bar(state, "{model: rigid}"); }
void BM_RingingBarHooke(benchmark::State& state) { run_ringing_bar(state, "{model: hooke, wave_speed: 0.5}"); }
BENCHMARK(BM_RingingBarRigid)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RingingBarHooke)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

/// The paper's scene: load (parse and validate) and solve, outputs collected in memory.
void BM_PaperSceneLoadAndSolve(benchmark::State& state) {
  for (auto _ : state) {
    const rigidity::Scene scene = rigidity::load_scene_string(rigidity::default_scene_text(), "<default>");
    const rigidity::RunResult r = rigidity::solve(scene);
    benchmark::DoNotOptimize(r.stats.interactions);
  }
}
BENCHMARK(BM_PaperSceneLoadAndSolve)->Unit(benchmark::kMicrosecond);

}  // namespace
