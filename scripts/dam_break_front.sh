#!/usr/bin/env bash
# Dam-break surge front of a finished run against the experiments (Martin & Moyce 1952;
# Koshizuka & Oka 1996). Needs csv snapshots (output.formats with "csv") and gnuplot.
#   scripts/dam_break_front.sh OUT_DIR [a=1.0] [g=9.81] [T_shift=0.175]
# Writes OUT_DIR/front.csv (T, Z, t, x_front) and OUT_DIR/front.png; the simulated T is plotted
# both as is and shifted by T_shift (the usual allowance for the gate release in the experiments).
set -euo pipefail
dir=${1:?usage: dam_break_front.sh OUT_DIR [a] [g] [T_shift]}
a=${2:-1.0}
g=${3:-9.81}
shift_T=${4:-0.175}
here=$(cd "$(dirname "$0")/.." && pwd)
ref="$here/reference/dam_break_front.csv"
[ -f "$dir/series.csv" ] || { echo "dam_break_front.sh: $dir/series.csv: not found" >&2; exit 1; }

# Front = largest x over fluid particles of each snapshot; times from series.csv (row k+1 is
# snapshot k, one row per output time).
{
  echo "T,Z,t,x_front"
  k=0
  tail -n +2 "$dir/series.csv" | cut -d, -f1 | while read -r t; do
    f=$(printf "%s/particles_%04d.csv" "$dir" "$k")
    [ -f "$f" ] || break
    xf=$(awk -F, 'NR > 1 && $3 == "fluid" { if (m == "" || $4 > m) m = $4 } END { print m }' "$f")
    awk -v t="$t" -v x="$xf" -v a="$a" -v g="$g" \
      'BEGIN { printf "%.6g,%.6g,%.9g,%.9g\n", t * sqrt(2 * g / a), x / a, t, x }'
    k=$((k + 1))
  done
} > "$dir/front.csv"

grep -v '^#' "$ref" | awk -F, '$1 == "martin_moyce_1952" { print $2 "," $3 }' > "$dir/.mm.dat"
grep -v '^#' "$ref" | awk -F, '$1 == "koshizuka_oka_1996" { print $2 "," $3 }' > "$dir/.ko.dat"
gnuplot <<GP
set terminal pngcairo size 800,560 noenhanced
set output "$dir/front.png"
set datafile separator ","
set key left top
set grid
set xlabel "T = t sqrt(2 g / a)"
set ylabel "Z = x_front / a"
set title "Dam-break surge front: $(basename "$dir")"
plot "$dir/front.csv" every ::1 using 1:2 with lines lw 2 title "vrsph", \
     "$dir/front.csv" every ::1 using (\$1 + $shift_T):2 with lines dt 2 lw 2 title "vrsph, T + $shift_T", \
     "$dir/.mm.dat" using 1:2 with points pt 7 title "Martin & Moyce 1952", \
     "$dir/.ko.dat" using 1:2 with points pt 5 title "Koshizuka & Oka 1996"
GP
rm -f "$dir/.mm.dat" "$dir/.ko.dat"
echo "wrote $dir/front.csv and $dir/front.png"
