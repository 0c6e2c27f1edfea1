// Building the levels of a simulation from a validated case: the parameters that depend on a
// level's dp, its particles (fluid, buffer and walls cut to the level's region) and the default
// domain.
#pragma once

#include <cstdint>

#include "vrsph/particles/particles.hpp"
#include "vrsph/setup/case_spec.hpp"
#include "vrsph/setup/geometry.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/wall_reaction.hpp"
#include "vrsph/vres/levels.hpp"

namespace vrsph {

// Default domain: bounding box of all particles grown by the margin of grow_default_domain
// (setup/block_extent.hpp): at least the fluid's largest extent (fluid_extent) on each side, so
// a free body can deform, plus room for splashes against gravity. cell_origin: where the cell
// grid is laid from (the domain's min under the earlier, smaller margin).
template <int D>
void default_domain(const ParticleSet<D>& ps, const Vec<D>& up, double h, double fluid_extent,
                    Vec<D>& lo, Vec<D>& hi, Vec<D>& cell_origin);

// Parameters of one level: everything that depends on its dp; c0 is common to all levels.
template <int D>
SolverParams<D> level_params(const CaseSpec& spec, double dp, double c0);

// The case filled at spacing dp (every block and wall, the whole domain).
template <int D>
InitialSet<D> level_fill(const CaseSpec& spec, double dp);

// The particles of one level from its fill (level_fill at the level's dp), ids from first_id
// (see level_setup.cpp). wall_ids (when given) gets the ids of each wall block's particles.
template <int D>
ParticleSet<D> level_particles(const CaseSpec& spec, const LevelLayout<D>& lay,
                               const SolverParams<D>& prm, std::uint64_t first_id,
                               InitialSet<D> fill, std::vector<IdRange>* wall_ids = nullptr);

}  // namespace vrsph
