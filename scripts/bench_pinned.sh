#!/usr/bin/env bash
# The one-thread speed ratio of two configurations of vrsph measured at the same time: A on one
# core and B on another (`taskset`), one thread each, the cores swapped every other run; then the
# median of the per-run ratios wall(A) / wall(B) (above 1: B is faster), and the median over
# the pairs of runs with the cores swapped of their geometric mean (the figure to quote: the
# two cores of a virtual machine need not run at the same speed). On a shared machine whose
# speed drifts from one minute to the next (walls of the same run 20-40% apart), two runs made at
# the same moment see the same machine: their ratios spread by a few percent where ratios of
# alternated runs (scripts/bench_rounds.sh) spread by tens of percent. It measures one thread
# only; the two runs share the caches and memory bandwidth of the machine.
#
#   scripts/bench_pinned.sh [--vrsph BIN] [--runs N] [--cores C0,C1] [--out DIR] \
#                           A='BENCH ARGUMENTS' B='BENCH ARGUMENTS'
#
#   A='ARGS', B='ARGS'  `vrsph bench ARGS --threads 1` (case, --time, --set ...); ARGS may start
#                       with `@BIN ` to run another binary (an older build)
#   --runs N            simultaneous runs, every other one with the cores swapped (default 6;
#                       an even number: an odd last run enters no swapped pair)
#   --cores C0,C1       the two cores (default 0,1)
#   --out DIR           where the JSON of every run goes (default a fresh folder under /tmp), kept
# Nothing else should run on the machine meanwhile.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
vrsph="$root/build/release/vrsph" runs=6 cores=0,1 out="" conf_a="" conf_b=""
fail() { echo "bench_pinned.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --vrsph) vrsph=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --cores) cores=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    A=*) conf_a=${1#A=}; shift ;;
    B=*) conf_b=${1#B=}; shift ;;
    *) fail "unknown argument '$1' (configurations are A='bench arguments' B='bench arguments')" ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || fail "--runs: '$runs' is not a positive integer"
[[ "$cores" =~ ^[0-9]+,[0-9]+$ ]] || fail "--cores: '$cores' is not two core numbers C0,C1"
[ -n "$conf_a" ] && [ -n "$conf_b" ] || fail "both A='...' and B='...' are needed"
for c in "$conf_a" "$conf_b"; do
  [[ " $c " != *" --threads"* ]] || fail "'$c': leave --threads out (each run has one thread)"
done
command -v taskset > /dev/null || fail "taskset not found (Debian package util-linux)"
c0=${cores%,*} c1=${cores#*,}
[ "$c0" != "$c1" ] || fail "--cores: the two cores must differ"
[ -n "$out" ] || out=$(mktemp -d /tmp/bench_pinned.XXXXXX)
mkdir -p "$out"

# shellcheck source=scripts/bench_common.sh
. "$root/scripts/bench_common.sh"
# launch NAME CONF CORE RUN: one bench run in the background
launch() {
  split_config "$2" "$vrsph"
  # shellcheck disable=SC2086  # ARGS is a list of words
  OMP_NUM_THREADS=1 taskset -c "$3" "$config_bin" bench $config_args --threads 1 \
    --json "$out/$1-$4.json" > "$out/$1-$4.log" 2>&1 &
}

echo "bench_pinned.sh: $runs simultaneous run(s) of A and B on cores $c0 and $c1; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); work in $out"
ratios=""
for run in $(seq 1 "$runs"); do
  ca=$c0 cb=$c1
  [ $((run % 2)) -eq 0 ] && ca=$c1 cb=$c0
  launch A "$conf_a" "$ca" "$run"; pa=$!
  launch B "$conf_b" "$cb" "$run"; pb=$!
  wait "$pa" || fail "A (run $run) failed: $(tail -n 3 "$out/A-$run.log")"
  wait "$pb" || fail "B (run $run) failed: $(tail -n 3 "$out/B-$run.log")"
  wa=$(wall_of "$out/A-$run.json") wb=$(wall_of "$out/B-$run.json")
  r=$(awk -v x="$wa" -v y="$wb" 'BEGIN { printf "%.4f", x / y }')
  ratios="$ratios $r"
  echo "run $run (A on core $ca): A $wa s, B $wb s, A/B $r"
done
echo "ratio A/B: median $(echo $ratios | tr ' ' '\n' | median) (runs:$ratios)"
# Runs 2k-1 and 2k put A on each core once: the product of their ratios is (A/B)^2 times
# (speed of core c0 / c1) times its inverse, so the square root of the product, the pair's
# geometric mean, is free of the cores' difference. On a machine whose two vCPUs ran 1.3x apart
# (docs/validation.md) the per-run ratios alternated 0.75, 1.32, while the pairs agreed within 1%.
pairs=$(echo $ratios | tr ' ' '\n' | awk 'NF { v[++n] = $1 }
  END { for (k = 2; k <= n; k += 2) printf " %.4f", sqrt(v[k - 1] * v[k]) }')
if [ -n "$pairs" ]; then
  echo "ratio A/B of swapped pairs (the cores' difference cancelled): median $(echo $pairs | tr ' ' '\n' | median) (pairs:$pairs)"
fi
