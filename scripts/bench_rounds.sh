#!/usr/bin/env bash
# Speed ratios between configurations of vrsph (two builds, two option sets, two cases), as the
# project measures them: every configuration once per round, in the order given, for N rounds;
# then each configuration's median wall time and, for each requested pair A/B, the median of the
# per-round ratios wall(A) / wall(B) (above 1: B is faster).
#
#   scripts/bench_rounds.sh [--vrsph BIN] [--runs N] [--out DIR] [--ratio A/B]... \
#                           NAME='BENCH ARGUMENTS' ...
#
#   NAME='ARGS'   a configuration: `vrsph bench ARGS` (case, --time, --threads, --set ...); ARGS
#                 may start with `@BIN ` to run another binary (an older build) for this one
#   --vrsph BIN   the default binary (default build/release/vrsph)
#   --runs N      rounds, at least 3 for a claim (default 3)
#   --ratio A/B   a pair to report (repeatable; default: every configuration against the first)
#   --out DIR     where the JSON of every run goes (default a fresh folder under /tmp), kept
#
# Example: the cost of surface tension, 3 rounds:
#   scripts/bench_rounds.sh on='cases/droplet_2d.toml --time 0.01 --threads 2' \
#     off='cases/droplet_2d.toml --time 0.01 --threads 2 --set fluid.surface_tension=0'
# Nothing else should run on the machine meanwhile.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
vrsph="$root/build/release/vrsph" runs=3 out=""
names=() args=() ratios=()
fail() { echo "bench_rounds.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --vrsph) vrsph=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --ratio) ratios+=("$2"); shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *=*) names+=("${1%%=*}"); args+=("${1#*=}"); shift ;;
    *) fail "unknown argument '$1' (a configuration is NAME='bench arguments')" ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || fail "--runs: '$runs' is not a positive integer"
[ ${#names[@]} -ge 1 ] || fail "no configuration given (NAME='bench arguments')"
index_of() {
  local k
  for k in "${!names[@]}"; do [ "${names[$k]}" = "$1" ] && { echo "$k"; return 0; }; done
  return 1
}
for k in "${!names[@]}"; do
  [[ "${names[$k]}" =~ ^[A-Za-z0-9_.-]+$ ]] || fail "configuration name '${names[$k]}': letters, digits, _ . - only"
  [ "$(index_of "${names[$k]}")" = "$k" ] || fail "configuration name '${names[$k]}' given twice"
done
if [ ${#ratios[@]} -eq 0 ]; then
  for k in "${!names[@]}"; do [ "$k" -gt 0 ] && ratios+=("${names[$k]}/${names[0]}"); done
fi
for r in "${ratios[@]}"; do
  [[ "$r" == */* ]] || fail "--ratio '$r': expected A/B"
  index_of "${r%%/*}" > /dev/null || fail "--ratio '$r': no configuration '${r%%/*}'"
  index_of "${r#*/}" > /dev/null || fail "--ratio '$r': no configuration '${r#*/}'"
done
[ -n "$out" ] || out=$(mktemp -d /tmp/bench_rounds.XXXXXX)
mkdir -p "$out"

# shellcheck source=scripts/bench_common.sh
. "$root/scripts/bench_common.sh"

echo "bench_rounds.sh: $runs round(s) of ${names[*]}; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); work in $out"
for round in $(seq 1 "$runs"); do
  for k in "${!names[@]}"; do
    split_config "${args[$k]}" "$vrsph"
    json="$out/${names[$k]}-$round.json"
    # shellcheck disable=SC2086  # ARGS is a list of words
    "$config_bin" bench $config_args --json "$json" > "$out/${names[$k]}-$round.log" 2>&1 ||
      fail "${names[$k]} (round $round) failed: $(tail -n 3 "$out/${names[$k]}-$round.log")"
    echo "round $round: ${names[$k]} $(wall_of "$json") s"
  done
done

for k in "${!names[@]}"; do
  walls=$(for round in $(seq 1 "$runs"); do wall_of "$out/${names[$k]}-$round.json"; done)
  echo "${names[$k]}: median $(echo "$walls" | median) s (runs: $(echo $walls))"
done
for r in "${ratios[@]}"; do
  a=${r%%/*} b=${r#*/}
  per=$(for round in $(seq 1 "$runs"); do
    awk -v x="$(wall_of "$out/$a-$round.json")" -v y="$(wall_of "$out/$b-$round.json")" \
      'BEGIN { printf "%.4f\n", x / y }'
  done)
  echo "ratio $a/$b: median $(echo "$per" | median) (rounds: $(echo $per))"
done
