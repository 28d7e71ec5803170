#!/usr/bin/env python3
"""The paper's wall impact swept over the impact speed, for `rigid` and for `hooke` at
V = 0.3 ... 0.9, with the closed forms drawn as lines and the runs as points:

    peak wall pressure   p(s*),  s* = gamma (V - v) / V       (the front runs at V into the bar)
    contact duration     2 l0 gamma (1 - V v) / V             (front out to the rear and back)
    rebound velocity     -v                                    (every wave is a jump: no loss)

V = 1 is `rigid` (s* = sqrt((1 - v)/(1 + v)), contact 2 l0 s*: the paper's eqs.). A `hooke`
bar hit at v >= V would be crushed: those runs end with rigidity.InadmissibleError and are
drawn as the vertical line v = V. `constant_sound_speed` runs are drawn too (points only:
its shock dissipates, so it rebounds slower than it came).

    PYTHONPATH=build-tests/python /usr/bin/python3 examples/python/wall_impact.py --out wall_impact.png
"""

import argparse
import math
import os

import numpy

import rigidity


def closed_form(V, v, rho=1.0):
    """Peak pressure, contact duration and rebound velocity of a bar of natural length 1 of
    Brotas' Hooke material (V = 1: the rigid one) hitting a wall at v < V."""
    gamma = 1.0 / math.sqrt((1.0 - v) * (1.0 + v))
    s = gamma * (V - v) / V
    if V == 1.0:
        p = 0.5 * rho * (1.0 / (s * s) - 1.0)
    else:
        R = math.sqrt(V * V + (1.0 - V * V) / (s * s))
        e = rho * (R - V * V) / (1.0 - V * V)
        p = e / R - rho
    return p, 2.0 * gamma * (1.0 - V * v) / V, -v


def impact(model, v, **parameters):
    """Runs the paper's scene with another material and impact speed: (peak p, contact, rebound)."""
    overrides = {"materials.rigid_steel.model": model, "bodies.0.velocity": v,
                 "boundaries.right.position": math.sqrt((1.0 - v) * (1.0 + v)),  # touching at t = 0
                 "outputs.probes.0.every": 0.01}
    V = {"rigid": 1.0, "hooke": parameters.get("wave_speed")}.get(model)
    # Past the separation: the closed form's contact, or long enough for the fluid's.
    overrides["time.end"] = 1.2 * closed_form(V, v)[1] + 0.2 if V and v < V else 6.0
    for key, value in parameters.items():
        overrides["materials.rigid_steel." + key] = value
    if model == "constant_sound_speed":
        overrides["solver.tolerance"] = 1e-3
    r = rigidity.run(PAPER_SCENE, set=overrides)
    t, p = r.probes["wall"]["p"]
    events = r.events
    separations = [t for t, kind in zip(events["t"], events["kind"]) if kind == "separation"]
    contact = separations[0] if separations else float("nan")
    return float(numpy.max(p)), contact, r.summary["bodies"][0]["velocity_mean"]


# The paper's scene as the project ships it (the embedded default, as a file).
PAPER_SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "configs", "paper_wall_impact.yaml")


def sweep(speeds, cases):
    """{label: (V or None, [(v, p, contact, rebound) ...])} from real runs."""
    out = {}
    for label, model, V, parameters in cases:
        rows = []
        for v in speeds:
            try:
                rows.append((v,) + impact(model, v, **parameters))
            except rigidity.InadmissibleError:
                pass  # a hooke bar crushed: v >= V
        out[label] = (V, rows)
    return out


CASES = [("rigid", "rigid", 1.0, {})] + [
    ("hooke V=%.1f" % V, "hooke", V, {"wave_speed": V}) for V in (0.3, 0.5, 0.7, 0.9)
] + [("css c_s=0.5", "constant_sound_speed", None, {"sound_speed": 0.5})]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="wall_impact.png")
    parser.add_argument("--points", type=int, default=24, help="impact speeds per material")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    speeds = numpy.linspace(0.02, 0.96, args.points)
    results = sweep(speeds, CASES)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for (label, (V, rows)), colour in zip(results.items(), plt.cm.viridis(numpy.linspace(0, 0.9, len(CASES)))):
        if not rows:
            continue
        data = numpy.array(rows)
        for k, ax in enumerate(axes):
            ax.plot(data[:, 0], data[:, k + 1], "o", ms=3.5, color=colour, label=label + " (runs)")
        if V is not None:
            fine = numpy.linspace(0.005, min(V, 0.995) - 1e-3, 300)
            curves = numpy.array([closed_form(V, v) for v in fine])
            for k, ax in enumerate(axes):
                ax.plot(fine, curves[:, k], "-", lw=1, color=colour)
    axes[0].set_yscale("log")
    for ax, title in zip(axes, ["peak wall pressure [rho00 c^2]", "contact duration [l0/c]", "rebound velocity [c]"]):
        ax.set_xlabel("impact velocity v [c]")
        ax.set_title(title)
        ax.grid(alpha=0.3)
    axes[1].set_yscale("log")
    axes[2].legend(fontsize=7, loc="lower left")
    fig.suptitle("Bar against a wall: runs (points) and closed forms (lines); hooke bars are crushed at v >= V")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
