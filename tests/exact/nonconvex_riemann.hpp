#pragma once
/// The exact Riemann problem of one material whose genuine nonlinearity changes sign any finite
/// number of times: waves made of fans and shocks in sequence (composite waves), selected by Liu's
/// entropy condition. An independent reference for the tests: written from docs/physics.md's
/// conservation laws and a law given as p(s) and dp/ds; it shares no code with solvers/ or
/// materials/, nor with exact/riemann.hpp (the convex reference it is checked against).
///
/// The system, per unit label X, with v = tanh φ, γ = cosh φ, w = e + p (docs/physics.md):
///
///   labels    τ = s/γ          flux −v
///   momentum  M = w s γ v      flux p
///
/// from W(s) = ρ00 − ∫_1^s p dσ (rest energy included), e = W/s, c_s² = −s p'(s)/w, and the
/// Riemann invariants J± = φ ± Ψ(s), Ψ(s) = ∫_s^1 c_s(σ)/σ dσ. The C− wave (family −1) runs into
/// the left state, the C+ wave (family +1) into the right one; the state a wave runs into is its
/// outer state, the one it leaves behind its star state. Lagrangian characteristic speeds
/// dX/dt = ±c_s/(s γ (1 ± v c_s)); μ below is their magnitude.
///
/// Pieces of a wave of family f:
///   - a fan carries the other family's invariant, J+ = φ + Ψ across a C− wave, J− = φ − Ψ across
///     a C+ wave, so that φ = φ_a + f (Ψ(s) − Ψ(s_a)) along it (its integral curve);
///   - a shock between states a and b satisfies the label and momentum jump conditions,
///     m [τ] = −[v] and m [M] = [p]; m eliminated, H(φ_b) = [v][M] + [p][τ] = 0 is the Hugoniot
///     locus through a, taken on the branch tangent to the integral curve at a.
///
/// Liu's entropy condition and how the wave is built. From its outer state to its star state the
/// pieces of a wave run ever slower (μ never increases inward: the wave spreads or keeps its
/// shape). A shock from a (outer side) to b (star side) is admissible by Liu's condition when no
/// state u between them on the Hugoniot locus through a gives a faster chord, μ(a, b) ≥ μ(a, u),
/// which for this reflection-symmetric system is Liu's σ(u−, u+) ≤ σ(u−, u) with the left state as
/// base for the C− family and its mirror image for the C+ family. For a Newtonian p-system μ²(a, u)
/// is the chord slope of −p between the two stretches and the construction below is the convex
/// (or concave) hull of −p(s) over the wave's range, traversed from the outer state (Wendroff's).
/// Here the jump conditions are those of labels and momentum only: the energy a shock removes is
/// dissipated, so they are not invariant under boosts, and the Hugoniot locus through a state
/// depends on its rapidity as well as its stretch (nonconvex_riemann_test.cpp measures this). The
/// speeds along the wave are then not chord slopes of one function of s, and the hull is built
/// as Liu builds his wave curves, as a gift-wrapping march from the outer state:
///
///   at a state a (the outer state, or the end of the last piece), the fastest chord from a over
///   the rest of the range, max_u μ(a, u) along the Hugoniot locus through a, is compared with
///   μ(a) itself. Faster: a shock from a to the state where it is attained (the farthest, if
///   several), which by Liu's condition is admissible, and which, if that state is inside the
///   range, is sonic there (μ is stationary along a Hugoniot locus exactly where the shock speed
///   equals the characteristic speed of the far state: Lax's lemma). Not faster: a fan from a
///   along the integral curve, up to the first state t where the fastest chord from t catches up
///   with μ(t); there a shock leaves the fan at the fan's own characteristic speed (a shock
///   attached at a sonic point) to the state where that chord is attained. Repeat to the star.
///
/// Each piece is Liu-admissible by construction, each attachment sonic; what the construction
/// does not impose (the pieces' speeds never increasing inward, Liu's condition written from the
/// star state's Hugoniot locus, the jump conditions) the tests check. The fastest chord is found
/// on kChordSamples stretches (uniform in ln s), then refined: so a feature of the law narrower
/// than a fraction ~1/kChordSamples of a wave's range in ln s can be missed.
///
/// The star state: one stretch s* (one material on both sides) where the rapidities behind the two
/// waves agree, φ*_L(s*) = φ*_R(s*), the first increasing and the second decreasing with s*.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace rigidity::exact::nonconvex {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Stretches at which the fastest chord from a state is sampled before it is refined.
inline constexpr int kChordSamples = 48;
/// Stretches at which a fan is sampled for the first sonic point before it is refined.
inline constexpr int kFanSamples = 48;
/// Most pieces one wave may have (each inflection of the law adds at most two).
inline constexpr int kMaxPieces = 64;
/// Width in ln s of one panel of the Gauss–Legendre quadratures (W and Ψ).
inline constexpr double kPanel = 1.0 / 32.0;

/// A root of f between lo and hi, where f changes sign (or vanishes): the Illinois variant of
/// regula falsi with a bisection every fourth step, to adjacent numbers (4 ulp). NaN if the
/// signs do not bracket.
template <class F>
double find_root(const F& f, double lo, double hi) {
  double f_lo = f(lo), f_hi = f(hi);
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  if (!((f_lo < 0.0) != (f_hi < 0.0))) return kNaN;
  int side = 0;
  for (int i = 0; i < 600; ++i) {
    const double width = std::abs(hi - lo);
    if (width <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo), std::abs(hi))) break;
    double x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (i % 4 == 3 || !(x > std::min(lo, hi) && x < std::max(lo, hi))) x = lo + (hi - lo) / 2;
    if (!(x > std::min(lo, hi) && x < std::max(lo, hi))) break;  // adjacent numbers
    const double f_x = f(x);
    if (f_x == 0.0) return x;
    if ((f_x < 0.0) == (f_lo < 0.0)) {
      lo = x;
      f_lo = f_x;
      if (side < 0) f_hi /= 2;
      side = -1;
    } else {
      hi = x;
      f_hi = f_x;
      if (side > 0) f_lo /= 2;
      side = +1;
    }
  }
  return lo + (hi - lo) / 2;
}

/// ∫_a^b f by composite 8-point Gauss–Legendre, panels no wider than kPanel.
template <class F>
double integrate(const F& f, double a, double b) {
  static constexpr std::array<double, 4> node = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                                 0.9602898564975363};
  static constexpr std::array<double, 4> weight = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                                   0.1012285362903763};
  if (a == b) return 0.0;
  const int panels = std::max(1, static_cast<int>(std::ceil(std::abs(b - a) / kPanel)));
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int k = 0; k < panels; ++k) {
    const double mid = a + (k + 0.5) * h;
    for (std::size_t i = 0; i < node.size(); ++i)
      sum += weight[i] * (f(mid - 0.5 * h * node[i]) + f(mid + 0.5 * h * node[i]));
  }
  return 0.5 * h * sum;
}

/// A material given by its pressure law: p(s) (compression positive), dp/ds (< 0: hyperbolic),
/// ρ00, and the stretches it is admissible between; W(s) in closed form if known, else
/// W = ρ00 − ∫_1^s p dσ by quadrature.
class Law {
 public:
  using Function = std::function<double(double)>;

  Law(Function p, Function dp_ds, double rho00, double s_min, double s_max, Function W = {})
      : p_(std::move(p)), dp_(std::move(dp_ds)), w_(std::move(W)), rho_(rho00), s_min_(s_min), s_max_(s_max) {}

  [[nodiscard]] double rest_density() const { return rho_; }
  [[nodiscard]] double min_stretch() const { return s_min_; }
  [[nodiscard]] double max_stretch() const { return s_max_; }
  [[nodiscard]] double pressure(double s) const { return p_(s); }
  [[nodiscard]] double pressure_slope(double s) const { return dp_(s); }
  /// W(s) = e s, rest energy included.
  [[nodiscard]] double strain_energy(double s) const {
    if (w_) return w_(s);
    // −∫_1^s p dσ = −∫_0^{ln s} p(e^u) e^u du
    return rho_ - integrate([&](double u) { return p_(std::exp(u)) * std::exp(u); }, 0.0, std::log(s));
  }
  [[nodiscard]] double energy_density(double s) const { return strain_energy(s) / s; }
  [[nodiscard]] double enthalpy(double s) const { return energy_density(s) + pressure(s); }
  /// c_s² = s W''/(e + p), W'' = −dp/ds
  [[nodiscard]] double sound_speed(double s) const { return std::sqrt(-s * pressure_slope(s) / enthalpy(s)); }
  /// Ψ(a) − Ψ(b) = ∫_a^b c_s(σ)/σ dσ
  [[nodiscard]] double psi_between(double a, double b) const {
    return integrate([&](double u) { return sound_speed(std::exp(u)); }, std::log(a), std::log(b));
  }
  [[nodiscard]] double psi(double s) const { return psi_between(s, 1.0); }

 private:
  Function p_, dp_, w_;
  double rho_, s_min_, s_max_;
};

/// A uniform state: rapidity φ and stretch s.
struct State {
  double rapidity = 0.0;
  double stretch = 1.0;
};

inline double velocity(const State& u) { return std::tanh(u.rapidity); }
inline double label_density(const State& u) { return u.stretch / std::cosh(u.rapidity); }
inline double momentum_density(const Law& law, const State& u) {
  return law.enthalpy(u.stretch) * u.stretch * std::sinh(u.rapidity);
}
/// dX/dt of the characteristic of family ±1: ± c_s/(s γ (1 ± v c_s)).
inline double characteristic_speed(const Law& law, const State& u, int family) {
  const double c = law.sound_speed(u.stretch), f = family;
  return f * c / (u.stretch * (std::cosh(u.rapidity) + f * c * std::sinh(u.rapidity)));
}
/// dX/dt of a shock between a and b from the label jump condition, m = −[v]/[τ].
inline double shock_speed(const State& a, const State& b) {
  return -(velocity(b) - velocity(a)) / (label_density(b) - label_density(a));
}

/// The state of stretch s on the Hugoniot locus of family ±1 through `base`: the rapidity that
/// solves H = [v][M] + [p][τ] = 0 on the side of base.rapidity where the integral curve through
/// base lies (Δφ = f ΔΨ; Ψ falls as s grows). H < 0 at Δφ = 0 ([p] and [s] of opposite signs) and
/// > 0 far out (where [v] and [M] share the sign of Δφ).
inline State hugoniot_state(const Law& law, const State& base, double s, int family) {
  if (s == base.stretch) return base;
  const double dp = law.pressure(s) - law.pressure(base.stretch), w = law.enthalpy(s);
  const double v0 = velocity(base), tau0 = label_density(base), m0 = momentum_density(law, base);
  const double direction = (family < 0 ? -1.0 : 1.0) * (s < base.stretch ? 1.0 : -1.0);
  const auto h = [&](double d) {
    const double phi = base.rapidity + direction * d;
    return (std::tanh(phi) - v0) * (w * s * std::sinh(phi) - m0) + dp * (s / std::cosh(phi) - tau0);
  };
  double hi = 2.0 * law.sound_speed(base.stretch) * std::abs(std::log(s / base.stretch)) + 1e-300;
  for (int i = 0; i < 2000 && !(h(hi) > 0.0); ++i) hi *= 2.0;
  return State{base.rapidity + direction * find_root(h, 0.0, hi), s};
}

/// The state of stretch s on the fan (integral curve) of family ±1 through `from`.
inline State fan_state(const Law& law, const State& from, double s, int family) {
  return State{from.rapidity + (family < 0 ? -1.0 : 1.0) * law.psi_between(s, from.stretch), s};
}

/// The fastest chord from a state over a range of stretches: its excess over the state's own
/// characteristic speed, μ(a, u) − μ(a), and the state u on the Hugoniot locus through a.
struct Chord {
  double excess = kNaN;
  State state;
  bool at_end = false;  ///< u is the range's far end
};

/// max_u μ(a, u) over the stretches from a (excluded) to s_end (included), sampled at kChordSamples
/// stretches, refined by golden section, and polished where it is interior by Lax's lemma (μ(a, ·)
/// stationary where it equals μ(u)). Near a, μ(a, u) → μ(a): if the nearest sample is the fastest
/// and slower than μ(a), a fan may start at a and no refinement is made.
inline Chord fastest_chord(const Law& law, const State& a, int family, double s_end) {
  const double t0 = std::log(a.stretch), t1 = std::log(s_end);
  const double mu_a = std::abs(characteristic_speed(law, a, family));
  const auto state_at = [&](double t) { return hugoniot_state(law, a, t == t1 ? s_end : std::exp(t), family); };
  const auto excess_at = [&](double t) { return std::abs(shock_speed(a, state_at(t))) - mu_a; };
  const auto t_of = [&](int k) { return k == kChordSamples ? t1 : t0 + (t1 - t0) * k / kChordSamples; };
  int best = 1;
  double best_excess = -std::numeric_limits<double>::infinity();
  std::array<double, kChordSamples + 1> sample{};
  for (int k = 1; k <= kChordSamples; ++k) {
    sample[static_cast<std::size_t>(k)] = excess_at(t_of(k));
    if (sample[static_cast<std::size_t>(k)] >= best_excess) {
      best = k;
      best_excess = sample[static_cast<std::size_t>(k)];
    }
  }
  if (best == 1 && best_excess < 0.0) return Chord{best_excess, state_at(t_of(1)), kChordSamples == 1};
  // Golden section on the samples either side of the best one.
  double lo = t_of(best - 1), hi = t_of(std::min(best + 1, kChordSamples));
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double f1 = excess_at(x1), f2 = excess_at(x2);
  while (std::abs(hi - lo) > 1e-10 * std::max(1e-300, std::abs(t1 - t0))) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = excess_at(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = excess_at(x1);
    }
  }
  double t_best = f1 > f2 ? x1 : x2, f_best = std::max(f1, f2);
  if (best >= kChordSamples - 1 && sample[kChordSamples] >= f_best)
    return Chord{sample[kChordSamples], state_at(t1), true};
  // Interior: polish where the shock speed equals the far state's characteristic speed.
  const auto sonic = [&](double t) {
    const State u = state_at(t);
    return std::abs(shock_speed(a, u)) - std::abs(characteristic_speed(law, u, family));
  };
  const double span = 1e-6 * std::abs(t1 - t0);
  const double lo_polish = t_best - span, hi_polish = t_best + span;
  const bool inside = (t1 > t0) ? (lo_polish > t0 && hi_polish < t1) : (lo_polish < t0 && hi_polish > t1);
  if (inside && (sonic(lo_polish) < 0.0) != (sonic(hi_polish) < 0.0)) {
    t_best = find_root(sonic, lo_polish, hi_polish);
    f_best = excess_at(t_best);
  }
  return Chord{f_best, state_at(t_best), false};
}

enum class PieceKind { fan, shock };

/// One piece of a wave: from its outer-side state to its star-side state.
struct Piece {
  PieceKind kind = PieceKind::fan;
  State from, to;
};

/// A wave of family ±1 centred at the origin of (X, t): its pieces from the outer state inward.
struct Wave {
  const Law* law = nullptr;
  int family = -1;
  State outer, star;
  std::vector<Piece> pieces;
  bool solved = true;  ///< false if the construction did not reach the star (kMaxPieces)

  /// The pieces from the outer state inward, 'S' a shock and 'R' a fan: "SR" is a shock with a
  /// fan attached behind it, "" no wave.
  [[nodiscard]] std::string pattern() const {
    std::string out;
    for (const Piece& p : pieces) out += p.kind == PieceKind::shock ? 'S' : 'R';
    return out;
  }
  /// dX/dt of a piece's outer-side and star-side edges (equal for a shock).
  [[nodiscard]] double outer_edge_speed(const Piece& p) const {
    return p.kind == PieceKind::shock ? shock_speed(p.from, p.to) : characteristic_speed(*law, p.from, family);
  }
  [[nodiscard]] double star_edge_speed(const Piece& p) const {
    return p.kind == PieceKind::shock ? shock_speed(p.from, p.to) : characteristic_speed(*law, p.to, family);
  }

  /// The state at ξ = X/t. Outer edges come first from the outer side: for a C− wave the pieces
  /// run left to right, for a C+ wave right to left.
  [[nodiscard]] State at(double xi) const {
    const double f = family < 0 ? 1.0 : -1.0;  // ξ measured inward from the outer side
    for (const Piece& p : pieces) {
      if (f * xi < f * outer_edge_speed(p)) return p.from;
      if (p.kind == PieceKind::fan && f * xi < f * star_edge_speed(p)) {
        // The fan's own edge stretches at the ends of the bracket; ξ within round-off of an
        // edge, outside it, gets that edge's state.
        const double t_from = std::log(p.from.stretch), t_to = std::log(p.to.stretch);
        const auto stretch_at = [&](double t) {
          return t == t_from ? p.from.stretch : t == t_to ? p.to.stretch : std::exp(t);
        };
        const double t = find_root(
            [&](double u) {
              return characteristic_speed(*law, fan_state(*law, p.from, stretch_at(u), family), family) - xi;
            },
            t_from, t_to);
        if (std::isnan(t)) return p.to;
        return fan_state(*law, p.from, stretch_at(t), family);
      }
    }
    return star;
  }
};

/// The wave of family ±1 from `outer` to the star stretch s_star, built as the header says.
inline Wave build_wave(const Law& law, const State& outer, int family, double s_star) {
  Wave out{&law, family, outer, outer, {}, true};
  State a = outer;
  while (a.stretch != s_star) {
    if (static_cast<int>(out.pieces.size()) >= kMaxPieces) {
      out.solved = false;
      break;
    }
    const Chord first = fastest_chord(law, a, family, s_star);
    if (first.excess > 0.0) {
      out.pieces.push_back(Piece{PieceKind::shock, a, first.state});
      a = first.state;
      continue;
    }
    // A fan from a, up to the first sonic point t where the fastest chord catches up with μ(t).
    const double t0 = std::log(a.stretch), t1 = std::log(s_star);
    const auto excess_on_fan = [&](double t) {
      return fastest_chord(law, fan_state(law, a, std::exp(t), family), family, s_star).excess;
    };
    double previous = t0, sonic = kNaN;
    for (int k = 1; k < kFanSamples; ++k) {
      const double t = t0 + (t1 - t0) * k / kFanSamples;
      if (excess_on_fan(t) >= 0.0) {
        sonic = find_root(excess_on_fan, previous, t);
        break;
      }
      previous = t;
    }
    if (std::isnan(sonic)) {
      out.pieces.push_back(Piece{PieceKind::fan, a, fan_state(law, a, s_star, family)});
      a = out.pieces.back().to;
      break;
    }
    const State t_state = fan_state(law, a, std::exp(sonic), family);
    const Chord chord = fastest_chord(law, t_state, family, s_star);
    out.pieces.push_back(Piece{PieceKind::fan, a, t_state});
    out.pieces.push_back(Piece{PieceKind::shock, t_state, chord.state});
    a = chord.state;
  }
  out.star = a;
  return out;
}

/// Two states of one material meeting at the origin (bonded: tension is transmitted).
struct Solution {
  bool solved = false;  ///< false: no star stretch in the law's range, or a wave not built
  double pressure = kNaN;
  Wave left, right;  ///< the C− wave into the left state, the C+ wave into the right one

  /// The state at ξ = X/t.
  [[nodiscard]] State at(double xi) const { return xi < 0.0 ? left.at(xi) : right.at(xi); }
};

inline Solution riemann_problem(const Law& law, const State& left, const State& right) {
  const auto mismatch = [&](double t) {
    const double s = std::exp(t);
    return build_wave(law, left, -1, s).star.rapidity - build_wave(law, right, +1, s).star.rapidity;
  };
  // Increasing in ln s*: bracket it from the two states outward, within the law's range.
  const double t_min = std::log(law.min_stretch()), t_max = std::log(law.max_stretch());
  double lo = std::min(std::log(left.stretch), std::log(right.stretch));
  double hi = std::max(std::log(left.stretch), std::log(right.stretch));
  Solution out;
  double step = 0.05;
  while (mismatch(lo) > 0.0) {
    if (lo == t_min) return out;
    lo = std::max(t_min, lo - step);
    step *= 2.0;
  }
  step = 0.05;
  while (mismatch(hi) < 0.0) {
    if (hi == t_max) return out;
    hi = std::min(t_max, hi + step);
    step *= 2.0;
  }
  const double s = std::exp(find_root(mismatch, lo, hi));
  out.left = build_wave(law, left, -1, s);
  out.right = build_wave(law, right, +1, s);
  out.pressure = law.pressure(s);
  out.solved = out.left.solved && out.right.solved;
  return out;
}

}  // namespace rigidity::exact::nonconvex
