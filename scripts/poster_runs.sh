#!/usr/bin/env bash
# The runs of the poster's tables (Lee et al., single-phase surface tension across resolution
# levels): the drop cases with the models as published, or with vrsph's own options, at the
# poster's settings (docs/validation.md, "The poster's tables").
#   scripts/poster_runs.sh [--binary PATH] [--threads N] [--model published|vrsph] ROW OUT_DIR [--set K=V ...]
# ROW:
#   sr_lattice, sr_rings, sr_rings_on_radius  droplet_2d (R = 2 mm, dp 5e-5) started at the Laplace
#       pressure p0 = 36.4 Pa, to 1 s, with the fill of that name (rings_on_radius: the outer
#       particles on R, as the poster lays them)
#   vr_circle_4h, vr_circle_2h                droplet_vr_2d (dp 1e-4 / 5e-5), p0 = 36.4 Pa, to 0.5 s
#   vr_square_4h, vr_square_2h                square_droplet_vr_2d, from rest at p = 0, to 0.5 s
# --model published (the default): Cen et al. 2024 and Ricci et al. 2024 as published, none of
#   vrsph's options (no surface_offset, curvature_correction, zero_net_force,
#   vres_conserve_momentum, vres_buffer_fill_min, vres_shepard_fill, vres_flux_edge; buffers keep
#   their own level's lambda and normal; shells rounded up to whole dp as DualSPHysics lays them;
#   the VR drops on the lattice, the square's from min), the surface fields refreshed at every
#   step.
#   Without the net-force correction the drop drifts (about 3 mm by 0.6 s on droplet_2d): these
#   rows run in a domain of 6 cm (single resolution) or 1.6 cm (VR) and are measured in the
#   drop's frame with scripts/laplace_centroid.sh.
# --model vrsph: the shipped case's own options (the case file as it is), with the same start,
#   end time and buffer width.
# Extra --set arguments go to vrsph after these (the last one given wins). The run writes csv
# only; read it with scripts/laplace_window.sh OUT_DIR 0.4 0.5, or for a drop that drifts
# scripts/laplace_centroid.sh OUT_DIR 0.4 0.5.
set -euo pipefail

usage() {
  echo "usage: poster_runs.sh [--binary PATH] [--threads N] [--model published|vrsph] ROW OUT_DIR [--set K=V ...]" >&2
}
die() { echo "poster_runs.sh: $*" >&2; exit 2; }

here="$(cd "$(dirname "$0")/.." && pwd)"
binary="$here/build/release/vrsph"
threads=1
model=published
while [ $# -gt 0 ]; do
  case "$1" in
    --binary) binary="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --model) model="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || { usage; exit 2; }
row="$1"; out="$2"; shift 2
[ -x "$binary" ] || die "--binary $binary: not an executable (build first: cmake --build --preset release)"
case "$model" in published|vrsph) ;; *) die "--model $model: must be published or vrsph" ;; esac

sets=(--set 'output.formats=["csv"]')
published_st=(--set 'numerics.surface_tension.refresh="every_step"'
  --set numerics.surface_tension.surface_offset=false
  --set numerics.surface_tension.curvature_correction=false
  --set numerics.surface_tension.zero_net_force=false)
published_vr=("${published_st[@]}" --set numerics.vres_conserve_momentum=false
  --set numerics.vres_buffer_fill_min=0 --set 'numerics.vres_buffer_surface="own"'
  --set numerics.vres_shepard_fill=0 --set numerics.vres_flux_edge=0
  --set 'refinement.0.buffer_rounding="whole_dp"' --set 'fluid_block.0.fill="lattice"')

case "$row" in
  sr_lattice|sr_rings|sr_rings_on_radius)
    case_file=cases/droplet_2d.toml
    sets+=(--set fluid_block.0.pressure=36.4 --set case.end_time=1.0
      --set "fluid_block.0.fill=\"${row#sr_}\"")
    [ "$model" = published ] && sets+=("${published_st[@]}" --set 'domain.min=[-0.03,-0.03]'
      --set 'domain.max=[0.03,0.03]') ;;
  vr_circle_4h|vr_circle_2h|vr_square_4h|vr_square_2h)
    width="${row##*_}"; width="${width%h}.0"
    sets+=(--set "refinement.0.buffer_width=$width" --set case.end_time=0.5)
    if [ "${row#vr_circle}" != "$row" ]; then
      case_file=cases/droplet_vr_2d.toml
      sets+=(--set fluid_block.0.pressure=36.4)
    else
      case_file=cases/square_droplet_vr_2d.toml
    fi
    [ "$model" = published ] && sets+=("${published_vr[@]}" --set 'domain.min=[-0.008,-0.008]'
      --set 'domain.max=[0.008,0.008]') ;;
  *) die "ROW $row: not one of sr_lattice sr_rings sr_rings_on_radius vr_circle_4h vr_circle_2h vr_square_4h vr_square_2h" ;;
esac

cmd=("$binary" run "$here/$case_file" --out "$out" --threads "$threads" --quiet "${sets[@]}" "$@")
echo "${cmd[*]}"
exec "${cmd[@]}"
