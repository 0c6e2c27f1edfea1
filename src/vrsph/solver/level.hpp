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
};

}  // namespace vrsph
