#!/bin/sh
# A PNG like the VisibleSim paper's Fig. 11 from a conveyor run (gnuplot, Debian package
# gnuplot-nox): left, the mobile's trajectory over the goal path on the 20x20 floor; right, its
# distance to the goal against time. Prints the figures of conveyor-figures.sh too.
#   plot-conveyor.sh TRAJ.csv OUT.png
# TRAJ.csv: vsim examples/worlds/smartblocks-conveyor.xml --mobiles-csv TRAJ.csv
set -eu
[ $# -eq 2 ] || { sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
command -v gnuplot >/dev/null || { echo "plot-conveyor.sh: gnuplot is not installed (apt-get install gnuplot-nox)" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$here/conveyor-figures.sh" "$1" | tee "$work/figures"
"$here/conveyor-figures.sh" --steps "$1" >"$work/steps"
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
