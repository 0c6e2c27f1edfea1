#!/usr/bin/env bash
# Cost per particle-step against problem size: runs `vrsph bench` on one case at several
# particle spacings (--set resolution.dp) and prints, for each, the particle count, the speed
# and the cost per particle-step relative to the first size. A flat cost means the code scales
# with the particle count (no part grows faster than N, and the working set's move out of cache
# costs little). Writes DIR/scaling.csv, and DIR/scaling.png when gnuplot is installed.
#
#   scripts/bench_scaling.sh CASE.toml TIME DP... [--threads N] [--set KEY=VALUE]... [--out DIR]
#     TIME: physical time of each run, scaled with dp (TIME x dp / first dp) so that every run
#           takes about the same number of steps.
#   e.g. scripts/bench_scaling.sh cases/bench_dam_break_2d.toml 0.01 0.01 0.005 0.0025 0.0014
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
vrsph=${VRSPH:-$root/build/release/vrsph}
[ $# -ge 3 ] || { sed -n '2,12p' "$0" >&2; exit 2; }
case_file=$1 time=$2; shift 2
dps=() sets=() threads=2 out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --threads) threads=$2; shift 2 ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) dps+=("$1"); shift ;;
  esac
done
[ ${#dps[@]} -ge 1 ] || { echo "bench_scaling.sh: no dp given" >&2; exit 2; }
[ -x "$vrsph" ] || { echo "bench_scaling.sh: $vrsph: not built (VRSPH=... to choose)" >&2; exit 1; }
out=${out:-$(mktemp -d /tmp/bench_scaling.XXXXXX)}
mkdir -p "$out"
echo "particles,dp,time,steps,particle_steps_per_second,ns_per_particle_step,relative_cost,bytes_per_particle" > "$out/scaling.csv"
first_dp=${dps[0]} first_cost=""
for dp in "${dps[@]}"; do
  t=$(awk -v T="$time" -v d="$dp" -v d0="$first_dp" 'BEGIN { printf "%.6g", T * d / d0 }')
  json="$out/bench_$dp.json"
  "$vrsph" bench "$case_file" --time "$t" --threads "$threads" --set "resolution.dp=$dp" \
    "${sets[@]}" --json "$json" > "$out/bench_$dp.log" 2>&1 ||
    { echo "bench_scaling.sh: vrsph failed at dp = $dp (log: $out/bench_$dp.log)" >&2; exit 1; }
  row=$(python3 - "$json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
pss = j["particle_steps_per_second"]
print(j["particles"], j["steps"], pss, 1e9 * j["threads"] / pss, j["bytes_per_particle"])
PY
)
  read -r n steps pss ns bytes <<< "$row"
  first_cost=${first_cost:-$ns}
  rel=$(awk -v a="$ns" -v b="$first_cost" 'BEGIN { printf "%.3f", a / b }')
  echo "$n,$dp,$t,$steps,$pss,$ns,$rel,$bytes" >> "$out/scaling.csv"
  printf '%9d particles (dp %s): %7.3f M particle-steps/s, %6.1f ns per particle-step and thread, %.3f of the first, %.0f B/particle\n' \
    "$n" "$dp" "$(awk -v p="$pss" 'BEGIN{print p/1e6}')" "$ns" "$rel" "$bytes"
done
if command -v gnuplot > /dev/null; then
  gnuplot <<GP
set terminal pngcairo size 800,500 noenhanced
set output "$out/scaling.png"
set datafile separator ","
set logscale x
set xlabel "particles"
set ylabel "cost per particle-step, relative to the smallest run"
set yrange [0:*]
set grid
plot "$out/scaling.csv" using 1:7 skip 1 with linespoints title "$(basename "$case_file" .toml), $threads threads"
GP
fi
echo "bench_scaling.sh: $out/scaling.csv"
