// One resolution level: a complete particle system with its own dp, h, mass, cell grid and
// particles (fluid, wall and buffer), and the part of space it owns. Physics passes run per
// level and never look at another level; vres/coupling.hpp exchanges data between levels.
#pragma once

#include <vector>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/surface_pass.hpp"
#include "vrsph/vres/region.hpp"

namespace vrsph {

template <int D>
struct Level {
  SolverParams<D> prm;
  ParticleSet<D> ps;
  CellGrid<D> grid;
  LevelColumns<D> cols;  // the state packed for the neighbour passes of one force evaluation
  SurfaceFields<D> sf;
  LevelRegion<D> region;                // single-resolution runs: level 0 owns everything
  std::vector<MassPoint<D>> mass_points;  // where particles of this level are created
};

}  // namespace vrsph
