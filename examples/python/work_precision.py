#!/usr/bin/env python3
"""Work against precision through the Python API: the centred rarefaction behind a
withdrawing piston in the constant-sound-speed fluid, by front tracking at several
tolerances and by finite volume at several resolutions, each against the exact fan.

The exact solution is computed here, from the law alone (docs/materials.md): for c_s = V the
Riemann invariant is Ψ(s) = −V ln s, the gas at rest at s0 is crossed by a C+ simple
wave (J− = φ − Ψ kept), so inside the fan φ = V ln(s0/s), and a label X sits at the
state whose C+ speed dX/dt = V / (s (cosh φ + V sinh φ)) is X/t. The piston at velocity
−u leaves s_p = s0 exp(artanh(u)/V) at its face.

    PYTHONPATH=build-tests/python /usr/bin/python3 examples/python/work_precision.py --out work_precision.png
"""

import argparse
import math

import numpy

import rigidity

V, S0, U, T = 0.5, 0.6, 0.2, 0.5  # sound speed, initial stretch (compressed: p > 0), piston speed, time
SAMPLES = 2001


def label_speed(s):
    phi = V * math.log(S0 / s)
    return V / (s * (math.cosh(phi) + V * math.sinh(phi)))


def exact_stretch(X, t):
    """s at label X, time t: the gas at rest ahead of the fan, the piston's state behind it."""
    s_piston = S0 * math.exp(math.atanh(U) / V)
    xi = X / t
    if xi >= label_speed(S0):
        return S0
    if xi <= label_speed(s_piston):
        return s_piston
    lo, hi = S0, s_piston  # the speed falls as s grows across the fan: bisect
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if label_speed(mid) > xi:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def scene(solver):
    return {
        "name": "withdrawing_piston",
        "materials": {"gas": {"model": "constant_sound_speed", "sound_speed": V}},
        "bodies": [{"name": "gas", "material": "gas", "length": 1.0, "stretch": S0}],
        "boundaries": {"left": {"type": "piston", "velocity": -U}, "right": {"type": "wall"}},
        "solver": solver,
        "time": {"end": T},
        "outputs": {"snapshots": [{"times": [T], "quantities": ["s"], "samples": SAMPLES}]},
    }


def error_and_time(solver):
    """L1 error of s over the labels at t = T (trapezoid rule on the samples), solve time."""
    r = rigidity.run(scene(solver))
    X, s = r.snapshots["X"], r.snapshots["value"]
    exact = numpy.array([exact_stretch(x, T) for x in X])
    return float(numpy.trapz(numpy.abs(s - exact), X)), r.summary["stats"]["wall_time_s"]


def best_of(solver, repeat=3):
    """Error and the shortest of `repeat` solve times (a shared machine's noise is one-sided)."""
    runs = [error_and_time(solver) for _ in range(repeat)]
    return runs[0][0], min(t for _, t in runs)


def rows(tolerances, resolutions):
    out = []
    for tol in tolerances:
        e, t = best_of({"method": "characteristics", "tolerance": tol})
        out.append(("characteristics", tol, e, t))
    for cells in resolutions:
        e, t = best_of({"method": "finite_volume", "cells": cells, "order": 2})
        out.append(("finite_volume", cells, e, t))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="work_precision.png")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    table = rows([1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4], [50, 100, 200, 400, 800])
    for method, setting, error, seconds in table:
        print("%-16s %-8g L1 error %.3e  solve %.3e s" % (method, setting, error, seconds))
    fig, ax = plt.subplots(figsize=(6.5, 4.8))
    for method, marker in (("characteristics", "o-"), ("finite_volume", "s-")):
        data = numpy.array([(t, e) for m, _, e, t in table if m == method])
        ax.loglog(data[:, 0], data[:, 1], marker, label=method)
    ax.set_xlabel("solve time [s]")
    ax.set_ylabel("L1 error of s at t = %g" % T)
    ax.set_title("Rarefaction behind a withdrawing piston (c_s = %g c, piston at -%g c)" % (V, U), fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
