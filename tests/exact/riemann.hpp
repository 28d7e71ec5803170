#pragma once
/// Independent exact solutions of relativistic elasticity in Lagrangian form (docs/physics.md),
/// for tests and the work-precision driver: Riemann problems of one or two materials, a
/// state against a wall or piston, a free end, the exact rarefaction fan, shock speeds and
/// the energy a shock dissipates. Written from the conservation laws alone, with plain
/// bisection; nothing here calls rigidity's Riemann solver or its solvers.
///
/// Per unit label X, with v = tanh φ, γ = cosh φ and w = e + p:
///
///   labels    τ = s/γ                  flux −v
///   momentum  M = w s γ v              flux p
///   energy    E = (w γ² − p) s/γ       flux p v     (not conserved across a shock)
///
/// A front moving at dX/dt = m between a left state a and a right state b satisfies
/// m (U_b − U_a) = F_b − F_a for the labels and momentum; across a shock the energy removed
/// per unit time is D = m [E] − [p v] (docs/physics.md), [q] = q_b − q_a.
///
/// Waves: the C− wave (family −1) runs into the left state, the C+ wave (family +1) into
/// the right state. Along a rarefaction (and every wave of a linearly degenerate material)
/// the invariant of the other family is carried: J+ = φ + Ψ across a C− wave, J− = φ − Ψ
/// across a C+ wave. Which it is (fan or shock) is Lax's condition: a fan spreads, its
/// characteristic speed growing from its left edge to its right.

#include <cmath>
#include <limits>

#include "exact/bisection.hpp"
#include "exact/law.hpp"

namespace rigidity::exact {

/// A uniform state: rapidity φ and stretch s.
template <class Real>
struct State {
  Real rapidity = 0;
  Real stretch = 1;
};

// ---- conserved densities and fluxes per unit label (docs/physics.md) --------------------------------

template <class Real>
Real velocity(const State<Real>& u) {
  return std::tanh(u.rapidity);
}
template <class Real>
Real label_density(const State<Real>& u) {
  return u.stretch / std::cosh(u.rapidity);
}
template <class Real>
Real momentum_density(const Law<Real>& law, const State<Real>& u) {
  return law.enthalpy(u.stretch) * u.stretch * std::sinh(u.rapidity);
}
template <class Real>
Real energy_density(const Law<Real>& law, const State<Real>& u) {
  const Real g = std::cosh(u.rapidity);
  return (law.enthalpy(u.stretch) * g * g - law.pressure(u.stretch)) * u.stretch / g;
}
template <class Real>
Real energy_flux(const Law<Real>& law, const State<Real>& u) {
  return law.pressure(u.stretch) * velocity(u);
}

/// Lagrangian speed dX/dt of the characteristic of family ±1: ± c_s / (s γ (1 ± v c_s)) (docs/physics.md).
template <class Real>
Real characteristic_speed(const Law<Real>& law, const State<Real>& u, int family) {
  const Real c = law.sound_speed(u.stretch), f = Real(family);
  return f * c / (u.stretch * std::cosh(u.rapidity) * (1 + f * velocity(u) * c));
}
/// Lab speed dx/dt of that characteristic: (v ± c_s)/(1 ± v c_s).
template <class Real>
Real characteristic_lab_speed(const Law<Real>& law, const State<Real>& u, int family) {
  const Real c = law.sound_speed(u.stretch), v = velocity(u), f = Real(family);
  return (v + f * c) / (1 + f * v * c);
}

// ---- one wave ---------------------------------------------------------------------------------

enum class WaveKind {
  none,   ///< outer and star states are the same
  jump,   ///< a linearly degenerate jump, moving at the characteristic speed of both sides
  fan,    ///< a centred rarefaction fan
  shock,  ///< a genuine shock: label and momentum jump conditions, energy dissipated
};

/// One wave of family ±1 from the outer state to the star state, centred at the origin of
/// (X, t). For family −1 the outer state is on the left, for +1 on the right.
template <class Real>
struct Wave {
  const Law<Real>* law = nullptr;
  int family = -1;
  WaveKind kind = WaveKind::none;
  State<Real> outer, star;

  [[nodiscard]] const State<Real>& left() const { return family < 0 ? outer : star; }
  [[nodiscard]] const State<Real>& right() const { return family < 0 ? star : outer; }

  /// Lagrangian speed of a shock from the label jump condition, m = −[v]/[τ]; of a jump,
  /// the characteristic speed (the same on both sides).
  [[nodiscard]] Real front_speed() const {
    if (kind == WaveKind::shock)
      return -(velocity(right()) - velocity(left())) / (label_density(right()) - label_density(left()));
    return characteristic_speed(*law, star, family);
  }
  /// Lab speed of a jump or shock: dx/dt = v + τ dX/dt on either side.
  [[nodiscard]] Real front_lab_speed() const { return velocity(outer) + label_density(outer) * front_speed(); }

  /// Lagrangian speeds of the wave's edges, left edge first.
  [[nodiscard]] Real left_edge_speed() const {
    if (kind == WaveKind::none) return 0;
    if (kind != WaveKind::fan) return front_speed();
    return characteristic_speed(*law, left(), family);
  }
  [[nodiscard]] Real right_edge_speed() const {
    if (kind == WaveKind::none) return 0;
    if (kind != WaveKind::fan) return front_speed();
    return characteristic_speed(*law, right(), family);
  }

  /// The invariant carried across: J+ = φ + Ψ (C−) or J− = φ − Ψ (C+), in the outer state.
  [[nodiscard]] Real invariant() const { return outer.rapidity + Real(family < 0 ? 1 : -1) * law->psi(outer.stretch); }
  /// The state on the fan (or its rarefaction curve) at Ψ.
  [[nodiscard]] State<Real> on_curve(Real psi) const {
    return State<Real>{family < 0 ? invariant() - psi : invariant() + psi, law->stretch_at_psi(psi)};
  }

  /// The state at Lagrangian speed ξ = (X − X_centre)/t; left of the wave the left state,
  /// right of it the right state. Inside a fan: the characteristic of speed ξ, by bisection on Ψ.
  [[nodiscard]] State<Real> at(Real xi) const {
    if (kind == WaveKind::none) return outer;
    if (xi < left_edge_speed()) return left();
    if (xi >= right_edge_speed()) return right();
    if (kind != WaveKind::fan) return right();
    const Real psi_left = law->psi(left().stretch), psi_right = law->psi(right().stretch);
    const Real psi =
        bisect<Real>([&](Real q) { return characteristic_speed(*law, on_curve(q), family) - xi; }, psi_left, psi_right);
    return on_curve(psi);
  }

  /// D = m [E] − [p v]: the energy a shock removes per unit time and area (zero for other waves).
  [[nodiscard]] Real dissipation_rate() const {
    if (kind != WaveKind::shock) return 0;
    return front_speed() * (energy_density(*law, right()) - energy_density(*law, left())) -
           (energy_flux(*law, right()) - energy_flux(*law, left()));
  }
};

/// The rapidity behind a shock of family ±1 from `outer` to the star stretch: the root of
///   H(φ) = [v] [M] + [p] [τ],
/// m eliminated between m [τ] = −[v] and m [M] = [p], on the side of the outer rapidity where
/// the rarefaction curve through the same stretch lies (the two curves are tangent there).
template <class Real>
Real hugoniot_rapidity(const Law<Real>& law, const State<Real>& outer, Real star_stretch, int family) {
  const Real p_outer = law.pressure(outer.stretch), p_star = law.pressure(star_stretch);
  const Real v_outer = velocity(outer), tau_outer = label_density(outer), m_outer = momentum_density(law, outer);
  const auto h = [&](Real d, Real direction) {
    const State<Real> star{outer.rapidity + direction * d, star_stretch};
    return (velocity(star) - v_outer) * (momentum_density(law, star) - m_outer) +
           (p_star - p_outer) * (label_density(star) - tau_outer);
  };
  const Real psi_change = law.psi(star_stretch) - law.psi(outer.stretch);
  const Real direction = Real(family) * (psi_change > 0 ? Real(1) : Real(-1));
  Real hi = std::fabs(psi_change) + std::numeric_limits<Real>::min();
  for (int i = 0; i < 200 && !(h(hi, direction) > 0); ++i) hi *= 2;
  const Real d = bisect<Real>([&](Real x) { return h(x, direction); }, Real(0), hi);
  return outer.rapidity + direction * d;
}

/// The wave of family ±1 from `outer` to the star at pressure p.
template <class Real>
Wave<Real> wave_to_pressure(const Law<Real>& law, const State<Real>& outer, int family, Real p) {
  Wave<Real> w{&law, family, WaveKind::none, outer, outer};
  if (p == law.pressure(outer.stretch)) return w;
  const Real s = law.stretch_at_pressure(p);
  const Real psi_star = law.psi(s), psi_outer = law.psi(outer.stretch);
  w.star = State<Real>{outer.rapidity + Real(family) * (psi_star - psi_outer), s};
  // Lax: a fan spreads, the characteristic speed growing from its left edge to its right.
  const Real on_outer = characteristic_speed(law, outer, family), on_star = characteristic_speed(law, w.star, family);
  const Real spread = family < 0 ? on_star - on_outer : on_outer - on_star;
  const Real round_off = Real(1e-12) * (std::fabs(on_outer) + std::fabs(on_star));
  if (std::fabs(spread) <= round_off) {
    w.kind = WaveKind::jump;
  } else if (spread > 0) {
    w.kind = WaveKind::fan;
  } else {
    w.kind = WaveKind::shock;
    w.star.rapidity = hugoniot_rapidity(law, outer, s, family);
  }
  return w;
}

// ---- problems ---------------------------------------------------------------------------------

/// The solution of a Riemann, wall or free-end problem, centred at the origin of (X, t).
template <class Real>
struct Solution {
  bool solved = true;      ///< false: no classical solution (the material would be crushed)
  bool parted = false;     ///< the sides separate: each relaxes to the minimum pressure
  Real pressure = 0;       ///< p* (the minimum pressure if parted)
  Wave<Real> left, right;  ///< C− wave into the left state, C+ wave into the right (a wall's side: none)

  /// The state at Lagrangian speed ξ = (X − X_interface)/t: left material for ξ < 0, right for ξ ≥ 0.
  [[nodiscard]] State<Real> at(Real xi) const { return xi < 0 ? left.at(xi) : right.at(xi); }
};

namespace detail {

/// Where the pressure of a solution may lie: above the largest maximum tension (and the
/// minimum pressure), below the smallest maximum pressure.
template <class Real>
struct PressureRange {
  Real lo, hi;
  bool lo_included;
};

/// f decreasing in p on the range; its root by bisection, the bracket's upper end expanded
/// towards the range's end. NaN if f > 0 even there (crushed).
template <class Real, class F>
Real decreasing_root(const F& f, PressureRange<Real> range, Real scale) {
  Real lo = range.lo;
  if (!range.lo_included) {
    // An open end (the maximum tension): approach it.
    Real step = std::isfinite(range.hi) ? std::fmin(scale, (range.hi - range.lo) / 2) : scale;
    lo = range.lo + step;
    for (int i = 0; i < 200 && f(lo) < 0; ++i) {
      step /= 2;
      lo = range.lo + step;
    }
  }
  // Expanding: by doubling on an unbounded range, else by halving the distance to its end.
  const bool bounded = std::isfinite(range.hi);
  Real hi = bounded ? lo + (range.hi - lo) / 2 : std::fmax(lo, Real(0)) + scale;
  for (int i = 0; i < 400 && f(hi) > 0; ++i) {
    const Real next = bounded ? range.hi - (range.hi - hi) / 2 : 2 * hi + scale;
    if (next == hi) break;
    hi = next;
  }
  if (!(f(hi) <= 0)) return std::numeric_limits<Real>::quiet_NaN();
  return bisect<Real>(f, lo, hi);
}

}  // namespace detail

/// Two states meeting at a point: left (law_left) and right (law_right). min_pressure: −inf
/// for a bonded interface, 0 for a contact that pushes but does not pull; a fluid parts at its
/// cavitation pressure whatever the caller says.
template <class Real>
Solution<Real> riemann_problem(const Law<Real>& law_left, const State<Real>& left, const Law<Real>& law_right,
                               const State<Real>& right, Real min_pressure = -std::numeric_limits<Real>::infinity()) {
  min_pressure = std::fmax(min_pressure, std::fmax(law_left.cavitation_pressure(), law_right.cavitation_pressure()));
  const auto rapidity_left = [&](Real p) { return wave_to_pressure(law_left, left, -1, p).star.rapidity; };
  const auto rapidity_right = [&](Real p) { return wave_to_pressure(law_right, right, +1, p).star.rapidity; };
  // φ*_L falls and φ*_R rises with p.
  const auto mismatch = [&](Real p) { return rapidity_left(p) - rapidity_right(p); };
  const Real tension = std::fmax(law_left.max_tension(), law_right.max_tension());
  detail::PressureRange<Real> range{tension, std::fmin(law_left.max_pressure(), law_right.max_pressure()), false};
  Solution<Real> out;
  if (min_pressure >= tension) {
    range = {min_pressure, range.hi, true};
    if (!(mismatch(min_pressure) > 0)) {
      // The sides would need less than the minimum pressure to stay together: they part.
      out.parted = true;
      out.pressure = min_pressure;
      out.left = wave_to_pressure(law_left, left, -1, min_pressure);
      out.right = wave_to_pressure(law_right, right, +1, min_pressure);
      return out;
    }
  }
  const Real scale = std::fmax(law_left.rest_density(), law_right.rest_density());
  out.pressure = detail::decreasing_root<Real>(mismatch, range, scale);
  if (std::isnan(out.pressure)) {
    out.solved = false;
    return out;
  }
  out.left = wave_to_pressure(law_left, left, -1, out.pressure);
  out.right = wave_to_pressure(law_right, right, +1, out.pressure);
  return out;
}

/// Which side of a wall (or free end) the material is on: left means the wall is on its right.
enum class Side { left, right };

/// A state against a wall or piston moving at `wall_rapidity`. min_pressure: 0 for a wall that
/// pushes but does not pull, −inf for a bonded wall. The star moves with the wall; if that needs
/// less than the minimum pressure, the wall lets go and the end relaxes to it.
template <class Real>
Solution<Real> wall_problem(const Law<Real>& law, const State<Real>& state, Side side, Real wall_rapidity,
                            Real min_pressure) {
  min_pressure = std::fmax(min_pressure, law.cavitation_pressure());
  const int family = side == Side::left ? -1 : +1;
  // Decreasing in p: the harder the wall pushes, the more it slows what runs into it.
  const auto mismatch = [&](Real p) {
    const Real star = wave_to_pressure(law, state, family, p).star.rapidity;
    return side == Side::left ? star - wall_rapidity : wall_rapidity - star;
  };
  Solution<Real> out;
  Wave<Real>& wave = side == Side::left ? out.left : out.right;
  detail::PressureRange<Real> range{law.max_tension(), law.max_pressure(), false};
  if (min_pressure >= range.lo) {
    range = {min_pressure, range.hi, true};
    if (!(mismatch(min_pressure) > 0)) {
      out.parted = true;
      out.pressure = min_pressure;
      wave = wave_to_pressure(law, state, family, min_pressure);
      return out;
    }
  }
  out.pressure = detail::decreasing_root<Real>(mismatch, range, law.rest_density());
  if (std::isnan(out.pressure)) {
    out.solved = false;
    return out;
  }
  wave = wave_to_pressure(law, state, family, out.pressure);
  wave.star.rapidity = wall_rapidity;
  return out;
}

/// A state at a free end: p = 0 (or the cavitation pressure if higher).
template <class Real>
Solution<Real> free_end_problem(const Law<Real>& law, const State<Real>& state, Side side) {
  Solution<Real> out;
  out.parted = true;
  out.pressure = std::fmax(Real(0), law.cavitation_pressure());
  (side == Side::left ? out.left : out.right) =
      wave_to_pressure(law, state, side == Side::left ? -1 : +1, out.pressure);
  return out;
}

}  // namespace rigidity::exact
