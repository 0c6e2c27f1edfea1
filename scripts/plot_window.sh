#!/usr/bin/env bash
# A zoom on one snapshot: the particles inside a window, coloured by a field of the particle csv
# (lambda, curvature, p, ...), level 0 as large dots and finer levels as small ones, buffer
# particles ringed in black. Meant for the place where a free surface crosses a resolution
# boundary (lambda across the interface). 2D runs with csv snapshots; needs gnuplot.
#   scripts/plot_window.sh OUT_DIR INDEX FIELD XMIN XMAX YMIN YMAX [OUT.png]
# Coordinates in metres; the plot is in mm. Default output: OUT_DIR/plot_FIELD_window_NNNN.png.
set -euo pipefail

usage() { echo "usage: plot_window.sh OUT_DIR INDEX FIELD XMIN XMAX YMIN YMAX [OUT.png]" >&2; }
die() { echo "plot_window.sh: $*" >&2; exit 1; }

if [ $# -lt 7 ] || [ $# -gt 8 ]; then usage; exit 2; fi
command -v gnuplot > /dev/null || die "gnuplot not found (scripts/setup.sh installs it)"
dir=${1%/}
[[ "$2" =~ ^[0-9]+$ ]] || die "INDEX must be a non-negative integer, not '$2'"
nnnn=$(printf "%04d" $((10#$2)))
field=$3; x0=$4; x1=$5; y0=$6; y1=$7
parts="$dir/particles_$nnnn.csv"
[ -f "$parts" ] || die "$parts: not found"
out=${8:-$dir/plot_${field}_window_$nnnn.png}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# "x_mm y_mm value" per level and kind: $tmp/L<level>.dat, buffer particles also in $tmp/buf.dat.
awk -F, -v f="$field" -v x0="$x0" -v x1="$x1" -v y0="$y0" -v y1="$y1" -v out="$tmp" '
  NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
            if (!("x" in c) || !("y" in c) || !("kind" in c) || !(f in c)) exit 3
            next }
  {
    x = $c["x"] + 0; y = $c["y"] + 0
    if (x < x0 || x > x1 || y < y0 || y > y1 || $c["kind"] == "wall") next
    lev = ("level" in c) ? $c["level"] : 0
    line = sprintf("%.6g %.6g %s", 1000 * x, 1000 * y, $c[f])
    print line > (out "/L" lev ".dat")
    if ($c["kind"] == "buffer") print line > (out "/buf.dat")
  }' "$parts" || die "$parts: no x, y, kind or '$field' column"
ls "$tmp"/L*.dat > /dev/null 2>&1 || die "no particle inside the window"

plots=""
for f in "$tmp"/L*.dat; do
  lev=$(basename "$f" .dat); lev=${lev#L}
  ps=$([ "$lev" = 0 ] && echo 1.4 || echo 0.7)
  [ -n "$plots" ] && plots="$plots, "
  plots="$plots'$f' using 1:2:3 with points pt 7 ps $ps lc palette title 'level $lev'"
done
[ -f "$tmp/buf.dat" ] && plots="$plots, '$tmp/buf.dat' using 1:2 with points pt 6 ps 1.2 lc rgb 'black' title 'buffer'"
gnuplot <<GP
set terminal pngcairo size 900,760 noenhanced
set output '$out'
set size ratio -1
set xlabel 'x (mm)'
set ylabel 'y (mm)'
set cblabel '$field'
set key outside bottom center horizontal
set title '$(basename "$dir"): $field, snapshot $nnnn'
set palette rgbformulae 33,13,10
plot $plots
GP
echo "wrote $out"
