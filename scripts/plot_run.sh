#!/usr/bin/env bash
# PNG plots of one snapshot of a finished (or stopped) run. Needs csv snapshots (output.formats with
# "csv") and gnuplot; bash + awk only otherwise.
#   scripts/plot_run.sh OUT_DIR [INDEX]      (INDEX: snapshot number, default the last one)
# Writes, in OUT_DIR (NNNN = INDEX, 4 digits):
#   plot_line_NNNN.png      pressure along the first [[output.line]] against s: the particles of
#                           the strip, the interpolated points (line_<name>_interp_NNNN.csv), the
#                           Laplace value (case.toml [analysis] laplace_pressure) as a horizontal
#                           line, and with gravity rho0 g depth below the highest fluid particle of
#                           each particle's column
#   plot_pressure_NNNN.png  particles at (x, y) coloured by p (3D: the slice |z| < dp); each level
#                           at a dot size in proportion to its dp, buffer particles ringed, walls grey
#   plot_lambda_NNNN.png    the same coloured by lambda (the surface-tension eigenvalue), if written
#   plot_max_speed.png      series.csv max_speed against t
#   plot_laplace_rmse.png   series.csv laplace_rmse and laplace_mean_interior against t, if present
# Titles name the case (name, dimension, levels, walls, gravity, surface tension) and count what
# is drawn. Columns are found by their header names, so 2D and 3D files both work.
set -euo pipefail

usage() {
  echo "usage: plot_run.sh OUT_DIR [INDEX]" >&2
  echo "  plots snapshot INDEX (default: the last) of the run in OUT_DIR into OUT_DIR/plot_*.png" >&2
}
die() { echo "plot_run.sh: $*" >&2; exit 1; }

if [ $# -lt 1 ] || [ $# -gt 2 ]; then usage; exit 2; fi
case "$1" in -h|--help) usage; exit 0 ;; esac
dir=${1%/}
[ -d "$dir" ] || die "$dir: no such folder"
command -v gnuplot > /dev/null || die "gnuplot not found (scripts/setup.sh installs it)"

# Snapshot index: given, or the largest NNNN of particles_NNNN.csv.
if [ $# -ge 2 ]; then
  [[ "$2" =~ ^[0-9]+$ ]] || die "INDEX must be a non-negative integer, not '$2'"
  idx=$((10#$2))
else
  last=""
  for f in "$dir"/particles_[0-9]*.csv; do
    [ -f "$f" ] || continue
    k=$(basename "$f" .csv); k=${k#particles_}
    [[ "$k" =~ ^[0-9]+$ ]] || continue
    if [ -z "$last" ] || [ $((10#$k)) -gt $((10#$last)) ]; then last=$k; fi
  done
  [ -n "$last" ] || die "$dir: no particles_NNNN.csv (was the run written with output.formats = [..., \"csv\"]?)"
  idx=$((10#$last))
fi
nnnn=$(printf "%04d" "$idx")
parts="$dir/particles_$nnnn.csv"
[ -f "$parts" ] || die "$parts: not found"

# Settings from the resolved case.toml: value of KEY in [SECTION] (first table of that name for an
# array of tables such as [[output.line]]); empty when absent.
case_toml="$dir/case.toml"
toml_get() {  # SECTION KEY
  [ -f "$case_toml" ] || return 0
  awk -v want="$1" -v key="$2" '
    /^[ \t]*\[/ { s = $0; gsub(/[][ \t]/, "", s); sub(/#.*/, "", s); n[s]++; sec = s; next }
    sec == want && n[sec] == 1 {
      line = $0; sub(/#.*/, "", line)
      if (match(line, "^[ \t]*" key "[ \t]*=")) {
        v = substr(line, RLENGTH + 1); gsub(/^[ \t]+|[ \t]+$/, "", v); gsub(/"/, "", v)
        print v; exit
      }
    }' "$case_toml"
}
[ -f "$case_toml" ] || echo "plot_run.sh: $case_toml not found: no Laplace line, no dp" >&2
dim=$(toml_get case dimension)
if [ -z "$dim" ]; then  # no case.toml: 3D when the particle file has a z column
  dim=$(head -n 1 "$parts" | awk -F, '{ d = 2; for (i = 1; i <= NF; i++) if ($i == "z") d = 3; print d }')
fi
dp=$(toml_get resolution dp)
laplace=$(toml_get analysis laplace_pressure)
case_name=$(toml_get case name); case_name=${case_name:-$(basename "$dir")}
interval=$(toml_get output interval)
end_time=$(toml_get case end_time)
rho0=$(toml_get fluid density); rho0=${rho0:-1000}
sigma=$(toml_get fluid surface_tension); sigma=${sigma:-0}
# |g| from fluid.gravity ("[0.0, -9.81]"); 0 without it.
g=$(toml_get fluid gravity | awk -F, '{ s = 0; for (i = 1; i <= NF; i++) { v = $i; gsub(/[][ ]/, "", v); s += v * v }
                                       printf "%.10g", sqrt(s) }')
g=${g:-0}
count_tables() {  # NAME -> how many [[NAME]] tables case.toml has
  if [ -f "$case_toml" ]; then grep -c "^\[\[$1\]\]" "$case_toml" || true; else echo 0; fi
}
n_levels=$(( $(count_tables refinement) + 1 ))
n_walls=$(count_tables wall_block)
# What the case is, for the titles: "dam_break_2d (2D, 1 wall block, gravity)".
case_title="$case_name (${dim}D"
if [ "$n_levels" -gt 1 ]; then case_title="$case_title, $n_levels levels"; fi
if [ "$n_walls" -eq 1 ]; then case_title="$case_title, 1 wall block"; fi
if [ "$n_walls" -gt 1 ]; then case_title="$case_title, $n_walls wall blocks"; fi
is_pos() { awk -v v="$1" 'BEGIN { exit !(v + 0 > 0) }'; }
if is_pos "$g"; then case_title="$case_title, gravity"; fi
if is_pos "$sigma"; then case_title="$case_title, surface tension"; fi
case_title="$case_title)"

# Time of the snapshot: from particles.pvd, else INDEX x interval (the last one at the end time).
t=""
if [ -f "$dir/particles.pvd" ]; then
  t=$(sed -n "s/.*timestep=\"\([^\"]*\)\".*file=\"particles_$nnnn\.vtp\".*/\1/p" "$dir/particles.pvd")
fi
if [ -z "$t" ] && [ -n "$interval" ]; then
  t=$(awk -v k="$idx" -v dt="$interval" -v te="${end_time:-1e300}" \
      'BEGIN { t = k * dt; if (t > te) t = te; printf "%.6g", t }')
fi
tlabel=${t:+t = $t s}; tlabel=${tlabel:-snapshot $nnnn}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# ---------------------------------------------------------------------------------------------
# 1. Pressure along the first line.
line_name=$(toml_get output.line name)
line_file=""
[ -n "$line_name" ] && [ -f "$dir/line_${line_name}_$nnnn.csv" ] && line_file="$dir/line_${line_name}_$nnnn.csv"
if [ -z "$line_file" ]; then  # no case.toml: the first line file of this snapshot, by name
  for f in "$dir"/line_*_"$nnnn".csv; do
    [ -f "$f" ] || continue
    case "$f" in *_interp_"$nnnn".csv) continue ;; esac
    line_file=$f
    line_name=$(basename "$f" "_$nnnn.csv"); line_name=${line_name#line_}
    break
  done
fi
vcol=$([ "$dim" = 3 ] && echo z || echo y)  # the vertical coordinate
if [ -z "$line_file" ]; then
  echo "plot_run.sh: no line_<name>_$nnnn.csv in $dir: line plot skipped" >&2
else
  # "s p x y [z]" rows by header name (x y [z]: for the hydrostatic reference)
  line_rows() {  # FILE -> rows with a p value
    awk -F, -v dim="$dim" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
                       if (!("s" in c) || !("p" in c)) { print "no s or p column" > "/dev/stderr"; exit 1 }
                       next }
             $c["p"] != "" { printf "%s %s %s %s %s\n", $c["s"], $c["p"], $c["x"], $c["y"], (dim == 3 ? $c["z"] : 0) }' "$1"
  }
  line_rows "$line_file" > "$tmp/line.dat" || die "$line_file: header lacks s or p"
  npts=$(wc -l < "$tmp/line.dat")
  interp_file="$dir/line_${line_name}_interp_$nnnn.csv"
  interp_plot="" interp_note=""
  : > "$tmp/interp.dat"
  if [ -f "$interp_file" ]; then
    line_rows "$interp_file" > "$tmp/interp.dat" || die "$interp_file: header lacks s or p"
    ninterp=$(wc -l < "$tmp/interp.dat"); nall=$(($(wc -l < "$interp_file") - 1))
    interp_note=", $ninterp of $nall interpolated points inside the fluid"
    [ "$ninterp" -gt 0 ] && interp_plot=", \"$tmp/interp.dat\" using 1:2 with lines lw 2 lc rgb \"#2ca02c\" title \"interpolated every dp/2 ($ninterp points)\""
  fi
  ref_plot="" hydro_note=""
  if [ -n "$laplace" ]; then
    ref_plot=", $laplace with lines lw 2 dt 2 lc rgb \"#d62728\" title \"Laplace $laplace Pa\""
  fi
  if is_pos "$g" && [ -n "$dp" ]; then
    # rho0 g (z_top - z), z_top the highest fluid particle of the point's column (columns dp wide),
    # at the strip's particles and the interpolated points.
    cat "$tmp/line.dat" "$tmp/interp.dat" |
      awk -v parts="$parts" -v dp="$dp" -v dim="$dim" -v v="$vcol" -v rhog="$(awk -v r="$rho0" -v g="$g" 'BEGIN { print r * g }')" '
        function key(x, y) { return (dim == 3) ? sprintf("%d,%d", int(x / dp + (x < 0 ? -0.5 : 0.5)), int(y / dp + (y < 0 ? -0.5 : 0.5))) : sprintf("%d", int(x / dp + (x < 0 ? -0.5 : 0.5))) }
        BEGIN { while ((getline line < parts) > 0) {
                  n = split(line, a, ",")
                  if (++row == 1) { for (i = 1; i <= n; i++) c[a[i]] = i; continue }
                  if (a[c["kind"]] != "fluid") continue
                  k = key(a[c["x"]], (dim == 3) ? a[c["y"]] : 0); zz = a[c[v]] + 0
                  if (!(k in top) || zz > top[k]) top[k] = zz
                } }
        { k = key($3, (dim == 3) ? $4 : 0); zz = (dim == 3) ? $5 : $4
          if (k in top && top[k] >= zz) print $1, rhog * (top[k] - zz) }' | sort -g > "$tmp/hydro.dat"
    if [ -s "$tmp/hydro.dat" ]; then
      ref_plot="$ref_plot, \"$tmp/hydro.dat\" using 1:2 with lines lw 2 dt 2 lc rgb \"#ff7f0e\" title \"rho0 g depth below the column's top particle\""
      hydro_note=", with rho0 g depth"
    fi
  fi
  mean=$(awk '{ s += $2; n++ } END { if (n) printf "%.4g", s / n }' "$tmp/line.dat")
  if [ "$npts" -eq 0 ] && [ -z "$interp_plot" ]; then
    echo "plot_run.sh: $line_file has no particles (no particle within dp/2 of the segment) and no interpolated point in the fluid: line plot skipped" >&2
  else
    strip_plot="\"$tmp/line.dat\" using 1:2 with points pt 7 ps 0.6 lc rgb \"#1f77b4\" title \"particles within dp/2 ($npts)\""
    [ "$npts" -eq 0 ] && strip_plot="NaN notitle"
    title="$case_title: pressure along '$line_name', $tlabel\\n$npts particles (mean ${mean:-?} Pa)$interp_note$hydro_note"
    gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set output "$dir/plot_line_$nnnn.png"
set grid
set key outside bottom center horizontal
set xlabel "s along line '$line_name' (m)"
set ylabel "p (Pa)"
set title "$title"
plot $strip_plot$interp_plot$ref_plot
GP
    echo "wrote $dir/plot_line_$nnnn.png: ${title//\\n/ / }"
  fi
fi

# ---------------------------------------------------------------------------------------------
# 2./3. Particles coloured by a field; 3D: the slice |z| < dp.
# slice_of FIELD -> $tmp/fluid.dat "x y value level is_buffer" (fluid and buffer particles),
# $tmp/wall.dat "x y level", and $tmp/levels.dat "level dp_ratio fluid buffer wall" per level
# (dp_ratio = dp of the level / dp of level 0, from the particle masses rho0 dp^D); fails (3) if
# a column is missing.
slice_of() {
  awk -F, -v f="$1" -v dim="$dim" -v dp="${dp:-0}" -v out="$tmp" '
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
              if (!("x" in c) || !("y" in c) || !("kind" in c) || !(f in c)) exit 3
              hz = ("z" in c); hl = ("level" in c); hm = ("mass" in c); next }
    {
      if (hz && dim == 3) { z = $c["z"] + 0; if (dp > 0 && (z < 0 ? -z : z) >= dp) next }
      lev = hl ? $c["level"] + 0 : 0
      if (!(lev in mass) && hm) mass[lev] = $c["mass"] + 0
      seen[lev] = 1
      if ($c["kind"] == "wall") { print $c["x"], $c["y"], lev > (out "/wall.dat"); nw[lev]++ }
      else {
        b = ($c["kind"] == "buffer") ? 1 : 0
        print $c["x"], $c["y"], $c[f], lev, b > (out "/fluid.dat")
        if (b) nb[lev]++; else nf[lev]++
      }
    }
    END {
      for (l in seen) {
        r = (hm && (0 in mass) && mass[0] > 0) ? (mass[l] / mass[0]) ^ (1 / dim) : 0.5 ^ l
        printf "%d %.6g %d %d %d\n", l, r, nf[l], nb[l], nw[l] > (out "/levels.dat")
      }
    }' "$parts"
}

# Colour range: 1st to 99th percentile of the field over fluid particles, so that a few spikes at
# the surface do not wash out the interior (the title says so). FIELD_MIN/MAX fix it instead.
plot_field() {  # FIELD LABEL FILE CBMIN CBMAX (CBMIN/CBMAX empty = percentiles)
  local field=$1 label=$2 png=$3 lo=$4 hi=$5
  rm -f "$tmp/fluid.dat" "$tmp/wall.dat" "$tmp/levels.dat"
  if ! slice_of "$field"; then return 3; fi
  touch "$tmp/fluid.dat" "$tmp/wall.dat"
  sort -n -o "$tmp/levels.dat" "$tmp/levels.dat"
  local n
  n=$(wc -l < "$tmp/fluid.dat")
  [ "$n" -gt 0 ] || { echo "plot_run.sh: no fluid particles to plot in $parts" >&2; return 0; }
  local range_note=""
  if [ -z "$lo" ]; then
    read -r lo hi < <(awk '$5 == 0 { print $3 }' "$tmp/fluid.dat" | sort -g |
      awk '{ v[NR] = $1 } END { a = int(0.01 * (NR - 1)) + 1; b = int(0.99 * (NR - 1)) + 1
                                if (v[a] == v[b]) { v[a] -= 0.5; v[b] += 0.5 }
                                print v[a], v[b] }')
    range_note=", colours 1-99th percentile of the fluid"
  fi
  local stats
  stats=$(awk '$5 == 0 { if (!k++) mn = mx = $3; if ($3 < mn) mn = $3; if ($3 > mx) mx = $3 }
               END { printf "fluid min %.4g, max %.4g", mn, mx }' "$tmp/fluid.dat")
  # Canvas height from the aspect of the data (900 px wide), point size from the particle spacing:
  # about one dp of level 0 wide on a plot of the data extent; finer levels in proportion.
  local ps height
  read -r ps height < <(awk -v dp="${dp:-0}" 'NR == 1 { x0 = x1 = $1; y0 = y1 = $2 }
         { if ($1 < x0) x0 = $1; if ($1 > x1) x1 = $1; if ($2 < y0) y0 = $2; if ($2 > y1) y1 = $2 }
         END { e = x1 - x0; if (y1 - y0 > e) e = y1 - y0
               if (dp <= 0 || e <= 0) { n = sqrt(NR); px = 760 / (n > 1 ? n : 1) } else px = 760 * dp / (e + 2 * dp)
               ps = px / 7.5; if (ps < 0.12) ps = 0.12; if (ps > 2.5) ps = 2.5
               a = (x1 > x0) ? (y1 - y0) / (x1 - x0) : 1; hgt = int(260 + 650 * a)
               if (hgt < 450) hgt = 450; if (hgt > 1100) hgt = 1100; printf "%.3f %d\n", ps, hgt }' \
         "$tmp/fluid.dat" "$tmp/wall.dat")
  local where="all particles"
  if [ "$dim" = 3 ]; then
    if [ -n "$dp" ]; then where="slice |z| < dp = $dp m"; else where="all particles projected on x-y (no dp)"; fi
  fi
  # One clause per level and kind: walls grey, fluid coloured, buffer coloured and ringed in black,
  # each level's dots in proportion to its dp.
  local plots="" lev r nf nb nw psl ring drawn="" tf=0 tb=0 tw=0 per_level="" nlev=0
  while read -r lev r nf nb nw; do
    psl=$(awk -v p="$ps" -v r="$r" 'BEGIN { q = p * r; printf "%.3f", (q < 0.08 ? 0.08 : q) }')
    ring=$(awk -v p="$psl" 'BEGIN { printf "%.3f", 1.25 * p + 0.1 }')
    [ "$nw" -gt 0 ] && plots="$plots\"$tmp/wall.dat\" using 1:(\$3 == $lev ? \$2 : 1/0) with points pt 7 ps $psl lc rgb \"#a0a0a0\" title \"wall L$lev ($nw)\", "
    [ "$nf" -gt 0 ] && plots="$plots\"$tmp/fluid.dat\" using 1:(\$4 == $lev && \$5 == 0 ? \$2 : 1/0):3 with points pt 7 ps $psl lc palette title \"fluid L$lev ($nf)\", "
    if [ "$nb" -gt 0 ]; then
      plots="$plots\"$tmp/fluid.dat\" using 1:(\$4 == $lev && \$5 == 1 ? \$2 : 1/0):3 with points pt 7 ps $psl lc palette notitle, "
      plots="$plots\"$tmp/fluid.dat\" using 1:(\$4 == $lev && \$5 == 1 ? \$2 : 1/0) with points pt 6 ps $ring lw 0.5 lc rgb \"black\" title \"buffer L$lev ($nb, ringed)\", "
    fi
    tf=$((tf + nf)); tb=$((tb + nb)); tw=$((tw + nw))
    per_level="${per_level:+$per_level + }L$lev $nf"
    nlev=$((nlev + 1))
  done < "$tmp/levels.dat"
  drawn="$tf fluid"
  [ "$nlev" -gt 1 ] && drawn="$drawn ($per_level)"
  [ "$tb" -gt 0 ] && drawn="$drawn, $tb buffer"
  [ "$tw" -gt 0 ] && drawn="$drawn, $tw wall"
  local title="$case_title: $label, $tlabel\\n$where drawn: $drawn; $stats$range_note"
  gnuplot <<GP
set terminal pngcairo size 900,$height noenhanced
set output "$png"
set size ratio -1
set grid
set key outside bottom center horizontal
set xlabel "x (m)"
set ylabel "y (m)"
set cblabel "$label"
set cbrange [$lo:$hi]
set palette defined (0 "#30123b", 0.15 "#4662d7", 0.35 "#1ae4b6", 0.55 "#a2fc3c", 0.75 "#faba39", 0.9 "#e4460a", 1 "#7a0403")
set title "$title"
plot ${plots%, }
GP
  echo "wrote $png: ${title//\\n/ / }"
}

plot_field p "p (Pa)" "$dir/plot_pressure_$nnnn.png" "${P_MIN:-}" "${P_MAX:-}" \
  || die "$parts: header lacks one of kind, x, y, p"
if ! plot_field lambda "lambda (min eigenvalue of M)" "$dir/plot_lambda_$nnnn.png" \
     "${LAMBDA_MIN:-0}" "${LAMBDA_MAX:-1.1}"; then
  echo "plot_run.sh: $parts has no lambda column (surface tension off?): lambda plot skipped" >&2
fi

# ---------------------------------------------------------------------------------------------
# 4. max_speed against t from series.csv.
series="$dir/series.csv"
if [ ! -f "$series" ]; then
  echo "plot_run.sh: $series not found: max_speed plot skipped" >&2
else
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
                     ct = ("t" in c) ? c["t"] : 1; cv = ("max_speed" in c) ? c["max_speed"] : 8; next }
           { print $ct, $cv }' "$series" > "$tmp/series.dat"
  if [ "$(wc -l < "$tmp/series.dat")" -lt 1 ]; then
    echo "plot_run.sh: $series has no rows: max_speed plot skipped" >&2
  else
    # Only a drop without gravity or walls starts and should stay at rest.
    speed_note=""
    if is_pos "$sigma" && ! is_pos "$g" && [ "$n_walls" -eq 0 ]; then
      speed_note=" (for a drop at rest: the parasitic currents)"
    fi
    title="$case_title: largest fluid particle speed$speed_note"
    gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set output "$dir/plot_max_speed.png"
set grid
set key top right
set xlabel "t (s)"
set ylabel "max speed over fluid particles (m/s)"
set title "$title"
plot "$tmp/series.dat" using 1:2 with linespoints pt 7 ps 0.5 lw 2 lc rgb "#1f77b4" title "max_speed"
GP
    echo "wrote $dir/plot_max_speed.png: $title"
  fi
fi

# ---------------------------------------------------------------------------------------------
# 5. The Laplace error against t, when series.csv has it (analysis.laplace_pressure with a line):
# on the particle strip, and on the interpolated line when the columns are there.
if [ -f "$series" ] && head -1 "$series" | grep -q "laplace_rmse"; then
  # An RMSE of round-off size (a start set at the Laplace pressure) is left out of the log axis,
  # where it would squeeze the rest of the curve into the top decade.
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; ci = ("laplace_interp_rmse" in c); next }
           { r = $c["laplace_rmse"]; if (r + 0 < 1e-9) r = "NaN"
             ri = ci ? $c["laplace_interp_rmse"] : "NaN"; if (ri + 0 < 1e-9) ri = "NaN"
             print $c["t"], r, $c["laplace_mean_interior"], ri, (ci ? $c["laplace_interp_mean_interior"] : "NaN") }' "$series" \
    > "$tmp/laplace.dat"
  interp_curves=""
  if head -1 "$series" | grep -q "laplace_interp_rmse"; then
    interp_curves=", \"\" using 1:4 with linespoints pt 5 ps 0.5 lw 2 lc rgb \"#2ca02c\" title \"laplace_interp_rmse\", \"\" using 1:5 axes x1y2 with lines lw 1 dt 2 lc rgb \"#ff7f0e\" title \"laplace_interp_mean_interior (right)\""
  fi
  title="$case_title: pressure error on the first line against Laplace ${laplace:+$laplace Pa}\\nparticle strip (laplace_*) and interpolated points (laplace_interp_*)"
  gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set output "$dir/plot_laplace_rmse.png"
set grid
set key outside bottom center horizontal
set xlabel "t (s)"
set ylabel "RMSE along the line (Pa)"
set y2label "mean interior pressure (Pa)"
set ytics nomirror
set y2tics
set logscale y
set title "$title"
plot "$tmp/laplace.dat" using 1:2 with linespoints pt 7 ps 0.5 lw 2 lc rgb "#1f77b4" title "laplace_rmse", \
     "" using 1:3 axes x1y2 with lines lw 1 lc rgb "#d62728" title "laplace_mean_interior (right)"$interp_curves
GP
  echo "wrote $dir/plot_laplace_rmse.png: ${title//\\n/ / }"
fi
