#!/usr/bin/env bash
# Several draws of one case: the same run repeated with numerics.cfl nudged by k x 1e-7
# (k = 0 .. N-1), which changes every step's dt in its last digits and nothing else a user would
# call a setting. A run whose outcome hangs on discrete events (particles created and deleted at
# a resolution boundary) can end far from another whose inputs differ in the last bit, so one run
# says little about a case's parasitic speed; the spread of a few draws says how much. Per draw,
# the mean and largest max_speed of series.csv after T0, and the particles created and deleted;
# then the median, least and largest draw mean.
#   scripts/draws.sh [--jobs J] [--after T0] [--vrsph BIN] CASE N OUT_DIR [--set KEY=VALUE]...
# Draw k runs in OUT_DIR/k<k> with one thread, J at a time (default 2); a draw whose folder
# already holds summary.json (a finished run) is not run again, so an interrupted study resumes
# where it stopped. T0 defaults to 0.1 s. The base CFL is the case's (after --set), read from
# the resolved case.toml of a one-step run made first (and deleted).
set -euo pipefail

usage() { echo "usage: draws.sh [--jobs J] [--after T0] [--vrsph BIN] CASE N OUT_DIR [--set KEY=VALUE]..." >&2; }
die() { echo "draws.sh: $*" >&2; exit 1; }

root=$(cd "$(dirname "$0")/.." && pwd)
jobs=2; after=0.1; vrsph="$root/build/release/vrsph"
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) [ $# -ge 2 ] || { usage; exit 2; }; jobs=$2; shift 2 ;;
    --after) [ $# -ge 2 ] || { usage; exit 2; }; after=$2; shift 2 ;;
    --vrsph) [ $# -ge 2 ] || { usage; exit 2; }; vrsph=$2; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
[ $# -ge 3 ] || { usage; exit 2; }
case_file=$1; n=$2; out=${3%/}; shift 3
sets=("$@")
[ -f "$case_file" ] || die "$case_file: no such file"
[[ "$n" =~ ^[1-9][0-9]*$ ]] || die "N: '$n' is not a positive whole number"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs: '$jobs' is not a positive whole number"
[[ "$after" =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$ ]] || die "--after: '$after' is not a time"
[ -x "$vrsph" ] || die "$vrsph: not an executable (build first, or give --vrsph)"
for s in "${sets[@]}"; do [ "$s" = "--set" ] || [[ "$s" == *=* ]] || die "'$s': expected --set KEY=VALUE"; done
mkdir -p "$out"

# The case's CFL with the --set lines applied, from the resolved case.toml of a run of one step.
base_cfl=$("$vrsph" run "$case_file" "${sets[@]}" --set case.end_time=1e-12 --out "$out/.cfl" --quiet \
             --threads 1 > /dev/null && awk -F= '/^cfl[ \t]*=/ { gsub(/[ \t]|#.*/, "", $2); print $2; exit }' "$out/.cfl/case.toml") \
  || die "vrsph could not run $case_file with the given --set lines"
rm -rf "$out/.cfl"
[ -n "$base_cfl" ] || die "no numerics.cfl in the resolved case"

run_draw() {
  local k=$1 dir="$out/k$1" cfl
  [ -f "$dir/summary.json" ] && return 0
  cfl=$(awk -v c="$base_cfl" -v k="$k" 'BEGIN { printf "%.10g", c + k * 1e-7 }')
  OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive "$vrsph" run "$case_file" "${sets[@]}" \
    --set "numerics.cfl=$cfl" --out "$dir" --threads 1 --quiet > "$out/k$k.log" 2>&1 \
    || echo "draws.sh: draw $k failed (exit $?): see $out/k$k.log" >&2
}
running=0
for ((k = 0; k < n; ++k)); do
  run_draw "$k" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
done
wait

# One line per draw, then the spread of the draw means.
printf "%-4s %-12s %-10s %-10s %-8s %-8s\n" draw cfl mean max created deleted
for ((k = 0; k < n; ++k)); do
  f="$out/k$k/series.csv"
  [ -f "$f" ] || { echo "k$k: no series.csv"; continue; }
  awk -F, -v k="$k" -v t0="$after" -v cfl_file="$out/k$k/case.toml" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    $col["t"] > t0 { s += $col["max_speed"]; c += 1; if ($col["max_speed"] > m) m = $col["max_speed"] }
    { cr = ("created" in col) ? $col["created"] : 0; de = ("deleted" in col) ? $col["deleted"] : 0 }
    END {
      while ((getline line < cfl_file) > 0) if (line ~ /^cfl[ \t]*=/) { sub(/^[^=]*=[ \t]*/, "", line); sub(/[ \t]*#.*/, "", line); cfl = line }
      if (c == 0) { printf "k%-3s %-12s no samples after %s s\n", k, cfl, t0; exit }
      printf "k%-3s %-12s %-10.5f %-10.5f %-8d %-8d\n", k, cfl, s / c, m, cr, de }' "$f"
done | tee "$out/draws.txt"
awk '$3 ~ /^[0-9.]+$/ { v[++n] = $3 }
     END {
       if (n == 0) { print "no draw has samples"; exit 1 }
       for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
       med = (n % 2) ? v[(n + 1) / 2] : 0.5 * (v[n / 2] + v[n / 2 + 1])
       printf "draw means of max_speed after the start time: median %.5f, least %.5f, largest %.5f (%d draws)\n", med, v[1], v[n], n }' \
  "$out/draws.txt"
