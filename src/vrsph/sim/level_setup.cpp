#include "vrsph/sim/level_setup.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "vrsph/core/to_vec.hpp"
#include "vrsph/physics/density_diffusion.hpp"
#include "vrsph/setup/block_extent.hpp"
#include "vrsph/setup/geometry.hpp"

namespace vrsph {

// Default domain: the particles' bounding box grown by the margin of grow_default_domain
// (setup/block_extent.hpp).
template <int D>
void default_domain(const ParticleSet<D>& ps, const Vec<D>& up, double h, double fluid_extent,
                    Vec<D>& lo, Vec<D>& hi, Vec<D>& cell_origin) {
  Vec3d a{}, b{}, u{}, o{};
  for (int k = 0; k < D; ++k) {
    a[k] = 1e300;
    b[k] = -1e300;
    u[k] = up[k];
  }
  for (const auto& x : ps.pos) {
    for (int k = 0; k < D; ++k) {
      a[k] = std::min(a[k], x[k]);
      b[k] = std::max(b[k], x[k]);
    }
  }
  grow_default_domain(a, b, D, fluid_extent, u, h, o);
  lo = to_vec<D>(a);
  hi = to_vec<D>(b);
  cell_origin = to_vec<D>(o);
}

// Parameters of one level: everything that depends on its dp; c0 is common to all levels.
template <int D>
SolverParams<D> level_params(const CaseSpec& spec, double dp, double c0) {
  SolverParams<D> prm;
  prm.dp = dp;
  prm.h = spec.h_over_dp * dp;
  prm.eta2 = 0.01 * prm.h * prm.h;
  prm.kernel = WendlandC2<D>(prm.h);
  prm.mass = spec.fluid.density * std::pow(dp, D);
  prm.gravity = to_vec<D>(spec.fluid.gravity);
  const double g = norm(prm.gravity);
  prm.up = g > 0.0 ? prm.gravity * (-1.0 / g) : Vec<D>{};
  prm.eos = TaitEos(spec.fluid.density, spec.eos.gamma, c0);
  prm.cfl = spec.numerics.cfl;
  prm.precision = spec.numerics.precision;
  prm.sigma = spec.fluid.surface_tension;
  const NumericsSpec& n = spec.numerics;
  prm.viscosity = viscosity_level(n.viscosity, spec.fluid.kinematic_viscosity, c0, prm.h);
  prm.density_diffusion = diffusion_level(n.density_diffusion, prm.eos, g, prm.h);
  prm.shifting = shifting_level(n.shifting, prm.h, dp);
  prm.surface_tension = n.surface_tension;
  const DiffusionLevel& dd = prm.density_diffusion;
  const double fourtakas_x = dd.rho0_g_over_b * prm.kernel.support();
  if (dd.model == DiffusionModel::fourtakas && fourtakas_x > fourtakas_series_bound) {
    throw std::invalid_argument(fmt::format(
        "numerics.density_diffusion.model = \"fourtakas\": rho0 g 2h / B = {:.3g} exceeds {:g}: "
        "the speed of sound {:.4g} m/s is too low for this resolution (raise eos.sound_speed)",
        fourtakas_x, fourtakas_series_bound, c0));
  }
  prm.dt_min = 0.05 * prm.h / c0;
  return prm;
}

// The particles of one level: the case filled at the level's dp (with its initial pressures
// and hydrostatic density, computed on the whole fill so columns see the real free surface),
// then cut to the level's region: fluid where it owns the fluid, buffer in its shells, walls
// within 2h of either.
template <int D>
InitialSet<D> level_fill(const CaseSpec& spec, double dp) {
  CaseSpec s = spec;
  s.dp = dp;
  return build_particles<D>(s);
}

namespace {
// The wall block of particle i of a fill (its index in `first`, the blocks' first particles).
std::size_t wall_block_of(const std::vector<std::size_t>& first, std::size_t i) {
  std::size_t b = 0;
  while (b + 1 < first.size() && first[b + 1] <= i) ++b;
  return b;
}
}  // namespace

template <int D>
ParticleSet<D> level_particles(const CaseSpec& spec, const LevelLayout<D>& lay,
                               const SolverParams<D>& prm, std::uint64_t first_id,
                               InitialSet<D> init, std::vector<IdRange>* wall_ids) {
  ParticleSet<D>& all = init.particles;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (init.initial_pressure[i] != 0.0) all.rho[i] = prm.eos.density(init.initial_pressure[i]);
  }
  const double g = norm(prm.gravity);
  if (spec.numerics.hydrostatic_initial_density && g > 0.0) {
    apply_hydrostatic_density<D>(all, prm.gravity, spec.fluid.density, lay.dp, prm.eos);
  }
  // The level's particles are cut from the fill in place (ids and kinds set, the rest compacted
  // away), so set-up never holds two copies of the particles.
  std::vector<IdRange> ranges(init.wall_block_first.size());
  std::vector<std::uint8_t> keep(all.size(), 0);
  std::uint64_t id = first_id;
  for (std::size_t i = 0; i < all.size(); ++i) {
    Kind k = all.kind[i];
    if (k == Kind::wall) {
      if (!lay.region.covers(all.pos[i], prm.kernel.support())) continue;
      // A block's kept walls get consecutive ids: the fill lists blocks one after the other.
      IdRange& r = ranges[wall_block_of(init.wall_block_first, i)];
      if (r.end == r.first) r.first = id;
      r.end = id + 1;
    } else {
      const Zone z = lay.region.classify(all.pos[i]).zone;
      if (z == Zone::outside) continue;
      if (z == Zone::buffer) k = Kind::buffer;
    }
    keep[i] = 1;
    all.kind[i] = k;
    all.id[i] = id++;
  }
  all.compact(keep);
  all.shrink_to_fit();  // a refined level keeps a small part of its fill
  if (wall_ids != nullptr) *wall_ids = std::move(ranges);
  return std::move(all);
}

template void default_domain<2>(const ParticleSet<2>&, const Vec<2>&, double, double, Vec<2>&,
                                Vec<2>&, Vec<2>&);
template void default_domain<3>(const ParticleSet<3>&, const Vec<3>&, double, double, Vec<3>&,
                                Vec<3>&, Vec<3>&);
template SolverParams<2> level_params<2>(const CaseSpec&, double, double);
template SolverParams<3> level_params<3>(const CaseSpec&, double, double);
template InitialSet<2> level_fill<2>(const CaseSpec&, double);
template InitialSet<3> level_fill<3>(const CaseSpec&, double);
template ParticleSet<2> level_particles<2>(const CaseSpec&, const LevelLayout<2>&,
                                           const SolverParams<2>&, std::uint64_t, InitialSet<2>,
                                           std::vector<IdRange>*);
template ParticleSet<3> level_particles<3>(const CaseSpec&, const LevelLayout<3>&,
                                           const SolverParams<3>&, std::uint64_t, InitialSet<3>,
                                           std::vector<IdRange>*);

}  // namespace vrsph
