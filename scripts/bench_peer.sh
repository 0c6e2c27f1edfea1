#!/usr/bin/env bash
# Side-by-side speed of vrsph and DualSPHysics on the shipped benchmark cases: runs the two codes
# alternately (vrsph, peer, vrsph, peer, ...), on the same thread count and physical time, and
# prints each code's median particle-steps per second, the median of the per-round ratios, and
# peak memory per particle (peak resident set from /usr/bin/time, and what each code reports).
#
#   scripts/bench_peer.sh --ds BIN [--ds-cases DIR] [--vrsph BIN] [--threads N] [--runs N]
#                         [--cases 2d,3d,3d_400k] [--time T] [--set KEY=VALUE]... [--out DIR]
#
#   --ds BIN        a DualSPHysics 5.x CPU binary (not shipped with vrsph)
#   --ds-cases DIR  GenCase outputs Dam2D.xml/.bi4 and Spheric3D.xml/.bi4, made from the
#                   definitions in bench/peer/ (GenCase bench/peer/Dam2D_Def DIR/Dam2D).
#                   Without it, each peer case is written from vrsph's own particles at t = 0
#                   by scripts/peer_case.py (the same particles in both codes; no GenCase)
#   --vrsph BIN     the vrsph binary (default build/release/vrsph)
#   --threads N     threads for both codes (default 2)
#   --runs N        rounds, at least 3 for a claim (default 3)
#   --cases LIST    which cases (default 2d,3d): 2d = cases/bench_dam_break_2d.toml (85,415
#                   particles), 3d = cases/bench_dam_break_3d.toml (116,184), 3d_400k = the
#                   same 3D case at dp 0.015 m (397,993; its peer case is always written from
#                   vrsph's particles unless DIR holds Spheric3D_400k.xml/.bi4)
#   --time T        physical time of every run (default: 0.05 s in 2D, 0.02 s in 3D, 0.006 s
#                   for 3d_400k)
#   --set KEY=VALUE a case override for the vrsph runs (numerics.precision="mixed"), also
#                   applied to the particles a peer case is written from
#   --out DIR       working directory (default a fresh one under /tmp), kept for inspection
#
# Both codes run the same options: symplectic, Wendland, artificial viscosity, Fourtakas density
# diffusion (DualSPHysics -ddt:3) and no particle output; each code its fastest neighbour cells
# (DualSPHysics -cellmode:half in 2D and 3D; vrsph its default: full cells in 2D, half in 3D).
# Nothing else should run on the machine meanwhile: the figures are ratios of runs made minutes
# apart.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
ds="" ds_cases="" vrsph="$root/build/release/vrsph" threads=2 runs=3 which="2d,3d" time="" out=""
sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --ds) ds=$2; shift 2 ;;
    --ds-cases) ds_cases=$2; shift 2 ;;
    --vrsph) vrsph=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --cases) which=$2; shift 2 ;;
    --time) time=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    -h|--help) sed -n '2,32p' "$0"; exit 0 ;;
    *) echo "bench_peer.sh: unknown option '$1' (see --help)" >&2; exit 1 ;;
  esac
done
fail() { echo "bench_peer.sh: $*" >&2; exit 1; }
[ -n "$ds" ] || fail "--ds BIN is required (a DualSPHysics CPU binary)"
[ -x "$ds" ] || fail "--ds '$ds': not an executable file"
[ -x "$vrsph" ] || fail "--vrsph '$vrsph': not an executable file (build first)"
[ -x /usr/bin/time ] || fail "/usr/bin/time is missing (Debian package 'time')"
case "$runs" in ''|*[!0-9]*) fail "--runs '$runs': not a positive integer" ;; esac
[ "$runs" -ge 1 ] || fail "--runs '$runs': must be at least 1"
out=${out:-$(mktemp -d /tmp/bench_peer.XXXXXX)}
mkdir -p "$out"

median() { sort -g | awk '{a[NR]=$1} END {if (NR==0) {print "nan"; exit}
  print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

# run_vrsph CASE T TAG [SET...] -> "particle_steps_per_second peak_kib bytes_per_particle"
run_vrsph() {
  local c=$1 t=$2 tag=$3; shift 3
  local json="$out/$tag.json"
  /usr/bin/time -f %M -o "$out/$tag.mem" "$vrsph" bench "$c" --time "$t" --threads "$threads" \
    "$@" "${sets[@]}" --json "$json" > "$out/$tag.log" 2>&1 || fail "vrsph failed on $c (log: $out/$tag.log)"
  python3 - "$json" "$(cat "$out/$tag.mem")" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(j["particle_steps_per_second"], sys.argv[2], j["bytes_per_particle"])
PY
}

# run_ds CASE_PREFIX T TAG -> "particle_steps_per_second peak_kib np"
run_ds() {
  local dir="$out/$3"
  rm -rf "$dir"
  OMP_NUM_THREADS=$threads /usr/bin/time -f %M -o "$out/$3.mem" "$ds" -cpu \
    -ompthreads:"$threads" "$1" "$dir" -symplectic -ddt:3 -cellmode:half -sv:none \
    -tmax:"$2" > "$out/$3.log" 2>&1 || fail "DualSPHysics failed on $1 (log: $out/$3.log)"
  # Run.csv: one header line and one data line, ';'-separated; Np, TSimul and Steps by name.
  awk -F';' -v mem="$(cat "$out/$3.mem")" 'NR==1 {for (i=1;i<=NF;i++) col[$i]=i}
    NR==2 {np=$col["Np"]; gsub(",","",np); st=$col["Steps"]; gsub(",","",st)
           printf "%.6g %s %s\n", np*st/$col["TSimul"], mem, np}' "$dir/Run.csv"
}

# peer_case_dir VRSPH_CASE DS_NAME [SET...] -> the folder holding DS_NAME.xml/.bi4: --ds-cases
# when given (and required there for a case with a GenCase definition in bench/peer/), else
# written from vrsph's particles.
peer_case_dir() {
  local vcase=$1 dname=$2; shift 2
  if [ -n "$ds_cases" ] && { [ -f "$ds_cases/$dname.xml" ] ||
                             [ -f "$root/bench/peer/${dname}_Def.xml" ]; }; then
    [ -f "$ds_cases/$dname.xml" ] && [ -f "$ds_cases/$dname.bi4" ] ||
      fail "--ds-cases: $ds_cases/$dname.xml and .bi4 missing (run GenCase on bench/peer/${dname}_Def.xml)"
    echo "$ds_cases"; return
  fi
  local made="$out/peer_cases" run="$out/peer_cases/$dname.run"
  mkdir -p "$made"
  "$vrsph" run "$vcase" --out "$run" --force --quiet --threads "$threads" "$@" "${sets[@]}" \
    --set case.end_time=1e-9 --set output.interval=1 --set 'output.formats=["csv"]' \
    > "$run.log" 2>&1 || fail "vrsph could not write the particles of $vcase (log: $run.log)"
  python3 "$root/scripts/peer_case.py" "$run" "$made/$dname" >&2 ||
    fail "scripts/peer_case.py failed on $run"
  rm -rf "$run"
  echo "$made"
}

# compare LABEL VRSPH_CASE DS_NAME T [SET...]
compare() {
  local label=$1 vcase=$2 dname=$3 t=$4 r dir; shift 4
  local extra=("$@")
  dir=$(peer_case_dir "$vcase" "$dname" "${extra[@]}")
  echo "  $label: peer case $dir/$dname"
  : > "$out/$label.rounds"
  for r in $(seq 1 "$runs"); do
    read -r vs vmem vbytes < <(run_vrsph "$vcase" "$t" "$label-vrsph-$r" "${extra[@]}")
    read -r ps pmem np < <(run_ds "$dir/$dname" "$t" "$label-ds-$r")
    echo "$vs $ps $vmem $pmem $np $vbytes" >> "$out/$label.rounds"
    printf '  %s round %d: vrsph %.3f M, DualSPHysics %.3f M particle-steps/s\n' "$label" "$r" \
      "$(echo "$vs" | awk '{print $1/1e6}')" "$(echo "$ps" | awk '{print $1/1e6}')"
  done
  local mv mp mr vm pm n vb
  mv=$(awk '{print $1}' "$out/$label.rounds" | median)
  mp=$(awk '{print $2}' "$out/$label.rounds" | median)
  mr=$(awk '{print $1/$2}' "$out/$label.rounds" | median)
  vm=$(awk '{print $3}' "$out/$label.rounds" | median)
  pm=$(awk '{print $4}' "$out/$label.rounds" | median)
  vb=$(awk '{print $6}' "$out/$label.rounds" | median)
  n=$(awk 'NR==1 {print $5}' "$out/$label.rounds")
  awk -v l="$label" -v mv="$mv" -v mp="$mp" -v mr="$mr" -v vm="$vm" -v pm="$pm" -v n="$n" \
    -v vb="$vb" -v runs="$runs" -v th="$threads" 'BEGIN {
    printf "%s (%d particles, %d threads, %d rounds): vrsph %.3f M, DualSPHysics %.3f M particle-steps/s, ratio %.2f (median of rounds)\n", l, n, th, runs, mv/1e6, mp/1e6, mr
    printf "  peak resident per particle: vrsph %.0f B (it reports %.0f B over its set-up), DualSPHysics %.0f B\n", vm*1024/n, vb, pm*1024/n }'
}

echo "bench_peer.sh: vrsph $("$vrsph" --version 2>/dev/null | head -1) ${sets[*]:-}, peer $ds, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), work in $out"
IFS=',' read -ra list <<< "$which"
for c in "${list[@]}"; do
  case "$c" in
    2d) compare 2d "$root/cases/bench_dam_break_2d.toml" Dam2D "${time:-0.05}" ;;
    3d) compare 3d "$root/cases/bench_dam_break_3d.toml" Spheric3D "${time:-0.02}" ;;
    3d_400k) compare 3d_400k "$root/cases/bench_dam_break_3d.toml" Spheric3D_400k \
               "${time:-0.006}" --set resolution.dp=0.015 ;;
    *) fail "--cases: unknown case '$c' (2d, 3d, 3d_400k)" ;;
  esac
done
