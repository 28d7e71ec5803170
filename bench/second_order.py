#!/usr/bin/env python3
"""Work against error where the solution is smooth: the front tracker, whose smooth waves are
steps reconstructed between them (second order in the step, 0.7 sqrt(tolerance)), beside the
second-order finite-volume baseline, on three scenes:

  crossed_fan  a constant_sound_speed bar (V = 0.5) withdrawn by a bonded piston at -0.3c
               towards a bonded wall: the fan reflects off the wall and crosses itself (t = 3);
  shock_tube   configs/shock_tube.yaml at t = 2: the fan has reflected off the wall and
               crossed the shock's reflection;
  pushed_rod   a rigid rod (rho00 = 1, l0 = 1) pushed from rest by a bonded piston at constant
               proper acceleration 1, its velocity table every 0.1 interpolated linearly
               (t = 1.5: the wave has come back from the free end to the piston);
  bouncing_gas the constant_sound_speed bar (V = 0.5) at 0.4c into a wall, free on the other
               end (t = 10: a shock has formed out of a compression wave, taken in its steps
               and reflected weak waves, and the bar has left the wall and rings).

Error: the mean over each body's natural length of |dphi| + |dPsi| at t_end (the error
bound's norm), on 4001 samples per body, against a front-tracking run at tolerance 1e-8
(1e-7 for bouncing_gas; the bound of each is printed beside it). Time: the solver's
wall_time_s (sampling apart).

  bench/second_order.py [--rigidity build/rigidity] [--out docs] [--quick]

Writes second_order.csv and second_order.md into --out; docs/benchmarks.md includes second_order.md.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

CROSSED_FAN = """name: crossed_fan
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies: [{name: bar, material: gas, length: 1.0, velocity: 0.0}]
boundaries: {left: {type: piston, velocity: -0.3, bonded: true}, right: {type: wall, bonded: true}}
time: {end: 3}
outputs: {snapshots: [{times: [3], quantities: [s, v], samples: 4001}]}
"""

SHOCK_TUBE = """name: shock_tube
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies:
  - name: tube
    material: gas
    segments: [{length: 0.5, velocity: 0.0, stretch: 0.5}, {length: 0.5, velocity: 0.0, stretch: 1.0}]
boundaries: {left: {type: wall}, right: {type: wall}}
time: {end: 2}
outputs: {snapshots: [{times: [2], quantities: [s, v], samples: 4001}]}
"""


def pushed_rod():
    rows = ", ".join("[%.1f, %.15f]" % (0.1 * i, 0.1 * i / math.sqrt(1 + (0.1 * i) ** 2)) for i in range(16))
    return """name: pushed_rod
materials: {rod: {model: rigid, rest_density: 1.0}}
bodies: [{name: rod, material: rod, position: 0.0, length: 1.0, velocity: 0.0}]
boundaries:
  left: {type: piston, bonded: true, interpolation: linear, table: [%s]}
  right: {type: free}
time: {end: 1.5}
outputs: {snapshots: [{times: [1.5], quantities: [s, v], samples: 4001}]}
""" % rows


BOUNCING_GAS = """name: bouncing_gas
materials: {gas: {model: constant_sound_speed, sound_speed: 0.5}}
bodies: [{name: bar, material: gas, position: 0, length: 1, velocity: 0.4}]
boundaries: {left: {type: free}, right: {type: wall}}
time: {end: 10}
outputs: {snapshots: [{times: [10], quantities: [s, v], samples: 4001}]}
"""

# Psi(s) = integral from s to 1 of c_s/sigma: V ln(1/s) for the gas, ln(1/s) for the rigid rod.
# (scene, sound speed in Psi, reference tolerance)
SCENES = {
    "crossed_fan": (CROSSED_FAN, 0.5, 1e-8),
    "shock_tube": (SHOCK_TUBE, 0.5, 1e-8),
    "pushed_rod": (pushed_rod(), 1.0, 1e-8),
    "bouncing_gas": (BOUNCING_GAS, 0.5, 1e-7),
}
TOLERANCES = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6]
CELLS = [125, 250, 500, 1000, 2000, 4000]


def run(rigidity, scene, settings, work):
    path = os.path.join(work, "scene.yaml")
    with open(path, "w") as f:
        f.write(scene)
    out = os.path.join(work, "out")
    cmd = [rigidity, "run", path, "--out", out, "--quiet"]
    for s in settings:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    samples = {}
    with open(os.path.join(out, "snapshots.csv")) as f:
        for row in csv.DictReader(f):
            samples.setdefault((row["body"], float(row["X"])), {})[row["quantity"]] = float(row["value"])
    return summary, samples


def error(samples, reference, sound_speed):
    total, count = 0.0, 0
    for key, ref in reference.items():
        got = samples[key]
        total += abs(math.atanh(got["v"]) - math.atanh(ref["v"])) + sound_speed * abs(math.log(got["s"] / ref["s"]))
        count += 1
    return total / count


def slope(points):
    """Least-squares slope of log(error) against log(time)."""
    xs = [math.log(t) for t, e in points if t > 0 and e > 0]
    ys = [math.log(e) for t, e in points if t > 0 and e > 0]
    if len(xs) < 2:
        return float("nan")
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rigidity", default="build/rigidity")
    ap.add_argument("--out", default="docs")
    ap.add_argument("--quick", action="store_true", help="fewer tolerances and cells")
    a = ap.parse_args()
    tolerances = TOLERANCES[:4] if a.quick else TOLERANCES
    cells = CELLS[:4] if a.quick else CELLS
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name, (scene, sound_speed, reference_tolerance) in SCENES.items():
            ref_summary, reference = run(a.rigidity, scene, ["solver.tolerance=%g" % reference_tolerance, "solver.resolution=tolerance"], work)
            print("%s: reference at tolerance %g, bound %.2g" % (name, reference_tolerance,
                                                                ref_summary["solver"]["error_bound"]), file=sys.stderr)
            for tol in tolerances:
                summary, samples = run(a.rigidity, scene, ["solver.tolerance=%g" % tol, "solver.resolution=tolerance"], work)
                rows.append(dict(scene=name, method="characteristics", resolution=tol,
                                 error=error(samples, reference, sound_speed),
                                 bound=summary["solver"]["error_bound"], time_s=summary["stats"]["wall_time_s"],
                                 interactions=summary["stats"]["interactions"]))
            for n in cells:
                summary, samples = run(a.rigidity, scene, ["solver.method=finite_volume", "solver.cells=%d" % n,
                                                           "solver.order=2"], work)
                rows.append(dict(scene=name, method="finite_volume", resolution=n,
                                 error=error(samples, reference, sound_speed), bound="",
                                 time_s=summary["stats"]["wall_time_s"], interactions=""))
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "second_order.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    lines = ["| scene | method | tolerance / cells | error | bound | time [s] | interactions |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        bound = "%.2g" % r["bound"] if r["bound"] != "" else ""
        lines.append("| %s | %s | %g | %.2g | %s | %.3g | %s |" % (r["scene"], r["method"], r["resolution"],
                                                                   r["error"], bound, r["time_s"], r["interactions"]))
    lines += ["", "Slope of log(error) against log(time), fitted over the rows above:", "",
              "| scene | characteristics | finite volume |", "|---|---|---|"]
    for name in SCENES:
        ft = [(r["time_s"], r["error"]) for r in rows if r["scene"] == name and r["method"] == "characteristics"]
        fv = [(r["time_s"], r["error"]) for r in rows if r["scene"] == name and r["method"] == "finite_volume"]
        lines.append("| %s | %.2f | %.2f |" % (name, slope(ft), slope(fv)))
    text = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "second_order.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
