#!/usr/bin/env bash
# The Laplace-pressure error of a drop measured in its own frame, from the particle snapshots: for
# a drop that drifts (a model without a net-force correction), the fixed [[output.line]] of
# series.csv loses it. Same definition as summary.json "laplace" (docs/physics.md section 11),
# with the line moved onto the drop's centre of mass:
#   - the line: the case's first [[output.line]] (its length and direction), centred on the
#     centroid of the fluid mass (both levels);
#   - the strip: fluid particles within dp/2 of that segment (dp of each particle's level);
#   - interior: samples at least 2h from both ends of the strip's samples (h of the end's level);
#   - rmse and mean over the interior samples against analysis.laplace_pressure.
#   scripts/laplace_centroid.sh OUT_DIR T0 T1 [P_EXPECTED]
# P_EXPECTED (Pa) replaces analysis.laplace_pressure (for example sigma / R_eff, R_eff from the
# drop's area).
# Needs csv snapshots (output.formats with "csv"). Prints one line per snapshot with T0 <= t <= T1
# ("t cx cy n mean rmse") and the window means of mean and rmse.
set -euo pipefail

die() { echo "laplace_centroid.sh: $*" >&2; exit 1; }
[ $# -eq 3 ] || [ $# -eq 4 ] || { echo "usage: laplace_centroid.sh OUT_DIR T0 T1 [P_EXPECTED]" >&2; exit 2; }
dir="${1%/}"
case_file="$dir/case.toml"
[ -f "$case_file" ] || die "$case_file: no such file (not a run folder?)"
[ -f "$dir/series.csv" ] || die "$dir/series.csv: no such file"

# Case values: dp, h_over_dp, dp_ratio (1 without refinement), laplace_pressure, the first line.
read -r dp hdp ratio expected fx fy tx ty < <(awk '
  function num(s) { gsub(/#.*/, "", s); sub(/^[^=]*=[ \t]*/, "", s); return s + 0 }
  function pair(s, out) { gsub(/#.*/, "", s); sub(/^[^[]*\[/, "", s); sub(/\].*/, "", s); split(s, out, ",") }
  /^\[/ { sec = $0 }
  sec == "[resolution]" && /^dp[ \t]*=/ { dp = num($0) }
  sec == "[resolution]" && /^h_over_dp[ \t]*=/ { hdp = num($0) }
  sec == "[[refinement]]" && /^dp_ratio[ \t]*=/ && ratio == "" { ratio = num($0) }
  sec == "[analysis]" && /^laplace_pressure[ \t]*=/ { p = num($0) }
  sec == "[[output.line]]" && /^from[ \t]*=/ && fx == "" { pair($0, a); fx = a[1]; fy = a[2] }
  sec == "[[output.line]]" && /^to[ \t]*=/ && tx == "" { pair($0, a); tx = a[1]; ty = a[2] }
  END { if (ratio == "") ratio = 1; print dp, hdp, ratio, p, fx, fy, tx, ty }' "$case_file")
[ $# -eq 4 ] && expected="$4"
[ -n "$ty" ] || die "$case_file: needs resolution.dp, analysis.laplace_pressure and an [[output.line]]"

# Snapshot times from series.csv (row k is snapshot k).
mapfile -t times < <(awk -F, 'NR > 1 { print $1 }' "$dir/series.csv")
printf '%-6s %10s %10s %4s %9s %7s\n' t cx_mm cy_mm n mean rmse
for k in "${!times[@]}"; do
  t="${times[$k]}"
  f=$(printf '%s/particles_%04d.csv' "$dir" "$k")
  [ -f "$f" ] || continue
  awk -v t0="$2" -v t1="$3" -v t="$t" 'BEGIN { exit !(t + 0 >= t0 - 1e-9 && t + 0 <= t1 + 1e-9) }' || continue
  awk -F, -v t="$t" -v dp="$dp" -v hdp="$hdp" -v ratio="$ratio" -v pexp="$expected" \
      -v fx="$fx" -v fy="$fy" -v tx="$tx" -v ty="$ty" '
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $c["kind"] != "fluid" { next }
    { n++; x[n] = $c["x"]; y[n] = $c["y"]; m = $c["mass"]; lv[n] = $c["level"]; p[n] = $c["p"]
      M += m; sx += m * x[n]; sy += m * y[n] }
    END {
      if (M == 0) exit
      cx = sx / M; cy = sy / M
      ux = tx - fx; uy = ty - fy; L = sqrt(ux * ux + uy * uy); ux /= L; uy /= L
      ax = cx - 0.5 * L * ux; ay = cy - 0.5 * L * uy          # the line moved onto the centroid
      ns = 0
      for (i = 1; i <= n; i++) {
        d = dp / ratio ^ lv[i]
        s = (x[i] - ax) * ux + (y[i] - ay) * uy
        q = (x[i] - ax) * uy - (y[i] - ay) * ux
        if (s < 0 || s > L || (q < 0 ? -q : q) > 0.5 * d) continue
        ns++; ss[ns] = s; ps[ns] = p[i]; hs[ns] = hdp * d
      }
      if (ns == 0) { printf "%-6s %10.4f %10.4f %4d %9s %7s\n", t, cx * 1e3, cy * 1e3, 0, "nan", "nan"; exit }
      lo = 1; hi = 1
      for (i = 2; i <= ns; i++) { if (ss[i] < ss[lo]) lo = i; if (ss[i] > ss[hi]) hi = i }
      a = ss[lo] + 2 * hs[lo]; b = ss[hi] - 2 * hs[hi]
      k = 0; sp = 0; se = 0
      for (i = 1; i <= ns; i++) if (ss[i] >= a && ss[i] <= b) { k++; sp += ps[i]; se += (ps[i] - pexp) ^ 2 }
      if (k == 0) { printf "%-6s %10.4f %10.4f %4d %9s %7s\n", t, cx * 1e3, cy * 1e3, 0, "nan", "nan"; exit }
      printf "%-6s %10.4f %10.4f %4d %9.4f %7.4f\n", t, cx * 1e3, cy * 1e3, k, sp / k, sqrt(se / k)
    }' "$f"
done | awk '{ print } $5 != "nan" { n++; m += $5; r += $6 }
  END { if (n) printf "window: %d snapshots, mean interior %.4f Pa, rmse %.4f Pa\n", n, m / n, r / n }'
