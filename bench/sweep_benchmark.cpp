// Sweeps of the paper's wall impact run in-process: cases per second for a whole
// sweep (threads as the argument), and the parts of one case's cost, loading the
// scene with its overrides and solving it, to show the per-case overhead.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rigidity/run_recorder.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"
#include "rigidity/sweep.hpp"

namespace {

namespace fs = std::filesystem;

rigidity::Sweep paper_sweep(std::size_t cases) {
  const fs::path file = fs::temp_directory_path() / "rigidity_sweep_benchmark.yaml";
  std::ofstream(file) << "parameters:\n  bodies.0.velocity: {linspace: [0.01, 0.99, " << cases
                      << "]}\ncollect:\n  p_max: probe.wall.p.max\n  rebound: body.bar.velocity_mean\n";
  return rigidity::load_sweep_file(file.string());
}

/// A whole sweep of 1000 cases (table written), on state.range(0) threads.
void BM_SweepPaperScene(benchmark::State& state) {
  const rigidity::Sweep sweep = paper_sweep(1000);
  const fs::path dir = fs::temp_directory_path() / "rigidity_sweep_benchmark";
  rigidity::SweepOptions options;
  options.out_dir = dir.string();
  options.jobs = static_cast<unsigned>(state.range(0));
  for (auto _ : state) {
    fs::remove_all(dir);
    benchmark::DoNotOptimize(rigidity::run_sweep(sweep, options));
  }
  fs::remove_all(dir);
  state.SetItemsProcessed(state.iterations() * 1000);
  state.SetLabel("items/s = cases per second");
}
BENCHMARK(BM_SweepPaperScene)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// One case as the sweep runs it: load with the override, solve, collect.
void BM_SweepOneCase(benchmark::State& state) {
  const rigidity::Sweep sweep = paper_sweep(1000);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(rigidity::run_sweep_case(sweep, i++ % 1000));
}
BENCHMARK(BM_SweepOneCase)->Unit(benchmark::kMicrosecond);

/// Its parts: reading and validating the scene with the override ...
void BM_SweepLoadScene(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(
        rigidity::load_scene_string(rigidity::default_scene_text(), "<default>", {"bodies.0.velocity=0.6"}));
}
BENCHMARK(BM_SweepLoadScene)->Unit(benchmark::kMicrosecond);

/// ... and solving it with every output kept in memory.
void BM_SweepSolveOnly(benchmark::State& state) {
  const rigidity::Scene scene = rigidity::load_scene_string(rigidity::default_scene_text(), "<default>");
  for (auto _ : state) {
    rigidity::MemoryRecorder recorder;
    benchmark::DoNotOptimize(rigidity::solve(scene, recorder));
  }
}
BENCHMARK(BM_SweepSolveOnly)->Unit(benchmark::kMicrosecond);

}  // namespace
