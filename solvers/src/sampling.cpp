#include "rigidity/solvers/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rigidity {

std::vector<SampleTime> sample_times(const Scene& scene) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  std::vector<SampleTime> samples;
  const double t_end = scene.t_end;
  for (std::size_t i = 0; i < scene.outputs.probes.size(); ++i) {
    const double every = scene.outputs.probes[i].every;
    const long count = static_cast<long>(std::floor(t_end / every * (1.0 + 4.0 * kEps)));
    for (long k = 0; k <= count; ++k)
      samples.push_back(SampleTime{std::min(static_cast<double>(k) * every, t_end), 0, static_cast<int>(i)});
  }
  for (std::size_t i = 0; i < scene.outputs.snapshots.size(); ++i)
    for (double t : scene.outputs.snapshots[i].times) samples.push_back(SampleTime{t, 1, static_cast<int>(i)});
  std::stable_sort(samples.begin(), samples.end(), [](const SampleTime& a, const SampleTime& b) { return a.t < b.t; });
  return samples;
}

int probe_body(const Scene& scene, const ProbeDecl& probe) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (scene.bodies[b].name == probe.body) return static_cast<int>(b);
  return 0;
}

bool snapshot_includes(const SnapshotDecl& snapshot, const BodyDecl& body) {
  return snapshot.bodies.empty() ||
         std::find(snapshot.bodies.begin(), snapshot.bodies.end(), body.name) != snapshot.bodies.end();
}

double quantity_value(Quantity q, const Material& m, const State& st, double X, double x) {
  switch (q) {
    case Quantity::X: return X;
    case Quantity::x: return x;
    case Quantity::v: return std::tanh(st.rapidity);
    case Quantity::s: return st.stretch.value();
    case Quantity::p: return m.pressure(st.stretch);
    case Quantity::e:
    case Quantity::rho: return m.energy_density(st.stretch);
    case Quantity::gamma: return std::cosh(st.rapidity);
    case Quantity::cs: return m.sound_speed(st.stretch);
  }
  return 0.0;
}

}  // namespace rigidity
