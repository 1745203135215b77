#!/bin/sh
# A PNG like the VisibleSim paper's Fig. 11 from a conveyor run (gnuplot, Debian package
# gnuplot-nox): left, the mobile's trajectory over the goal path on the 20x20 floor; right, its
# distance to the goal against time. Prints the figures of conveyor-figures.sh too.
#   plot-conveyor.sh TRAJ.csv OUT.png
# TRAJ.csv: vsim examples/worlds/smartblocks-conveyor.xml --mobiles-csv TRAJ.csv
set -eu
[ $# -eq 2 ] || { sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
command -v gnuplot >/dev/null || { echo "plot-conveyor.sh: gnuplot is not installed (apt-get install gnuplot-nox)" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$here/conveyor-figures.sh" "$1" | tee "$work/figures"
# The distance to the goal at every step (the figures script's goal, one line per step of mobile 0).
awk -F, 'BEGIN { split("0 10 13 24", T, " "); split("75 350 400 400", X, " "); split("425 425 375 75", Y, " ") }
NR > 1 && $2 == 0 {
  t = $1 + 0; gx = X[4]; gy = Y[4]
  if (t <= T[1]) { gx = X[1]; gy = Y[1] }
  else for (i = 1; i < 4; ++i) if (t <= T[i + 1]) { f = (t - T[i]) / (T[i + 1] - T[i]); gx = X[i] + f * (X[i + 1] - X[i]); gy = Y[i] + f * (Y[i + 1] - Y[i]); break }
  print t, $3, $4, sqrt(($3 - gx) ^ 2 + ($4 - gy) ^ 2)
}' "$1" >"$work/steps"
printf '75 425\n350 425\n400 375\n400 75\n' >"$work/goal"
mean=$(sed -n 's/^mean distance to the goal (2..24 s): \([0-9.]*\) mm/\1/p' "$work/figures")
gnuplot <<GNUPLOT
set terminal pngcairo size 1400,620 font "DejaVu Sans,12"
set output "$2"
set multiplot layout 1,2 title "Air-jet conveying on 20x20 Smart Blocks (VisibleSim paper, Fig. 11)"
set title "trajectory of the part's centre"
set xlabel "x (mm)"; set ylabel "y (mm)"
set xrange [-12.5:487.5]; set yrange [-12.5:487.5]; set size ratio -1
set grid
plot "$work/goal" with linespoints lw 2 pt 7 lc rgb "#c03030" title "goal path", \
     "$work/steps" using 2:3 with lines lw 2 lc rgb "#3060c0" title "part"
set title "distance to the goal (mean 2-24 s: $mean mm)"
set xlabel "t (s)"; set ylabel "distance (mm)"
set autoscale; set size noratio
plot "$work/steps" using 1:4 with lines lw 2 lc rgb "#3060c0" notitle
unset multiplot
GNUPLOT
echo "wrote $2"
