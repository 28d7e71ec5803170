#pragma once
/// What both solvers share to fill a scene's outputs: when to sample, and the value of
/// an output quantity in a uniform state.

#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/quantity.hpp"
#include "rigidity/scene.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace rigidity {

/// A time at which an output wants the solution.
struct SampleTime {
  enum class Kind { probe, snapshot };
  double t;
  Kind kind;
  int index;  ///< into scene.outputs.probes or .snapshots
};

/// Every probe sample (0, every, 2 every, ... ≤ t_end) and snapshot time, in time order
/// (probes before snapshots at equal times, each in scene order), made one at a time:
/// a run of 10⁹ probe samples costs no memory and no set-up.
class SampleSchedule {
 public:
  explicit SampleSchedule(const Scene& scene);
  [[nodiscard]] bool done() const { return next_.t == kNever; }
  /// The next sample's time (+∞ when done).
  [[nodiscard]] double next_time() const { return next_.t; }
  /// The next sample, and advance past it. \pre !done()
  SampleTime pop();

 private:
  static constexpr double kNever = std::numeric_limits<double>::infinity();
  struct Stream {
    double every = 0.0;         ///< a probe's interval (0 for a snapshot)
    long count = 0;             ///< samples in all
    long taken = 0;             ///< samples already made
    std::vector<double> times;  ///< a snapshot's times, sorted
  };
  [[nodiscard]] double time_of(const Stream& s) const;
  void find_next();

  double t_end_;
  std::vector<Stream> probes_, snapshots_;
  SampleTime next_{kNever, SampleTime::Kind::probe, -1};
};

/// Adds the time its scope takes to `total` [s]: what filling the outputs costs, reported
/// apart from solving (RunStats::sampling_time_s).
class SamplingTimer {
 public:
  explicit SamplingTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~SamplingTimer() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  SamplingTimer(const SamplingTimer&) = delete;
  SamplingTimer& operator=(const SamplingTimer&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

/// The label X in [X_lo, X_hi] at lab position x, for a body whose lab position x_of(X) rises
/// with X there (bisection to round-off; the ends where x lies beyond them).
template <class XOf>
[[nodiscard]] double label_at_lab(double x, double X_lo, double X_hi, XOf&& x_of) {
  for (int i = 0; i < 200 && X_hi - X_lo > 4e-16 * (1.0 + std::abs(X_hi)); ++i) {
    const double mid = 0.5 * (X_lo + X_hi);
    (x_of(mid) < x ? X_lo : X_hi) = mid;
  }
  return 0.5 * (X_lo + X_hi);
}

/// Index of the body a probe samples (the loader has checked that it exists).
[[nodiscard]] int probe_body(const Scene& scene, const ProbeDecl& probe);

/// True if a snapshot samples this body (an empty `bodies` list means every body).
[[nodiscard]] bool snapshot_includes(const SnapshotDecl& snapshot, const BodyDecl& body);

/// The value of quantity q in a uniform state at label X and lab position x (natural units).
[[nodiscard]] double quantity_value(Quantity q, const Material& material, const State& state, double X, double x);

}  // namespace rigidity
