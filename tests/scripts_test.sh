#!/usr/bin/env bash
# The shipped plotting and analysis scripts on real (tiny) runs: a two-level droplet at twice
# the case's spacing for 4 ms, and a hydrostatic tank at 2 cm for 20 ms. Each script must exit 0
# and write a PNG (checked by its signature) or the figures asked for; plot_run.sh's titles must
# say what was drawn (both levels and their buffer particles; walls; rho0 g depth on the tank's
# line; "parasitic currents" for the drop only); laplace_window.sh's mean must equal the mean of
# series.csv's column; probe_window.sh's figures on a probe file made up here; draws.sh's
# table for two draws, and a second call that finds them finished; poster_runs.sh's published
# preset with none of vrsph's options. Without gnuplot the test is skipped (exit 77) with a
# message.
#   tests/scripts_test.sh VRSPH_BINARY REPO_ROOT
set -euo pipefail

[ $# -eq 2 ] || { echo "usage: scripts_test.sh VRSPH_BINARY REPO_ROOT" >&2; exit 2; }
vrsph=$1; root=${2%/}
if ! command -v gnuplot > /dev/null; then
  echo "scripts_test: skipped: gnuplot is not installed (scripts/setup.sh installs it)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
is_png() { [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }

out=$tmp/run
"$vrsph" run "$root/cases/droplet_vr_2d.toml" --out "$out" --quiet --threads 1 \
  --set resolution.dp=2e-4 --set case.end_time=0.004 --set output.interval=0.002 \
  --set 'output.formats=["csv"]' || fail "vrsph run exited $?"

"$root/scripts/plot_run.sh" "$out" > "$tmp/plot_run.log" || fail "plot_run.sh exited $?"
for png in plot_line_0002 plot_pressure_0002 plot_lambda_0002 plot_max_speed plot_laplace_rmse; do
  is_png "$out/$png.png" || fail "plot_run.sh did not write $png.png: $(cat "$tmp/plot_run.log")"
done
said() { grep "^wrote .*/$1.png: " "$2" || fail "plot_run.sh said nothing of $1.png: $(cat "$2")"; }
title=$(said plot_pressure_0002 "$tmp/plot_run.log")
for want in "droplet_vr_2d (2D, 2 levels, surface tension)" "fluid (L0 " " + L1 " " buffer"; do
  [[ "$title" == *"$want"* ]] || fail "pressure plot title lacks '$want': $title"
done
[[ "$(said plot_max_speed "$tmp/plot_run.log")" == *"parasitic"* ]] || fail "drop speed title"
[[ "$(said plot_line_0002 "$tmp/plot_run.log")" == *"interpolated points"* ]] || fail "line title"

# A tank at rest: walls drawn and counted, rho0 g depth on the vertical line, no parasitic currents.
tank=$tmp/tank
"$vrsph" run "$root/cases/hydrostatic_2d.toml" --out "$tank" --quiet --threads 1 \
  --set resolution.dp=0.02 --set 'fluid_block.0.min=[0.02,0.02]' --set 'fluid_block.0.max=[0.98,0.5]' \
  --set case.end_time=0.02 --set output.interval=0.02 || fail "vrsph run (tank) exited $?"
"$root/scripts/plot_run.sh" "$tank" > "$tmp/plot_tank.log" 2>&1 || fail "plot_run.sh (tank) exited $?"
for png in plot_line_0001 plot_pressure_0001 plot_max_speed; do
  is_png "$tank/$png.png" || fail "plot_run.sh did not write $png.png: $(cat "$tmp/plot_tank.log")"
done
[[ "$(said plot_line_0001 "$tmp/plot_tank.log")" == *"rho0 g depth"* ]] || fail "tank line title"
[[ "$(said plot_pressure_0001 "$tmp/plot_tank.log")" == *"1225 fluid, 405 wall"* ]] \
  || fail "tank pressure title: $(said plot_pressure_0001 "$tmp/plot_tank.log")"
if [[ "$(said plot_max_speed "$tmp/plot_tank.log")" == *"parasitic"* ]]; then
  fail "the tank's speed plot speaks of parasitic currents"
fi

"$root/scripts/plot_window.sh" "$out" 2 lambda -0.001 0.001 0.0012 0.0022 "$tmp/window.png" \
  > /dev/null || fail "plot_window.sh exited $?"
is_png "$tmp/window.png" || fail "plot_window.sh wrote no PNG"

"$root/scripts/compare_max_speed.sh" "$tmp/speed.png" "$out" "a" "$out" "b" > /dev/null \
  || fail "compare_max_speed.sh exited $?"
is_png "$tmp/speed.png" || fail "compare_max_speed.sh wrote no PNG"
"$root/scripts/compare_max_speed.sh" --column mass_fluid "$tmp/mass.png" "$out" "a" > /dev/null \
  || fail "compare_max_speed.sh --column exited $?"
is_png "$tmp/mass.png" || fail "compare_max_speed.sh --column wrote no PNG"
if "$root/scripts/compare_max_speed.sh" --column no_such "$tmp/x.png" "$out" "a" 2> /dev/null; then
  fail "compare_max_speed.sh accepted a column series.csv lacks"
fi

# laplace_window.sh against the column it summarises, over the whole run (at this spacing the line
# can miss every interior particle: those outputs read nan and are left out).
got=$("$root/scripts/laplace_window.sh" "$out" 0 0.004 | awk '/^laplace_rmse:/ { print $3, $5 }')
want=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "laplace_rmse") r = i; next }
                $r != "nan" { n++; s += $r } END { printf "%d %.6g", n, s / n }' "$out/series.csv")
[ "${want%% *}" -ge 1 ] || fail "series.csv has no laplace_rmse value"
[ "$got" = "$want" ] || fail "laplace_window.sh: n and mean '$got', series.csv gives '$want'"
if "$root/scripts/laplace_window.sh" "$out" 1 2 2> /dev/null; then
  fail "laplace_window.sh accepted a window with no output"
fi
# probe_window.sh on a made-up probe file: dry at t = 0, then p = 10, 30, 20 Pa every 0.1 s.
mkdir -p "$tmp/probe"
printf 't,p,rho,vx,vy\n0,,,,\n0.1,10,1000,0,0\n0.2,30,1000,0,0\n0.3,20,1000,0,0\n' \
  > "$tmp/probe/probe_wall.csv"
got=$("$root/scripts/probe_window.sh" "$tmp/probe" wall 0 0.3)
want="probe wall [0, 0.3]: wet 3 of 4, mean_p 20 Pa, max_p 30 Pa at t = 0.2, impulse 5 Pa s"  # 0.5 + 2 + 2.5
[ "$got" = "$want" ] || fail "probe_window.sh printed '$got', expected '$want'"
if "$root/scripts/probe_window.sh" "$tmp/probe" wall 1 2 2> /dev/null; then
  fail "probe_window.sh accepted a window with no output"
fi
# laplace_centroid.sh on a made-up snapshot of a drop moved to (1, 1) mm: the line follows the
# centroid; particles off the strip (0.6 mm > dp/2 away) and buffer particles are left out; the
# 2h = 2.6 mm margins keep the samples at |x - 1 mm| <= 6 mm: 13 samples, one at p = 12 Pa and
# twelve at 10 Pa against 10 Pa: mean 10.1538, rmse sqrt(4/13) = 0.5547.
lc=$tmp/centroid
mkdir -p "$lc"
printf '[resolution]\ndp = 0.001\nh_over_dp = 1.3\n[[output.line]]\nname = "d"\nfrom = [-0.01, 0.0]\nto = [0.01, 0.0]\n[analysis]\nlaplace_pressure = 10.0\n' \
  > "$lc/case.toml"
printf 't,step\n0,0\n' > "$lc/series.csv"
awk 'BEGIN { print "id,level,kind,x,y,vx,vy,rho,p,mass"
  for (k = -9; k <= 9; k++) {
    printf "%d,0,fluid,%.6f,0.001,0,0,1000,%g,1\n", k + 9, 0.001 + k * 0.001, k == 0 ? 12 : 10
    printf "%d,0,fluid,%.6f,0.0016,0,0,1000,100,1\n", k + 30, 0.001 + k * 0.001
    printf "%d,0,fluid,%.6f,0.0004,0,0,1000,100,1\n", k + 60, 0.001 + k * 0.001 }
  print "99,0,buffer,0.0015,0.001,0,0,1000,1000,1" }' > "$lc/particles_0000.csv"
got=$("$root/scripts/laplace_centroid.sh" "$lc" 0 1 | awk '$1 == "0" { print $2, $3, $4, $5, $6 }')
want="1.0000 1.0000 13 10.1538 0.5547"
[ "$got" = "$want" ] || fail "laplace_centroid.sh printed '$got', expected '$want'"
# draws.sh: two draws of the tiny drop, the second with the CFL nudged by 1e-7; its table has a
# line per draw and the spread; a second call finds both finished and runs nothing again.
dr=$tmp/draws
"$root/scripts/draws.sh" --vrsph "$vrsph" --after 0.001 "$root/cases/droplet_vr_2d.toml" 2 "$dr" \
  --set resolution.dp=2e-4 --set case.end_time=0.002 --set output.interval=0.001 \
  --set 'output.formats=["csv"]' > "$tmp/draws.log" || fail "draws.sh exited $?: $(cat "$tmp/draws.log")"
grep -q '^cfl *= *0.2000001\b' "$dr/k1/case.toml" || fail "draw 1 did not run at cfl 0.2000001"
[ "$(grep -c '^k[01] ' "$tmp/draws.log")" = 2 ] || fail "draws.sh table: $(cat "$tmp/draws.log")"
grep -q '^draw means of max_speed .* (2 draws)$' "$tmp/draws.log" || fail "draws.sh: no spread line"
before=$(stat -c %Y "$dr/k0/summary.json")
sleep 1
"$root/scripts/draws.sh" --vrsph "$vrsph" --after 0.001 "$root/cases/droplet_vr_2d.toml" 2 "$dr" \
  --set resolution.dp=2e-4 --set case.end_time=0.002 --set output.interval=0.001 \
  --set 'output.formats=["csv"]' > /dev/null || fail "draws.sh (again) exited $?"
[ "$(stat -c %Y "$dr/k0/summary.json")" = "$before" ] || fail "draws.sh ran a finished draw again"
# poster_runs.sh: the published preset leaves none of vrsph's own options on (the resolved
# case.toml of a tiny VR circle run names none of them with a value other than 0 or false, and
# lays the drop on the lattice), while --model vrsph keeps the case's.
pr=$tmp/poster
for model in published vrsph; do
  "$root/scripts/poster_runs.sh" --binary "$vrsph" --threads 1 --model "$model" vr_circle_4h \
    "$pr/$model" --set resolution.dp=2e-4 --set case.end_time=0.0005 > "$tmp/poster.log" 2>&1 ||
    fail "poster_runs.sh --model $model exited $?: $(cat "$tmp/poster.log")"
done
pub=$pr/published/case.toml
on=$(awk '$1 ~ /^vres_(shepard_fill|flux_edge|buffer_spacing|buffer_ramp|buffer_fill_min)$/ &&
  $3 + 0 != 0 { print $1 }' "$pub")
[ -z "$on" ] || fail "published preset: $on not 0 in $pub"
for key in 'surface_offset = true' 'curvature_correction = true' 'zero_net_force = true' \
  'vres_conserve_momentum = true' 'refresh = "capillary"' 'fill = "rings"'; do
  grep -qF "$key" "$pub" && fail "published preset: $pub has '$key'"
done
for key in 'fill = "lattice"' 'vres_buffer_surface = "own"' 'buffer_rounding = "whole_dp"'; do
  grep -qF "$key" "$pub" || fail "published preset: $pub lacks '$key'"
done
grep -q '^vres_shepard_fill = 2' "$pr/vrsph/case.toml" || fail "--model vrsph lost the case's options"
echo "scripts_test: all scripts ran"
