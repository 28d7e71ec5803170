#pragma once
// The exact solution of the constant-sound-speed shock tube of configs/shock_tube.yaml,
// for tests: the star state from solve_riemann (itself checked against the jump
// conditions in riemann_test.cpp), the shock at its exact speed, and the self-similar
// rarefaction fan along J+ inverted by bisection.
#include <cmath>

#include "rigidity/material.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace rigidity {

struct ShockTube {
  double V = 0.5, T = 0.3, X0 = 0.5;
  State left{0.0, Stretch::from_value(0.5)}, right{0.0, Stretch::natural()};
};

/// The exact stretch at label X and time tube.T; `sol` is the tube's Riemann solution.
inline double shock_tube_exact_stretch(const Material& m, const RiemannSolution& sol, const ShockTube& tube, double X) {
  const double xi = (X - tube.X0) / tube.T;
  const double head = characteristic_speed(m, tube.left, -1);
  const double tail = characteristic_speed(m, sol.left, -1);
  const double shock = shock_speeds(m, tube.right, sol.right, +1).lagrangian;
  if (xi <= head) return tube.left.stretch.value();
  if (xi >= shock) return tube.right.stretch.value();
  if (xi >= tail) return sol.left.stretch.value();
  const double j_plus = tube.left.rapidity + m.riemann_psi(tube.left.stretch);
  double lo = m.riemann_psi(sol.left.stretch), hi = m.riemann_psi(tube.left.stretch);
  for (int i = 0; i < 100; ++i) {
    const double psi = 0.5 * (lo + hi);
    const State st{j_plus - psi, m.stretch_at_psi(psi).value};
    (characteristic_speed(m, st, -1) > xi ? lo : hi) = psi;  // C− speed rises from head (Ψ_L) to tail (Ψ*)
  }
  return m.stretch_at_psi(0.5 * (lo + hi)).value.value();
}

}  // namespace rigidity
