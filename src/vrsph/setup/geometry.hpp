// Initial particle sets from the case geometry.
// Fill conventions (documented in the case files):
//  - box fluid blocks: lattice nodes min + k dp (both faces included when the length is a multiple
//    of dp, GenCase style), so [dp, 1] x [dp, 2] at dp = 0.005 holds 200 x 400 particles;
//  - circle / sphere blocks, fill = "lattice": cell centres centre + (k + 1/2) dp inside the
//  radius;
//  - circle, fill = "rings": concentric rings at radii (k + 1/2) dp, round(2 pi r / dp) particles
//  each;
//  - tank walls: `layers` rows of nodes outside the open-top box min..max (bottom on the min face
//  of
//    the vertical axis, sides on the other faces); box walls: a solid box of nodes.
#pragma once

#include <vector>

#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/setup/case_spec.hpp"

namespace vrsph {

template <int D>
struct InitialSet {
  ParticleSet<D> particles;
  double fluid_height = 0.0;  // extent of the fluid along the vertical axis (for c0 = f sqrt(g H))
  std::vector<double> initial_pressure;  // per particle: its fluid block's `pressure` (0: none)
  // Index of the first particle of each [[wall_block]]: block b holds the particles from
  // wall_block_first[b] up to the next block's first (or the end).
  std::vector<std::size_t> wall_block_first;
};

// Positions, velocities and masses; densities are rho0 (see apply_hydrostatic_density).
template <int D>
InitialSet<D> build_particles(const CaseSpec& spec);

// Sets fluid and wall densities to the hydrostatic profile p = rho0 |g| depth, with depth measured
// from the top of the fluid in the same vertical column (walls with no fluid above stay at rho0).
template <int D>
void apply_hydrostatic_density(ParticleSet<D>& ps, const Vec<D>& gravity, double rho0, double dp,
                               const TaitEos& eos);

}  // namespace vrsph
