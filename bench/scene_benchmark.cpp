// Loading scenes: reading, checking and building a Scene from YAML text, for a scene of many
// segments (validation is linear: time and memory per segment stay the same as it grows).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cstdio>
#include <string>

#include "rigidity/scene_loader.hpp"

namespace {

/// A hooke bar of `segments` segments, as a user's generator would write it.
std::string segmented_bar(int segments) {
  std::string yaml =
      "name: segmented\nmaterials: {steel: {model: hooke, rest_density: 1.0, wave_speed: 0.5}}\n"
      "bodies:\n  - name: bar\n    material: steel\n    position: 0\n    segments:\n";
  char line[128];
  for (int i = 0; i < segments; ++i) {
    std::snprintf(line, sizeof line, "      - {length: 0.00001, velocity: %.9f, stretch: 1.0}\n", 0.1 + 1e-7 * i);
    yaml += line;
  }
  return yaml + "boundaries: {left: {type: free}, right: {type: wall}}\ntime: {end: 0.1}\n";
}

/// Peak resident memory of the process so far, in MB (Linux reports kB).
double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

void BM_LoadSegmentedBar(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  const std::string text = segmented_bar(segments);
  for (auto _ : state) benchmark::DoNotOptimize(rigidity::load_scene_string(text, "<bench>"));
  state.SetItemsProcessed(state.iterations() * segments);  // segments per second
  state.counters["MB_text"] = static_cast<double>(text.size()) / 1e6;
  // The process's peak so far: the largest scene loaded (run it alone, with
  // --benchmark_filter, to read the peak of one size).
  state.counters["MB_peak_rss"] = peak_rss_mb();
}
BENCHMARK(BM_LoadSegmentedBar)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
