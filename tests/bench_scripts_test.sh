#!/usr/bin/env bash
# The benchmark scripts on tiny runs. bench_peer.sh against a stand-in for DualSPHysics (a
# script that writes the Run.csv a DualSPHysics run writes, with 85,415 particles, 100 steps in
# 2 s: 4.27075 M particle-steps/s): the peer's speed must be read back exactly, the ratio be
# vrsph's over it, and bad options refused. bench_scaling.sh at two spacings: one csv row each,
# the first at relative cost 1. bench_rounds.sh and bench_pinned.sh: their ratios read back.
#   tests/bench_scripts_test.sh VRSPH_BINARY REPO_ROOT
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: bench_scripts_test.sh VRSPH_BINARY REPO_ROOT" >&2; exit 2; }
vrsph=$1; root=${2%/}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

mkdir -p "$tmp/cases"
touch "$tmp/cases/Dam2D.xml" "$tmp/cases/Dam2D.bi4"
cat > "$tmp/fake_ds" <<'SH'
#!/bin/sh
# arguments as DualSPHysics takes them: -cpu -ompthreads:N CASE OUTDIR options...
out=$4
mkdir -p "$out"
printf '%s\n' '#RunName;Np;TSimul;MemCpu;Steps' 'Dam2D;85,415;2.0;18,917,174;100' > "$out/Run.csv"
SH
chmod +x "$tmp/fake_ds"

log=$tmp/peer.log
"$root/scripts/bench_peer.sh" --ds "$tmp/fake_ds" --ds-cases "$tmp/cases" --vrsph "$vrsph" \
  --cases 2d --runs 1 --threads 1 --time 0.0002 --out "$tmp/peer" > "$log" 2>&1 ||
  fail "bench_peer.sh exited $?: $(cat "$log")"
line=$(grep '^2d (' "$log") || fail "no summary line: $(cat "$log")"
[[ "$line" == *"DualSPHysics 4.271 M particle-steps/s"* ]] || fail "peer speed misread: $line"
v=$(python3 -c "import json; print(json.load(open('$tmp/peer/2d-vrsph-1.json'))['particle_steps_per_second'])")
want=$(awk -v v="$v" 'BEGIN { printf "ratio %.2f", v / 4270750 }')
[[ "$line" == *"$want"* ]] || fail "ratio: want '$want' in: $line"

# Without --ds-cases the peer case is written from vrsph's own particles (scripts/peer_case.py).
"$root/scripts/bench_peer.sh" --ds "$tmp/fake_ds" --vrsph "$vrsph" --cases 2d --runs 1 \
  --threads 1 --time 0.0002 --out "$tmp/peer_own" > "$tmp/peer_own.log" 2>&1 ||
  fail "bench_peer.sh without --ds-cases exited $?: $(cat "$tmp/peer_own.log")"
grep -q "peer case $tmp/peer_own/peer_cases/Dam2D" "$tmp/peer_own.log" ||
  fail "peer case not written from vrsph's particles: $(cat "$tmp/peer_own.log")"
[ -s "$tmp/peer_own/peer_cases/Dam2D.bi4" ] || fail "no Dam2D.bi4 written"

if "$root/scripts/bench_peer.sh" --ds "$tmp/fake_ds" --ds-cases "$tmp/nowhere" --vrsph "$vrsph" \
  --cases 2d --runs 1 > "$tmp/bad.log" 2>&1; then fail "missing peer cases accepted"; fi
grep -q "Dam2D.xml and .bi4 missing" "$tmp/bad.log" || fail "bad message: $(cat "$tmp/bad.log")"
if "$root/scripts/bench_peer.sh" --ds "$tmp/fake_ds" --ds-cases "$tmp/cases" --runs x \
  > "$tmp/bad2.log" 2>&1; then fail "--runs x accepted"; fi
grep -q "not a positive integer" "$tmp/bad2.log" || fail "bad message: $(cat "$tmp/bad2.log")"

VRSPH=$vrsph "$root/scripts/bench_scaling.sh" "$root/cases/bench_dam_break_2d.toml" 0.0002 0.02 \
  0.01 --threads 1 --out "$tmp/scaling" > "$tmp/scaling.log" 2>&1 ||
  fail "bench_scaling.sh exited $?: $(cat "$tmp/scaling.log")"
[ "$(wc -l < "$tmp/scaling/scaling.csv")" -eq 3 ] || fail "scaling.csv: $(cat "$tmp/scaling/scaling.csv")"
awk -F, 'NR == 2 && $7 != "1.000" { exit 1 }' "$tmp/scaling/scaling.csv" || fail "first row not 1"
# check_ratios LINE DIR NUM DEN: the per-run ratios listed in LINE's parentheses ("(rounds: ...)"
# or "(runs: ...)") must be wall(DIR/NUM-k.json) / wall(DIR/DEN-k.json) for k = 1, 2.
check_ratios() {
  local want got
  want=$(python3 -c "
import json
w = lambda n: json.load(open('$2/' + n + '.json'))['wall_seconds']
r = sorted(w('$3-%d' % k) / w('$4-%d' % k) for k in (1, 2))
print('%.4f' % r[0], '%.4f' % r[1])")
  got=$(echo "$1" | sed -E 's/.*\((rounds|runs): (.*)\)/\2/' | tr ' ' '\n' | sort -g | xargs)
  [ "$got" = "$want" ] || fail "per-run ratios: got '$got', want '$want' ($1)"
}
# bench_rounds.sh: two configurations, two rounds; the ratio line must be the median of the
# per-round ratios of the walls in the JSON files, and a ratio naming no configuration refused.
small="$root/cases/bench_dam_break_2d.toml --time 0.0002 --threads 1"
"$root/scripts/bench_rounds.sh" --vrsph "$vrsph" --runs 2 --out "$tmp/rounds" \
  a="$small" b="@$vrsph $small --set numerics.precision=\"double\"" > "$tmp/rounds.log" 2>&1 ||
  fail "bench_rounds.sh exited $?: $(cat "$tmp/rounds.log")"
rline=$(grep '^ratio b/a: median' "$tmp/rounds.log") || fail "no ratio line: $(cat "$tmp/rounds.log")"
check_ratios "$rline" "$tmp/rounds" b a
if "$root/scripts/bench_rounds.sh" --vrsph "$vrsph" --ratio a/zz a="$small" \
  > "$tmp/bad3.log" 2>&1; then fail "--ratio a/zz accepted"; fi
grep -q "no configuration 'zz'" "$tmp/bad3.log" || fail "bad message: $(cat "$tmp/bad3.log")"
# bench_pinned.sh: A and B at once on two cores, two runs; the ratio line must be the median of
# the per-run ratios of the walls in the JSON files, and a missing configuration refused.
if [ "$(nproc)" -ge 2 ]; then
  one="$root/cases/bench_dam_break_2d.toml --time 0.0002"
  "$root/scripts/bench_pinned.sh" --vrsph "$vrsph" --runs 2 --out "$tmp/pinned" \
    A="$one" B="@$vrsph $one --set numerics.precision=\"double\"" > "$tmp/pinned.log" 2>&1 ||
    fail "bench_pinned.sh exited $?: $(cat "$tmp/pinned.log")"
  pline=$(grep '^ratio A/B: median' "$tmp/pinned.log") || fail "no ratio line: $(cat "$tmp/pinned.log")"
  check_ratios "$pline" "$tmp/pinned" A B
  # the swapped pair's line: the geometric mean of the two runs' ratios
  gline=$(grep '^ratio A/B of swapped pairs' "$tmp/pinned.log") || fail "no pair line: $(cat "$tmp/pinned.log")"
  want=$(python3 -c "
import json, math
w = lambda n: json.load(open('$tmp/pinned/' + n + '.json'))['wall_seconds']
print('%.4f' % math.sqrt(round(w('A-1') / w('B-1'), 4) * round(w('A-2') / w('B-2'), 4)))")
  got=$(echo "$gline" | sed -E 's/.*\(pairs: (.*)\)/\1/')
  [ "$got" = "$want" ] || fail "pair ratio: got '$got', want '$want' ($gline)"
  if "$root/scripts/bench_pinned.sh" --vrsph "$vrsph" A="$one" > "$tmp/bad4.log" 2>&1; then
    fail "bench_pinned.sh without B accepted"
  fi
  grep -q "both A=" "$tmp/bad4.log" || fail "bad message: $(cat "$tmp/bad4.log")"
else
  pline="bench_pinned.sh not run: one core"
fi
echo "bench_scripts_test: ok ($line; $rline; $pline)"
