// Neighbour passes of the surface-tension model (physics/surface_tension.hpp) and the sums that
// particle shifting needs (physics/shifting.hpp). Gather loops: each fluid particle writes only
// its own entries, so results do not depend on the thread count. Wall particles get zeros.
#pragma once

#include <array>
#include <vector>

#include "vrsph/core/mat.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/params.hpp"

namespace vrsph {

template <int D>
struct SurfaceFields {
  std::vector<double> lambda;    // smallest eigenvalue of M_i
  std::vector<Mat<D>> l_corr;    // L_i = M_i^-1 (or I)
  std::vector<Vec<D>> grad_c;    // sum_j V_j grad_i W_ij
  std::vector<double> div_r;     // -sum_j V_j r_ij . grad_i W_ij
  std::vector<double> shepard;   // sum_j V_j W_ij, self included
  std::vector<Vec<D>> normal;    // unit outward normal, or 0
  std::vector<double> curvature; // kappa_i
  std::vector<Vec<D>> acc_st;    // surface-tension acceleration

  // Positions and volumes as separate arrays, for the vectorised neighbour loops.
  std::array<std::vector<double>, D> x;
  std::vector<double> vol;

  void resize(std::size_t n);
  void pack(const ParticleSet<D>& ps);
};

// Pass 1: M_i (and lambda_i, L_i), grad C_i, div r_i and the Shepard sum, over fluid and wall
// neighbours (walls give support, so a wall is not mistaken for a free surface).
template <int D>
void surface_sums(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  SurfaceFields<D>& sf);

// Pass 2: normals from the corrected gradient of lambda (fluid neighbours). Needs surface_sums.
template <int D>
void surface_normals(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                     SurfaceFields<D>& sf);

// Pass 3: filtered curvature and the CSF acceleration from the normals in sf (fluid neighbours).
// Tests may impose sf.normal before calling it.
template <int D>
void surface_curvature_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                             const CellGrid<D>& grid, SurfaceFields<D>& sf);

// Passes 2 and 3 together.
template <int D>
void surface_tension_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                           const CellGrid<D>& grid, SurfaceFields<D>& sf);

}  // namespace vrsph
