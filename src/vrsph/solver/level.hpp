// One resolution level: a complete particle system with its own dp, h, mass, cell grid and
// particles (fluid, wall and buffer). The stepper (solver/stepper.hpp) advances one level and never
// looks at another; what ties levels together (regions, buffers, mass points) lives in vres/.
#pragma once

#include <vector>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/columns.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/surface_pass.hpp"

namespace vrsph {

template <int D>
struct Level {
  SolverParams<D> prm;
  ParticleSet<D> ps;
  CellGrid<D> grid;
  LevelColumns<D> cols;  // the state packed for the neighbour passes of one force evaluation
  SurfaceFields<D> sf;
  // Buffer particles only: the direction along which the corrector drops their shifting (the
  // normal of the nearest interface face), set before each corrector by whoever owns the buffers.
  // Empty when the level has no buffer.
  std::vector<Vec<D>> buffer_shift_normal;
  // A uniform acceleration of every fluid particle from the last force evaluation, beyond ps.acc:
  // the net-force corrections of vres/momentum.hpp (zero_net_force, vres_conserve_momentum with
  // one dt), which the integrator adds (fluid_acceleration) instead of a pass that adds it to
  // ps.acc. Zero after each force pass until a correction sets it.
  Vec<D> fluid_acc_uniform{};
  // Fluid particles only: the acceleration of the last force pass from the level's fluid and
  // buffer neighbours (compute_forces_packed's pair_acc), where vres_conserve_momentum asks for
  // it (vres/momentum.hpp); empty elsewhere.
  std::vector<Vec<D>> pair_acc;
};

// The acceleration the integrator gives fluid particle i (gravity excluded): ps.acc[i] plus the
// level's uniform correction where there is one (the same bits as adding it to ps.acc first).
template <int D>
inline Vec<D> fluid_acceleration(const Level<D>& L, std::size_t i, bool uniform) {
  return uniform ? L.ps.acc[i] + L.fluid_acc_uniform : L.ps.acc[i];
}

}  // namespace vrsph
