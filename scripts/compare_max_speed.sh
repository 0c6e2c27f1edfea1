#!/usr/bin/env bash
# One PNG with the max_speed column of several runs' series.csv against t (the parasitic-velocity
# measure), e.g. a variable-resolution droplet against the uniform run at its fine dp; with
# --column NAME another column of series.csv instead (laplace_rmse, mass_fluid, ...).
#   scripts/compare_max_speed.sh [--column NAME] OUT.png DIR1 LABEL1 [DIR2 LABEL2 ...]
set -euo pipefail

usage() { echo "usage: compare_max_speed.sh [--column NAME] OUT.png DIR1 LABEL1 [DIR2 LABEL2 ...]" >&2; }
die() { echo "compare_max_speed.sh: $*" >&2; exit 1; }

column=max_speed
if [ "${1:-}" = "--column" ]; then
  [ $# -ge 2 ] || { usage; exit 2; }
  column=$2; shift 2
  [[ "$column" =~ ^[A-Za-z0-9_]+$ ]] || die "--column: '$column' is not a column name"
fi
if [ $# -lt 3 ] || [ $(( ($# - 1) % 2 )) -ne 0 ]; then usage; exit 2; fi
command -v gnuplot > /dev/null || die "gnuplot not found (scripts/setup.sh installs it)"
out=$1; shift
plots=""
while [ $# -gt 0 ]; do
  dir=${1%/}; label=$2; shift 2
  f="$dir/series.csv"
  [ -f "$f" ] || die "$f: no such file"
  # Column numbers by header name: t and the column.
  cols=$(head -1 "$f" | awk -F, -v name="$column" '{for (i = 1; i <= NF; ++i) { if ($i == "t") t = i; if ($i == name) v = i }
                                  if (!t || !v) exit 1; print t ":" v}') || die "$f: no t or $column column"
  [ -n "$plots" ] && plots="$plots, "
  plots="$plots'$f' every ::1 using $cols with lines lw 2 title '${label//\'/}'"
done
gnuplot <<GP
set terminal pngcairo size 900,500 noenhanced
set output '$out'
set datafile separator ','
set xlabel 't (s)'
set ylabel '$( [ "$column" = max_speed ] && echo "max speed (m/s)" || echo "$column")'
set grid
set key top right
plot $plots
GP
echo "wrote $out"
