#!/usr/bin/env bash
# The materials' figures of docs/materials.md and the README: `rigidity compare` of the
# four built-in materials at their defaults, its charts copied into docs/figures/
# (stress_strain.png, sound_speed.png, impact.png, hugoniot.png). The executable is
# $RIGIDITY, else build-tests/rigidity or build/rigidity (build it first with
# scripts/test.sh or scripts/main.sh). A few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/find_rigidity.sh compare_figures
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$RIGIDITY" compare --materials rigid,hooke,rigid_fluid,constant_sound_speed --out "$out" >/dev/null
mkdir -p docs/figures
for chart in stress_strain sound_speed impact hugoniot; do
  cp "$out/$chart.png" "docs/figures/$chart.png"
done
echo "compare_figures: docs/figures/{stress_strain,sound_speed,impact,hugoniot}.png"
