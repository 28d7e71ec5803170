#include "rigidity/solvers/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rigidity {

SampleSchedule::SampleSchedule(const Scene& scene) : t_end_(scene.t_end) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  for (const ProbeDecl& probe : scene.outputs.probes) {
    Stream s;
    s.every = probe.every;
    s.count = static_cast<long>(std::floor(t_end_ / probe.every * (1.0 + 4.0 * kEps))) + 1;
    probes_.push_back(std::move(s));
  }
  for (const SnapshotDecl& snapshot : scene.outputs.snapshots) {
    Stream s;
    s.times = snapshot.times;
    std::stable_sort(s.times.begin(), s.times.end());
    s.count = static_cast<long>(s.times.size());
    snapshots_.push_back(std::move(s));
  }
  find_next();
}

double SampleSchedule::time_of(const Stream& s) const {
  if (s.taken >= s.count) return kNever;
  if (s.every == 0.0) return s.times[static_cast<std::size_t>(s.taken)];
  return std::min(static_cast<double>(s.taken) * s.every, t_end_);
}

void SampleSchedule::find_next() {
  // Outputs are few: a scan finds the earliest, the first in scene order at a tie, probes
  // before snapshots.
  next_ = SampleTime{kNever, SampleTime::Kind::probe, -1};
  for (std::size_t i = 0; i < probes_.size(); ++i)
    if (const double t = time_of(probes_[i]); t < next_.t) next_ = {t, SampleTime::Kind::probe, static_cast<int>(i)};
  for (std::size_t i = 0; i < snapshots_.size(); ++i)
    if (const double t = time_of(snapshots_[i]); t < next_.t)
      next_ = {t, SampleTime::Kind::snapshot, static_cast<int>(i)};
}

SampleTime SampleSchedule::pop() {
  const SampleTime taken = next_;
  auto& streams = taken.kind == SampleTime::Kind::probe ? probes_ : snapshots_;
  ++streams[static_cast<std::size_t>(taken.index)].taken;
  find_next();
  return taken;
}

int probe_body(const Scene& scene, const ProbeDecl& probe) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (scene.bodies[b].name == probe.body) return static_cast<int>(b);
  // The loader checks every probe's body: a scene built in code that names none is a bug.
  throw std::logic_error("probe '" + probe.name + "' samples body '" + probe.body + "', which the scene does not have");
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
