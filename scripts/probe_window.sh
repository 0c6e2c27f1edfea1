#!/usr/bin/env bash
# Statistics of one probe's pressure over a time window, from probe_<NAME>.csv: the number of
# rows with fluid at the probe, the mean and the largest p, and the pressure impulse, the
# integral of p over the window (trapezoids between output times; rows without fluid count as
# p = 0, the probe being dry). For impact pressures, which a weakly compressible run resolves
# as noisy spikes, the impulse and the window mean are the figures to compare between runs.
#   scripts/probe_window.sh OUT_DIR NAME T0 T1
# Prints "probe NAME [T0, T1]: wet W of N, mean_p M Pa, max_p X Pa at t = T, impulse I Pa s".
set -euo pipefail

usage() { echo "usage: probe_window.sh OUT_DIR NAME T0 T1" >&2; }
die() { echo "probe_window.sh: $*" >&2; exit 1; }

[ $# -eq 4 ] || { usage; exit 2; }
f="${1%/}/probe_$2.csv"
[ -f "$f" ] || die "$f: no such file"
num='^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$'
[[ "$3" =~ $num ]] || die "T0 must be a number, not '$3'"
[[ "$4" =~ $num ]] || die "T1 must be a number, not '$4'"

awk -F, -v t0="$3" -v t1="$4" -v name="$2" -v file="$f" '
  NR == 1 {
    for (i = 1; i <= NF; i++) c[$i] = i
    if (!("t" in c) || !("p" in c)) { print "probe_window.sh: " file ": no t or p column" > "/dev/stderr"; exit 3 }
    next
  }
  # A small tolerance on the window ends: output times are sums of the interval.
  $c["t"] + 0 >= t0 - 1e-9 && $c["t"] + 0 <= t1 + 1e-9 {
    t = $c["t"] + 0; wet = ($c["p"] != ""); p = wet ? $c["p"] + 0 : 0
    ++n
    if (wet) { ++w; sum += p; if (w == 1 || p > pmax) { pmax = p; tmax = t } }
    if (n > 1) impulse += 0.5 * (p + plast) * (t - tlast)
    tlast = t; plast = p
  }
  END {
    if (n == 0) { print "probe_window.sh: " file ": no output in [" t0 ", " t1 "]" > "/dev/stderr"; exit 4 }
    if (w == 0) { printf "probe %s [%s, %s]: wet 0 of %d, impulse 0 Pa s\n", name, t0, t1, n; exit 0 }
    printf "probe %s [%s, %s]: wet %d of %d, mean_p %.6g Pa, max_p %.6g Pa at t = %.6g, impulse %.6g Pa s\n",
           name, t0, t1, w, n, sum / w, pmax, tmax, impulse
  }' "$f"
