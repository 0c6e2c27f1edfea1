#!/usr/bin/env bash
# Statistics of a drop's pressure error over a time window, from series.csv: the RMSE along the
# first [[output.line]] against analysis.laplace_pressure (laplace_rmse), the mean interior
# pressure on that line (laplace_mean_interior) and the largest particle speed (max_speed).
# One output time can be a lucky instant; the mean over the last outputs is the figure to compare.
#   scripts/laplace_window.sh OUT_DIR T0 T1
# Prints one line per column, "name: n N mean M min A max B", over the outputs with T0 <= t <= T1
# (outputs where no particle lay on the line, laplace_rmse = nan, are left out and counted).
set -euo pipefail

usage() { echo "usage: laplace_window.sh OUT_DIR T0 T1" >&2; }
die() { echo "laplace_window.sh: $*" >&2; exit 1; }

[ $# -eq 3 ] || { usage; exit 2; }
f="${1%/}/series.csv"
[ -f "$f" ] || die "$f: no such file"
num='^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$'
[[ "$2" =~ $num ]] || die "T0 must be a number, not '$2'"
[[ "$3" =~ $num ]] || die "T1 must be a number, not '$3'"

awk -F, -v t0="$2" -v t1="$3" -v file="$f" '
  NR == 1 {
    for (i = 1; i <= NF; i++) c[$i] = i
    if (!("t" in c) || !("max_speed" in c)) { print "laplace_window.sh: " file ": no t or max_speed column" > "/dev/stderr"; exit 3 }
    if (!("laplace_rmse" in c)) { print "laplace_window.sh: " file ": no laplace_rmse column (the case needs analysis.laplace_pressure and an [[output.line]])" > "/dev/stderr"; exit 3 }
    ncol = split("laplace_rmse laplace_mean_interior max_speed", name, " ")
    next
  }
  # A small tolerance on the window ends: output times are sums of the interval.
  $c["t"] + 0 >= t0 - 1e-9 && $c["t"] + 0 <= t1 + 1e-9 {
    for (k = 1; k <= ncol; k++) {
      v = $c[name[k]]
      if (v == "nan" || v == "-nan") { skipped[k]++; continue }
      v += 0; n[k]++; s[k] += v
      if (n[k] == 1 || v < lo[k]) lo[k] = v
      if (n[k] == 1 || v > hi[k]) hi[k] = v
    }
  }
  END {
    if (ncol == 0) exit 3
    if (n[1] + skipped[1] == 0) { printf "laplace_window.sh: %s: no output between t = %s and %s\n", file, t0, t1 > "/dev/stderr"; exit 4 }
    for (k = 1; k <= ncol; k++) {
      if (n[k] == 0) { printf "%s: n 0 (all nan)\n", name[k]; continue }
      printf "%s: n %d mean %.6g min %.6g max %.6g", name[k], n[k], s[k] / n[k], lo[k], hi[k]
      if (skipped[k]) printf " (nan at %d outputs)", skipped[k]
      printf "\n"
    }
  }' "$f"
