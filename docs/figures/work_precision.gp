# Work precision: the L1 error of the stretch against the run time of one solve, one
# panel per scene, one curve per solver (finite volume: per order and flux).
# Data: docs/work_precision.csv, written by bench/work_precision.cpp; run
#   bash scripts/work_precision.sh
# or, with the CSV at hand,
#   gnuplot -e "csv='docs/work_precision.csv'; out='docs/figures/work_precision.png'" docs/figures/work_precision.gp
if (!exists("csv")) csv = 'docs/work_precision.csv'
if (!exists("out")) out = 'docs/figures/work_precision.png'

set terminal pngcairo size 1800,640 enhanced font 'Sans,11'
set output out
set datafile separator ','
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xrange [1e-7:10]
set yrange [1e-18:1]
set ytics 1e-16,100,1
set mytics 10
set grid xtics ytics
set xlabel 'run time of one solve [s]'
set ylabel 'L1 error of s(X)'
set key bottom right font ',10' spacing 1.1

floor = 1e-17  # an error of exactly 0 is drawn here
shown(e) = e > floor ? e : floor
pick(scene, solver, order, flux, value) = \
  (strcol(1) eq scene && strcol(2) eq solver && strcol(3) eq order && strcol(4) eq flux) ? value : NaN
# Characteristics tolerances down to 1e-10 are joined; 1e-11 and 1e-12 are drawn apart
# (on the shock tube they can fall far off the curve: see docs/benchmarks.md).
coarse(scene, value) = column(5) > 5e-11 ? pick(scene, 'characteristics', '-', '-', value) : NaN
fine(scene, value) = column(5) < 5e-11 ? pick(scene, 'characteristics', '-', '-', value) : NaN

scenes = 'wall_impact collision shock_tube'
titles = "'(a) paper wall impact: rigid, v = 0.6, t = 0.25 and 0.75' \
'(b) rigid flyer on hooke target (bar\\_on\\_bar), t = 0.75' \
'(c) constant\\_sound\\_speed shock tube, t = 0.3'"

set style line 1 lc rgb '#c0392b' lw 2 pt 7 ps 1.2
set style line 2 lc rgb '#2471a3' lw 2 pt 5 ps 1.0
set style line 3 lc rgb '#229954' lw 2 pt 9 ps 1.2
set style line 4 lc rgb '#2471a3' lw 1.5 pt 4 ps 1.0 dt 2
set style line 5 lc rgb '#229954' lw 1.5 pt 8 ps 1.2 dt 2
set style line 6 lc rgb '#c0392b' lw 2 pt 6 ps 1.8

set multiplot layout 1,3 title 'rigidity work precision: front tracking (characteristics, tolerance 10^{-1} … 10^{-12}) against finite volume (50, 100, … cells per body); errors of 0 drawn at 10^{-17}; dashed grey: the 1 s budget' font ',12'
do for [i=1:3] {
  sc = word(scenes, i)
  set title word(titles, i)
  set arrow 1 from 1, graph 0 to 1, graph 1 nohead lc rgb '#555555' lw 1.5 dt 2
  plot csv using (coarse(sc, $6)):(shown($7)) with linespoints ls 1 title 'characteristics, tolerance 10^{-1} … 10^{-10}', \
       csv using (fine(sc, $6)):(shown($7)) with points ls 6 title 'characteristics, tolerance 10^{-11}, 10^{-12}', \
       csv using (pick(sc, 'finite_volume', '1', 'hll', $6)):(shown($7)) with linespoints ls 2 title 'finite volume, order 1, HLL', \
       csv using (pick(sc, 'finite_volume', '2', 'hll', $6)):(shown($7)) with linespoints ls 3 title 'finite volume, order 2, HLL', \
       csv using (pick(sc, 'finite_volume', '1', 'exact', $6)):(shown($7)) with linespoints ls 4 title 'finite volume, order 1, exact flux', \
       csv using (pick(sc, 'finite_volume', '2', 'exact', $6)):(shown($7)) with linespoints ls 5 title 'finite volume, order 2, exact flux'
}
unset multiplot
