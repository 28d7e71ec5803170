// Composite waves of laws whose genuine nonlinearity changes sign (rigidity/solvers/riemann.hpp:
// composite_wave): Liu's construction as a march from the outer state.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include "outcome.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace rigidity {
namespace {

using solving::find_root;
using solving::numerical_failure;
using solving::Outcome;
using solving::succeeded;

/// Stretches at which the chords from a state are sampled before the fastest is refined.
constexpr int kChordSamples = 48;
/// Stretches at which a fan is sampled for the state its attached shock leaves from.
constexpr int kFanSamples = 16;
/// Most pieces a wave may have (each inflection adds at most two).
constexpr std::size_t kMaxPieces = 64;
/// A chord counts as faster than a characteristic only by more than this (relative): a chord
/// from a sonic point is equal to it up to the round-off of either.
constexpr double kSonicMargin = 1e-12;

constexpr std::string_view kComposite = "a composite wave could not be built";

/// The fastest chord from a state along its Hugoniot locus: its speed (magnitude) and where it ends.
struct Chord {
  double speed = -std::numeric_limits<double>::infinity();
  State end;
};

/// Liu's construction for one wave of family f of a material, from its outer state to ln s*.
class Construction {
 public:
  Construction(const Material& m, int family, double log_star) : m_(m), f_(family), log_star_(log_star) {}

  /// Speeds along the wave are magnitudes of Lagrangian speeds: positive, falling inwards.
  [[nodiscard]] double characteristic(const State& u) const { return f_ * characteristic_speed(m_, u, f_); }

  /// The state at ln s on the integral curve through b (the other family's invariant carried).
  [[nodiscard]] State fan_state(const State& b, double log_s) const {
    const Stretch s = Stretch::from_log(log_s);
    return State{b.rapidity + f_ * (m_.riemann_psi(s) - m_.riemann_psi(b.stretch)), s};
  }

  /// The state at ln s on the Hugoniot locus through b, and the chord's speed.
  [[nodiscard]] Outcome<Chord> chord(const State& b, double log_s) const {
    const Solved<double> rapidity = shock_rapidity(m_, b, Stretch::from_log(log_s), f_);
    if (!rapidity.ok()) return numerical_failure<Chord>(rapidity.status, kComposite, m_);
    const State u{rapidity.value, Stretch::from_log(log_s)};
    return succeeded(Chord{std::abs(label_jump(b, u).speed()), u});
  }

  /// The fastest chord from b to a state between it and the star (the farthest where several
  /// are as fast). Sampled, then, where it lies inside, refined as the sonic point there: the
  /// chord speed is stationary along the locus where it equals the far state's characteristic.
  [[nodiscard]] Outcome<Chord> fastest_chord(const State& b) const {
    const double from = b.stretch.log(), width = log_star_ - from;
    Chord best;
    int at = 0;
    std::vector<double> logs(kChordSamples + 1, from);
    for (int k = 1; k <= kChordSamples; ++k) {
      logs[k] = k == kChordSamples ? log_star_ : from + width * k / kChordSamples;
      const Outcome<Chord> c = chord(b, logs[k]);
      if (!c.ok()) return c;
      if (c.value.speed >= best.speed * (1.0 - 4.0 * std::numeric_limits<double>::epsilon())) {
        best = c.value;
        at = k;
      }
    }
    if (at == kChordSamples) return succeeded(best);
    const auto sonic = [&](double log_s) -> Outcome<double> {
      const Outcome<Chord> c = chord(b, log_s);
      if (!c.ok()) return c.as<double>();
      return succeeded(c.value.speed - characteristic(c.value.end));
    };
    for (const int side : {+1, -1}) {
      const int k = at + side;
      if (k < 1 || k > kChordSamples) continue;
      const Outcome<double> here = sonic(logs[at]), there = sonic(logs[k]);
      if (!here.ok() || !there.ok()) return here.ok() ? there.as<Chord>() : here.as<Chord>();
      if ((here.value < 0.0) == (there.value < 0.0)) continue;
      const Outcome<double> root = find_root(sonic, std::min(logs[at], logs[k]), std::max(logs[at], logs[k]), m_);
      if (!root.ok()) return root.as<Chord>();
      const Outcome<Chord> c = chord(b, root.value);
      if (!c.ok()) return c;
      if (c.value.speed >= best.speed) best = c.value;
    }
    return succeeded(best);
  }

  /// How much faster than b's characteristic the fastest chord from b is (negative: slower);
  /// minus infinity at the star, where no chord is left.
  [[nodiscard]] Outcome<double> excess(const State& b, Chord* chord_out = nullptr) const {
    if (b.stretch.log() == log_star_) return succeeded(-std::numeric_limits<double>::infinity());
    const Outcome<Chord> c = fastest_chord(b);
    if (!c.ok()) return c.as<double>();
    if (chord_out != nullptr) *chord_out = c.value;
    return succeeded(c.value.speed - characteristic(b));
  }

  /// Where a fan from b ends: at the star, or at the first state from which a chord catches up
  /// with the fan's characteristic (at the latest the first inflection on the way); with the
  /// shock attached there.
  struct FanEnd {
    double log_s = 0.0;
    bool shock_attached = false;
    Chord shock;
  };
  [[nodiscard]] Outcome<FanEnd> fan_end(const State& b) const {
    const double from = b.stretch.log();
    double limit = log_star_;
    for (const double inflection : m_.inflection_logs())
      if ((inflection - from) * (log_star_ - from) > 0.0 && std::abs(inflection - from) < std::abs(limit - from))
        limit = inflection;
    // The excess beyond the margin that makes a chord faster (at b itself it is not: b leads a fan).
    const auto catching_up = [&](double log_s) -> Outcome<double> {
      const State u = fan_state(b, log_s);
      const Outcome<double> e = excess(u);
      if (!e.ok()) return e;
      return succeeded(e.value - kSonicMargin * characteristic(u));
    };
    double previous = from;
    for (int k = 1; k <= kFanSamples; ++k) {
      const double log_s = k == kFanSamples ? limit : from + (limit - from) * k / kFanSamples;
      const Outcome<double> e = catching_up(log_s);
      if (!e.ok()) return e.as<FanEnd>();
      if (e.value > 0.0) {
        const Outcome<double> root = find_root(catching_up, std::min(previous, log_s), std::max(previous, log_s), m_);
        if (!root.ok()) return root.as<FanEnd>();
        FanEnd end{root.value, true, {}};
        const Outcome<Chord> shock = fastest_chord(fan_state(b, root.value));
        if (!shock.ok()) return shock.as<FanEnd>();
        end.shock = shock.value;
        return succeeded(end);
      }
      previous = log_s;
    }
    return succeeded(FanEnd{limit, false, {}});
  }

  [[nodiscard]] const Material& material() const { return m_; }
  [[nodiscard]] double log_star() const { return log_star_; }

 private:
  const Material& m_;
  int f_;
  double log_star_;
};

void add_piece(std::vector<WavePiece>& pieces, const State& from, bool shock, const State& end) {
  if (end.stretch.log() == from.stretch.log()) return;  // nothing between them
  pieces.push_back(WavePiece{shock, end});
}

}  // namespace

bool crosses_inflection(const Material& m, Stretch a, Stretch b) {
  const double lo = std::min(a.log(), b.log()), hi = std::max(a.log(), b.log());
  const std::vector<double>& inflections = m.inflection_logs();
  return std::any_of(inflections.begin(), inflections.end(), [&](double x) { return x > lo && x < hi; });
}

Solved<CompositeWave> composite_wave(const Material& m, const State& outer, Stretch star, int family) {
  CompositeWave wave;
  if (star.log() == outer.stretch.log()) return Solved<CompositeWave>{wave, Status::ok};
  if (!crosses_inflection(m, outer.stretch, star)) {
    const bool shock = wave_is_shock(m, outer, star, family);
    State end{0.0, star};
    if (shock) {
      const Solved<double> rapidity = shock_rapidity(m, outer, star, family);
      if (!rapidity.ok()) return Solved<CompositeWave>::failure(rapidity.status);
      end.rapidity = rapidity.value;
    } else {
      end.rapidity = outer.rapidity + family * (m.riemann_psi(star) - m.riemann_psi(outer.stretch));
    }
    wave.pieces.push_back(WavePiece{shock, end});
    return Solved<CompositeWave>{wave, Status::ok};
  }
  const Construction liu(m, family, star.log());
  State b = outer;
  while (b.stretch.log() != star.log()) {
    if (wave.pieces.size() >= kMaxPieces) return Solved<CompositeWave>::failure(Status::not_converged);
    Chord fastest;
    const Outcome<double> ahead = liu.excess(b, &fastest);
    if (!ahead.ok()) return Solved<CompositeWave>::failure(ahead.status);
    if (ahead.value > kSonicMargin * liu.characteristic(b)) {
      add_piece(wave.pieces, b, true, fastest.end);
      b = fastest.end;
      continue;
    }
    const Outcome<Construction::FanEnd> end = liu.fan_end(b);
    if (!end.ok()) return Solved<CompositeWave>::failure(end.status);
    const State fan_end = liu.fan_state(b, end.value.log_s);
    add_piece(wave.pieces, b, false, fan_end);
    b = fan_end;
    if (end.value.shock_attached) {
      add_piece(wave.pieces, b, true, end.value.shock.end);
      b = end.value.shock.end;
    }
  }
  // The star's stretch as asked, to the bit.
  if (!wave.pieces.empty()) wave.pieces.back().end.stretch = star;
  return Solved<CompositeWave>{wave, Status::ok};
}

}  // namespace rigidity
