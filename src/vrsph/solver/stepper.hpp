// The stepper of one level: the stages of one symplectic step (docs/physics.md section 9) of a
// level at a dt it is given. It knows nothing of other levels: variable resolution calls its stages
// in order and exchanges buffer data between them (vres/level_coupling.hpp), and the scheduler
// (sim/simulation.cpp) decides the dt.
#pragma once

#include <cmath>
#include <cstdint>

#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/level.hpp"
#include "vrsph/solver/timestep.hpp"

namespace vrsph {

// Packs the level's state into its columns: first stage of a force evaluation.
template <int D>
void pack_level(Level<D>& L);

// The surface passes on the packed columns: 1 (correction matrix, lambda, grad C, div r, Shepard),
// 2 (normals), 3 (curvature and capillary acceleration).
template <int D>
void surface_pass_sums(Level<D>& L);
// Pass 1 for shifting alone (surface_sums_for_shifting): the level's next level_forces sums the
// fluid particles' grad C and div r.
template <int D>
void surface_pass_shifting_sums(Level<D>& L);
// Pass 1 with the fluid rows left to the level's next level_forces, which sums all of it
// (surface_sums_in_forces); false where it cannot, having run the whole pass 1.
template <int D>
bool surface_pass_sums_in_forces(Level<D>& L);
template <int D>
void surface_pass_normals(Level<D>& L);
template <int D>
void surface_pass_curvature(Level<D>& L);

// Pair forces on the packed columns, with the capillary acceleration added when `capillary`;
// with `pair_acc`, L.pair_acc as compute_forces_packed gives it (vres_conserve_momentum); with
// the fluid particles' pass-1 sums after surface_pass_shifting_sums or surface_pass_sums_in_forces.
template <int D>
ForceStats level_forces(Level<D>& L, bool capillary, bool pair_acc);
// The capillary acceleration of passes 2 and 3 run after the force pass (a refresh whose pass 1
// the force pass summed) added to the fluid's, and s.max_acc taken anew over the sums: what
// level_forces with `capillary` gives, in two steps.
template <int D>
void add_capillary(Level<D>& L, ForceStats& s);

// Predictor (dt/2) and corrector (dt) of the symplectic scheme.
template <int D>
void predictor(Level<D>& L, double dt);
template <int D>
void corrector(Level<D>& L, double dt);

// v *= factor for the fluid particles of L (physics/start_damping.hpp); nothing when factor is 1.
template <int D>
void damp_fluid_velocities(Level<D>& L, double factor);

// The dt this level allows after a force evaluation with statistics s (its own speeds).
template <int D>
DtChoice level_dt(const Level<D>& L, const ForceStats& s, double c0);

// The dt a level at rest allows (first step): acoustic, viscous and capillary limits.
template <int D>
DtChoice level_dt_at_start(const Level<D>& L, double c0);

// Whether particle i's position, velocity and density are all finite.
template <int D>
inline bool state_is_finite(const ParticleSet<D>& ps, std::size_t i) {
  return std::isfinite(ps.rho[i]) && std::isfinite(norm2(ps.vel[i])) &&
         std::isfinite(norm2(ps.pos[i]));
}

// The lowest index of a non-wall particle with a non-finite state or a density outside
// [0.5, 2] rho0, or ps.size() when there is none.
template <int D>
std::size_t first_unstable(const Level<D>& L);

}  // namespace vrsph
