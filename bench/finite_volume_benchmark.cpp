// The finite-volume baseline: throughput (cell updates per second) and accuracy side
// by side, on the paper's wall impact (rigid bar at v = 0.6 against a wall) whose
// exact solution at t = 0.25 is p = 0 for X < 0.5 and p = 1.5 beyond. The front
// tracker solves the same scene exactly; see characteristics_benchmark.cpp.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace {

std::string wall_impact(int cells, int order, const char* flux) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, R"(
name: fv_wall_impact
materials: {steel: {model: rigid}}
bodies: [{name: bar, material: steel, position: 0.0, length: 1.0, velocity: 0.6}]
boundaries: {left: {type: free}, right: {type: wall}}
solver: {method: finite_volume, cells: %d, order: %d, flux: %s}
time: {end: 0.25}
outputs:
  snapshots: [{times: [0.25], quantities: [p], samples: 1001}]
)",
                cells, order, flux);
  return buf;
}

/// Mean |p − p_exact| over the snapshot.
double pressure_l1_error(const rigidity::RunResult& r) {
  double error = 0.0;
  int n = 0;
  for (const rigidity::SnapshotSample& s : r.snapshots) {
    if (std::abs(s.X - 0.5) < 1e-12) continue;
    error += std::abs(s.value - (s.X < 0.5 ? 0.0 : 1.5));
    ++n;
  }
  return n > 0 ? error / n : 0.0;
}

void run_wall_impact(benchmark::State& state, const char* flux) {
  const int cells = static_cast<int>(state.range(0));
  const int order = static_cast<int>(state.range(1));
  const rigidity::Scene scene = rigidity::load_scene_string(wall_impact(cells, order, flux), "<bench>");
  long updates = 0;
  double error = 0.0;
  for (auto _ : state) {
    const rigidity::RunResult r = rigidity::solve(scene);
    for (const auto& [name, value] : r.solver_numbers)
      if (name == "steps") updates += static_cast<long>(value) * cells;
    error = pressure_l1_error(r);
    benchmark::DoNotOptimize(error);
  }
  state.SetItemsProcessed(updates);  // cell updates
  state.counters["L1_p"] = error;
}

void BM_FiniteVolumeWallImpactHll(benchmark::State& state) { run_wall_impact(state, "hll"); }
void BM_FiniteVolumeWallImpactExact(benchmark::State& state) { run_wall_impact(state, "exact"); }
BENCHMARK(BM_FiniteVolumeWallImpactHll)
    ->ArgsProduct({{100, 200, 400, 800, 1600}, {1, 2}})
    ->ArgNames({"cells", "order"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FiniteVolumeWallImpactExact)
    ->ArgsProduct({{100, 400, 1600}, {1, 2}})
    ->ArgNames({"cells", "order"})
    ->Unit(benchmark::kMillisecond);

/// Cell updates per second of one scene at `cells` per body (Google Benchmark's items).
void run_scene(benchmark::State& state, const std::string& yaml) {
  const rigidity::Scene scene = rigidity::load_scene_string(yaml, "<bench>");
  long updates = 0;
  for (auto _ : state) {
    const rigidity::RunResult r = rigidity::solve(scene);
    updates += static_cast<long>(r.stats.interactions);  // one per face per step: about one per cell
    benchmark::DoNotOptimize(r.conservation.energy_final);
  }
  state.SetItemsProcessed(updates);
}

/// Two rigid_fluid bars meeting at ±0.6c (the plateau of docs/limits.md, "The
/// finite-volume plateau"): most cells sit in uniform states ahead of the two shocks, and a cell whose
/// U a step leaves unchanged keeps its state without a recovery.
void BM_FiniteVolumeCollision(benchmark::State& state) {
  run_scene(state, R"(
name: rigid_fluid_collision
materials: {fluid: {model: rigid_fluid}}
bodies:
  - {name: a, material: fluid, position: -1.0, length: 1.0, velocity: 0.6}
  - {name: b, material: fluid, position: 0.0, length: 1.0, velocity: -0.6}
time: {end: 0.3}
solver: {method: finite_volume, cells: )" +
                       std::to_string(state.range(0)) + ", order: 2, flux: hll}\n");
}

/// Every cell busy: a bar of 50 segments at alternating velocities ±0.3 between bonded
/// walls rings until t = 0.25 (each cell's recovery and both HLL face states every step).
void BM_FiniteVolumeRingingBar(benchmark::State& state, const char* law) {
  std::string segments;
  for (int k = 0; k < 50; ++k)
    segments += std::string(k ? ", " : "") + "{length: 0.02, velocity: " + (k % 2 ? "-0.3}" : "0.3}");
  run_scene(state, std::string("name: ringing\nmaterials: {m: ") + law +
                       "}\nbodies: [{name: bar, material: m, position: 0.0, segments: [" + segments +
                       "]}]\nboundaries: {left: {type: wall, bonded: true}, right: {type: wall, bonded: true}}\n"
                       "time: {end: 0.25}\nsolver: {method: finite_volume, cells: " +
                       std::to_string(state.range(0)) + ", order: 2, flux: hll}\n");
}
BENCHMARK(BM_FiniteVolumeCollision)->Arg(400)->Arg(3200)->ArgName("cells")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FiniteVolumeRingingBar, rigid, "{model: rigid}")
    ->Arg(400)
    ->Arg(3200)
    ->ArgName("cells")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FiniteVolumeRingingBar, constant_sound_speed, "{model: constant_sound_speed, sound_speed: 0.5}")
    ->Arg(400)
    ->ArgName("cells")
    ->Unit(benchmark::kMillisecond);

}  // namespace
