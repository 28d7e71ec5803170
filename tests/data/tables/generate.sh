#!/usr/bin/env bash
# Generates the tables of the `tabulated` material the tests read: the constant_sound_speed law
# (docs/materials.md) with V = 0.5, as p(s) and as e(s), in units of rest_density c², at stretches
# ln-spaced from 0.01 to 100 (41 rows, s = 1 exactly in the middle). Run from this directory:
#   bash generate.sh
set -euo pipefail
for column in p e; do
  awk -v column="$column" -v n=40 'BEGIN {
    v2 = 0.25; k = 1 + v2; lo = log(0.01); hi = log(100)
    printf "# constant_sound_speed, V = 0.5, as %s(s) in units of rest_density c^2 (generate.sh)\n", column
    printf "s,%s\n", column
    for (i = 0; i <= n; ++i) {
      t = lo + (hi - lo) * i / n
      if (i == n / 2) t = 0
      s = exp(t)
      value = column == "p" ? v2 / k * (exp(-k * t) - 1) : (exp(-k * t) + v2) / k
      printf "%.17g,%.17g\n", s, value
    }
  }' > "constant_sound_speed_0p5_$column.csv"
done
