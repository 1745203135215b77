# Shell functions the benchmark scripts share (sourced, not run).

# The script's leading comment block (after the #! line), without the "# ": its --help.
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; }

# The median of the numbers on stdin, one per line; nothing when there are none.
median() { sort -g | awk '{a[NR]=$1} END {if (NR == 0) print ""; else print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
