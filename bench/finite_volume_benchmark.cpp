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

}  // namespace
