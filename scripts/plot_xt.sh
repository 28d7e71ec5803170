#!/usr/bin/env bash
# Draws the x–t diagram of a run's fronts.csv with gnuplot: fronts coloured by kind
# (contact: linearly degenerate jumps, shock, rarefaction steps, interfaces, body ends).
# Usage: scripts/plot_xt.sh RUN_DIR OUT.png [TITLE]
set -euo pipefail
run=${1:?run directory}; out=${2:?output png}; title=${3:-$(basename "$run")}
command -v gnuplot >/dev/null || { echo "plot_xt: gnuplot is not installed (apt-get install gnuplot-nox)" >&2; exit 1; }
[ -f "$run/fronts.csv" ] || { echo "plot_xt: $run/fronts.csv not found (set outputs.fronts: true)" >&2; exit 1; }
gnuplot <<GP
set terminal pngcairo size 900,650 font "Sans,11"
set output "$out"
set datafile separator ","
set title "$title: fronts in the lab frame"
set xlabel "x"
set ylabel "t"
set key outside right
set grid lc rgb "#dddddd"
kinds = "contact shock rarefaction interface boundary"
colors = "#d62728 #9467bd #1f77b4 #2ca02c #222222"
plot for [i=1:5] "$run/fronts.csv" skip 1 \
  using (strcol(5) eq word(kinds,i) ? \$2 : NaN):1:(\$4-\$2):(\$3-\$1) \
  with vectors nohead lw (i==5 ? 2.5 : 1.5) lc rgb word(colors,i) title word(kinds,i)
GP
