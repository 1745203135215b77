#!/bin/sh
# The Fig. 11 figures of a conveyor run: reads the `vsim --mobiles-csv` file of
# examples/worlds/smartblocks-conveyor.xml (mobile 0) and prints the distance from the mobile's
# centre to the goal (the broken line (75, 425) at 0 s, (350, 425) at 10 s, (400, 375) at 13 s,
# (400, 75) at 24 s, interpolated in time) between 2 s and 24 s: mean and maximum; the final
# position and its distance to (400, 75).
#   conveyor-figures.sh TRAJ.csv [OTHER.csv]
#   conveyor-figures.sh --steps TRAJ.csv
# With a second file (the same run at another --physics-step), also the largest distance between
# the two trajectories at the times both have. With --steps, instead, one line per physics step:
# t, x, y and the distance to the goal (what plot-conveyor.sh draws).
set -eu
steps=0
if [ "${1:-}" = --steps ]; then steps=1; shift; fi
[ $# -ge 1 ] || { sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
awk -F, -v other="${2:-}" -v steps="$steps" '
function goal(t,   i, f) {
  if (t <= T[0]) { gx = X[0]; gy = Y[0]; return }
  for (i = 0; i < 3; ++i)
    if (t <= T[i + 1]) { f = (t - T[i]) / (T[i + 1] - T[i]); gx = X[i] + f * (X[i + 1] - X[i]); gy = Y[i] + f * (Y[i + 1] - Y[i]); return }
  gx = X[3]; gy = Y[3]
}
BEGIN {
  split("0 10 13 24", T, " "); split("75 350 400 400", X, " "); split("425 425 375 75", Y, " ")
  for (i = 0; i < 4; ++i) { T[i] = T[i + 1]; X[i] = X[i + 1]; Y[i] = Y[i + 1] }
  if (other != "") while ((getline line < other) > 0) { split(line, f, ","); if (f[2] == "0") { ox[f[1]] = f[3]; oy[f[1]] = f[4] } }
}
NR > 1 && $2 == 0 && steps {
  goal($1 + 0); print $1 + 0, $3, $4, sqrt(($3 - gx) ^ 2 + ($4 - gy) ^ 2); next
}
NR > 1 && $2 == 0 {
  t = $1 + 0; x = $3; y = $4; fx = x; fy = y
  if (t >= 2 && t <= 24) { goal(t); d = sqrt((x - gx) ^ 2 + (y - gy) ^ 2); sum += d; n++; if (d > max) max = d }
  if (other != "" && ($1 in ox)) { dd = sqrt((x - ox[$1]) ^ 2 + (y - oy[$1]) ^ 2); shared++; if (dd > apart) apart = dd }
}
END {
  if (steps) exit 0
  if (n == 0) { print "conveyor-figures: no line of mobile 0 between 2 s and 24 s" > "/dev/stderr"; exit 1 }
  printf "mean distance to the goal (2..24 s): %.2f mm\n", sum / n
  printf "max distance to the goal (2..24 s): %.2f mm\n", max
  printf "final position: (%.2f, %.2f) mm, %.2f mm from (400, 75)\n", fx, fy, sqrt((fx - 400) ^ 2 + (fy - 75) ^ 2)
  if (other != "") {
    if (shared == 0) { print "conveyor-figures: the two files share no time" > "/dev/stderr"; exit 1 }
    printf "largest distance between the two trajectories: %.4f mm (%d shared times)\n", apart, shared
  }
}' "$1"
