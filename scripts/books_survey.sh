#!/usr/bin/env bash
# Energy and momentum books of random scenes: runs each seed of a random
# scene generator at a tolerance, with a time-out, and lists the runs whose books do not
# close: energy_final + energy_dissipated - energy_initial - wall_work - energy_droplets - energy_waves
# (positive: energy created, or dissipation booked beyond what the bodies lost), the same for
# momentum, and a negative energy_dissipated. The energy residual is set against the run's
# error bound times sqrt(rest energy x (kinetic + internal energy at t = 0 + wall work)), the
# energy a rapidity error of that mean size moves at those speeds; the momentum residual
# against the bound times the rest energy (c = 1).
#   scripts/books_survey.sh RIGIDITY GENERATOR TOLERANCE FIRST_SEED LAST_SEED [TIMEOUT_S] [OUT_DIR]
# GENERATOR SEED --tolerance T --end 20 writes a scene to stdout (e.g. random_scene.py).
set -euo pipefail
rigidity=$1 generator=$2 tolerance=$3 first=$4 last=$5 timeout_s=${6:-20} out=${7:-books_survey_$3}
mkdir -p "$out"
for seed in $(seq "$first" "$last"); do
  python3 "$generator" "$seed" --tolerance "$tolerance" --end 20 > "$out/$seed.yaml"
  code=0
  timeout "$timeout_s" "$rigidity" run "$out/$seed.yaml" --out "$out/run$seed" --quiet > /dev/null 2> "$out/$seed.err" ||
    code=$?
  echo "$seed $code"
done > "$out/codes.txt"
python3 - "$out" <<'PY'
import json, math, os, sys
out = sys.argv[1]
rows = []
for line in open(os.path.join(out, "codes.txt")):
    seed, code = line.split()
    path = os.path.join(out, f"run{seed}", "summary.json")
    if not os.path.exists(path):
        print(f"seed {seed}: exit {code}, no summary.json")
        continue
    d = json.load(open(path))
    c = d["conservation"]
    rest = sum(b["rest_energy"] for b in d["bodies"])
    motion = c["energy_initial"] - rest + max(c["wall_work"], 0.0)
    e = (c["energy_final"] + c["energy_dissipated"] - c["energy_initial"] - c["wall_work"] - c.get("energy_droplets", 0.0)
         - c.get("energy_waves", 0.0))
    p = (c["momentum_final"] - c["momentum_initial"] - c["wall_impulse"] - c.get("momentum_droplets", 0.0)
         - c.get("momentum_waves", 0.0))
    bound = d["solver"].get("error_bound", float("nan"))
    allowed = bound * math.sqrt(rest * max(motion, 0.0)) + 1e-12 * rest
    rows.append((int(seed), d["status"], e, p, c["energy_dissipated"], bound, allowed, motion, bound * rest + 1e-12 * rest))
created = sum(1 for r in rows if r[2] > 1e-12 * abs(r[6]) + 1e-13)
print(f"{len(rows)} runs with books; energy residual > 0 in {created}")
for seed, status, e, p, dissipated, bound, allowed, motion, allowed_p in rows:
    why = []
    if dissipated < 0: why.append("negative dissipation")
    if e > allowed: why.append("energy created beyond the bound")
    if e < -allowed: why.append("energy lost beyond the bound")
    if abs(p) > allowed_p: why.append("momentum beyond the bound")
    if why:
        print(f"seed {seed} ({status}): energy residual {e:+.3e} ({e / motion if motion > 0 else float('nan'):+.1e} of the "
              f"motion), momentum {p:+.3e}, dissipated {dissipated:.3e}, bound {bound:.2e}, allowed {allowed:.2e}: "
              + "; ".join(why))
PY
