#pragma once
/// What both solvers share to fill a scene's outputs: when to sample, and the value of
/// an output quantity in a uniform state.

#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/quantity.hpp"
#include "rigidity/scene.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace rigidity {

/// A time at which an output wants the solution.
struct SampleTime {
  double t;
  int kind;   ///< 0 probe, 1 snapshot
  int index;  ///< into scene.outputs.probes or .snapshots
};

/// Every probe sample (0, every, 2 every, ... ≤ t_end) and snapshot time, in time order
/// (probes before snapshots at equal times, each in scene order).
[[nodiscard]] std::vector<SampleTime> sample_times(const Scene& scene);

/// Index of the body a probe samples (the loader has checked that it exists).
[[nodiscard]] int probe_body(const Scene& scene, const ProbeDecl& probe);

/// True if a snapshot samples this body (an empty `bodies` list means every body).
[[nodiscard]] bool snapshot_includes(const SnapshotDecl& snapshot, const BodyDecl& body);

/// The value of quantity q in a uniform state at label X and lab position x (natural units).
[[nodiscard]] double quantity_value(Quantity q, const Material& material, const State& state, double X, double x);

}  // namespace rigidity
