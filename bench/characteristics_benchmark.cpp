// Front-tracking throughput: crossings per second for a bar of many segments ringing
// between bonded walls (in a light or lattice piece, or visited one by one), and the
// paper's scene end to end.
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

/// Takes what a run records and keeps nothing: the benchmarks time the solve.
class DiscardingRecorder final : public rigidity::RunRecorder {
  void record_front(const rigidity::FrontSegment&) override {}
  void record_probe(const rigidity::ProbeSample&) override {}
  void record_snapshot(const rigidity::SnapshotSample&) override {}
  void record_event(const rigidity::RunEvent&) override {}
};

/// `extra`: the scene's outputs or solver line, if any.
void run_ringing_bar(benchmark::State& state, const char* material, const char* extra = "") {
  const int segments = static_cast<int>(state.range(0));
  const rigidity::Scene scene = rigidity::load_scene_string(ringing_bar(material, segments, 0.5) + extra, "<bench>");
  long interactions = 0;
  long crossings = 0;
  long fronts = 0;
  for (auto _ : state) {
    DiscardingRecorder recorder;
    const rigidity::RunResult r = rigidity::solve(scene, recorder);
    if (r.status != "ok") {
      state.SkipWithError(("the run stopped early: " + r.stop_reason).c_str());
      break;
    }
    interactions += r.stats.interactions;
    crossings += r.stats.crossings_unvisited;
    fronts = r.stats.fronts;
    benchmark::DoNotOptimize(r.conservation.energy_final);
  }
  // Items: every crossing of two fronts and every other Riemann problem, whether the tracker
  // visited it (interactions) or knew it without a visit (a light or lattice piece).
  const double runs = static_cast<double>(state.iterations());
  state.SetItemsProcessed(interactions + crossings);
  state.counters["interactions"] = static_cast<double>(interactions) / runs;
  state.counters["unvisited"] = static_cast<double>(crossings) / runs;
  state.counters["fronts"] = static_cast<double>(fronts);
}

void BM_RingingBarRigid(benchmark::State& state) { run_ringing_bar(state, "{model: rigid}"); }
void BM_RingingBarHooke(benchmark::State& state) { run_ringing_bar(state, "{model: hooke, wave_speed: 0.5}"); }
/// The same Hooke bar with fronts.csv asked for: its fronts' paths have a vertex at every
/// crossing, so the tracker visits every crossing on its node list (no lattice piece), the
/// kernel every body that touches others of other materials runs. The segments go nowhere.
void BM_RingingBarHookeVisited(benchmark::State& state) {
  run_ringing_bar(state, "{model: hooke, wave_speed: 0.5}", "outputs: {fronts: true}\n");
}
/// A bar of a genuinely nonlinear material at the tolerance of the random scenes: each crossing
/// finds its star on the two wave curves (a Hugoniot where a wave is a shock) and the label
/// jump speed and dissipation of its two new fronts, the kernel of a gas bar among others.
void BM_RingingBarGas(benchmark::State& state) {
  run_ringing_bar(state, "{model: constant_sound_speed, sound_speed: 0.5}", "solver: {tolerance: 1.0e-3}\n");
}
BENCHMARK(BM_RingingBarRigid)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RingingBarGas)->Arg(100)->Arg(300)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RingingBarHooke)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RingingBarHookeVisited)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

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
