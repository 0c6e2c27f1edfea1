#!/usr/bin/env bash
# The shipped plotting and analysis scripts on a real (tiny) run: a two-level droplet at twice
# the case's spacing for 4 ms. Each script must exit 0 and write a PNG (checked by its signature)
# or the figures asked for; laplace_window.sh's mean must equal the mean of series.csv's column.
#   tests/scripts_test.sh VRSPH_BINARY REPO_ROOT
set -euo pipefail

[ $# -eq 2 ] || { echo "usage: scripts_test.sh VRSPH_BINARY REPO_ROOT" >&2; exit 2; }
vrsph=$1; root=${2%/}
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

"$root/scripts/plot_window.sh" "$out" 2 lambda -0.001 0.001 0.0012 0.0022 "$tmp/window.png" \
  > /dev/null || fail "plot_window.sh exited $?"
is_png "$tmp/window.png" || fail "plot_window.sh wrote no PNG"

"$root/scripts/compare_max_speed.sh" "$tmp/speed.png" "$out" "a" "$out" "b" > /dev/null \
  || fail "compare_max_speed.sh exited $?"
is_png "$tmp/speed.png" || fail "compare_max_speed.sh wrote no PNG"

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
echo "scripts_test: all scripts ran"
