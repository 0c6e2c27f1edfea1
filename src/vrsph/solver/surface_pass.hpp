// Neighbour passes of the surface-tension model (physics/surface_tension.hpp) and the sums that
// particle shifting needs (physics/shifting.hpp). Gather passes through candidate blocks and the
// vector sweep of exec/: each fluid particle writes only its own entries, so results do not
// depend on the thread count. Wall particles get zeros.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "vrsph/core/mat.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/columns.hpp"
#include "vrsph/solver/cross_level.hpp"
#include "vrsph/solver/normal_bound.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/pass1_terms.hpp"

namespace vrsph {

template <int D>
struct SurfaceFields {
  std::vector<double> lambda;   // smallest eigenvalue of M_i
  std::vector<Mat<D>> l_corr;   // L_i = M_i^-1 (or I)
  std::vector<Vec<D>> grad_c;   // sum_j V_j grad_i W_ij
  std::vector<double> div_r;    // -sum_j V_j r_ij . grad_i W_ij
  std::vector<double> shepard;  // sum_j V_j W_ij, self included
  // G_i = sum_j V_j |grad_i W_ij|, which bounds pass 2's sum; pass 1 sums it only with surface
  // tension on (sums_grad_w), and leaves it empty otherwise. A level without particles has it
  // empty either way, so the flag, not the array's size, says whether G is summed.
  std::vector<double> grad_w;
  bool sums_grad_w = false;
  std::vector<Vec<D>> normal;     // unit outward normal, or 0
  std::vector<double> curvature;  // kappa_i
  std::vector<Vec<D>> acc_st;     // surface-tension acceleration
  // The capillary refresh's hold (sim/surface_refresh.hpp): the acceleration of the last refresh
  // and its rate of change since the refresh before, per particle; between refreshes acc_st is
  // extrapolated from them.
  std::vector<Vec<D>> acc_ref, acc_rate;

  // The columns the passes read when called without a level's packed columns (filled by the
  // four-argument surface_sums), and lambda (pass 2) and the normal (pass 3) as columns for the
  // passes' sweeps, padded as the packed state (particles/run_columns.hpp).
  LevelColumns<D> own;
  std::vector<double> lambda_col;
  std::array<std::vector<double>, D> normal_col;
  // The same in float for the mixed precision (core/precision.hpp); pass 1 reads the level's
  // float volumes.
  std::vector<float> lambda_f;
  std::array<std::vector<float>, D> normal_f;
  // Pass 2's scratch: lambda's range per cell and row of a block (solver/normal_bound.hpp).
  BlockRanges lambda_ranges;

  // Surface fields across levels (solver/cross_level.hpp): the other levels' fluid as further
  // neighbours (empty: none), and which particles found any in pass 1 (passes 2 and 3 look for
  // them only there). h_wide[i] > 0 (empty: none): particle i sums with a kernel of that h over
  // `wide` (its own level, then the others) instead of its blocks.
  std::vector<CrossSource<D>> cross, wide;
  std::vector<std::uint8_t> cross_hit;
  std::vector<double> h_wide;

  // Sizes the arrays pass 1 writes, and sizes the others without touching their values (a pass 1
  // alone leaves what passes 2 and 3 wrote).
  void resize(std::size_t n);

  // Held fields. With the capillary refresh (sim/surface_refresh.hpp) passes 2 and 3 do not run
  // at every force evaluation, and the capillary acceleration they wrote must follow its particle
  // until the next refresh: while `held`, the level's sorts, compactions and appends call these.
  // Once a refresh has set acc_ref, acc_st is formed anew from it at every evaluation and need
  // not follow the sorts. lambda, the normal and the curvature follow only while `held_geometry`
  // (local time stepping: a level's buffers read the other levels' fields between their passes).
  bool held = false;
  bool held_geometry = false;
  // Set by surface_sums_for_shifting and surface_sums_in_forces: what of pass 1 the level's next
  // force pass sums for the fluid particles (it clears it).
  Pass1InForces in_forces = Pass1InForces::none;
  // Where pass 1 writes its fields (solver/pass1_terms.hpp), for the whole pass or for shifting's
  // sums alone; G only where it is summed (grad_w sized).
  Pass1Out<D> pass1_out(bool whole) {
    Pass1Out<D> o{grad_c.data(), div_r.data(),   lambda.data(),
                  l_corr.data(), shepard.data(), sums_grad_w ? grad_w.data() : nullptr};
    if (whole) o.terms = kPass1Terms<D, false> + (sums_grad_w ? 1 : 0);
    return o;
  }
  // Reorders the held arrays after a sort of the level (CellGrid::carry).
  template <class Grid>
  void carry(Grid& grid) {
    if (!held) return;
    if (held_geometry) {
      grid.carry(lambda);
      grid.carry(normal);
      grid.carry(curvature);
    }
    if (acc_ref.empty()) grid.carry(acc_st);
    grid.carry(acc_ref);
    grid.carry(acc_rate);
  }
  // Keeps the entries with keep[i] != 0 (ParticleSet::compact), then sizes to n (new particles
  // get zeros: a created particle holds no capillary acceleration until the next refresh).
  void compact_held(const std::vector<std::uint8_t>& keep);
  void fit_held(std::size_t n);
  // After a refresh (pass 3 wrote acc_st): acc_rate = (acc_st - acc_ref) / since_last where both
  // are non-zero (0 where either is, and everywhere for since_last <= 0 or NaN: no refresh
  // before), then acc_ref = acc_st.
  void take_refresh(double since_last);
  // Between refreshes: acc_st = acc_ref + tau acc_rate, tau the time since the last refresh.
  void extrapolate(double tau);
};

// Pass 1: M_i (and lambda_i, L_i), grad C_i, div r_i and the Shepard sum, over fluid and wall
// neighbours (walls give support, so a wall is not mistaken for a free surface). `cols`: the
// level's columns packed from ps (positions and volumes are read), passed to passes 2 and 3 too.
template <int D>
void surface_sums(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  const LevelColumns<D>& cols, SurfaceFields<D>& sf);
// Pass 1 for shifting alone (an evaluation without a capillary refresh): the sums of the particles
// that are not fluid (buffer particles shift too; walls get neutral values), and sets
// sf.in_forces: the fluid particles' grad C and div r are then summed by the level's next force
// pass (solver/forces.hpp), which visits the same neighbours at the same positions, and their
// lambda, L, Shepard sum and G keep the values of the last full pass 1 (read only by passes 2 and
// 3, which run after a full pass 1). Returns whether it did so: with fields summed across levels
// (sf.cross, sf.h_wide) it runs the full pass 1 instead.
template <int D>
bool surface_sums_for_shifting(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                               const CellGrid<D>& grid, const LevelColumns<D>& cols,
                               SurfaceFields<D>& sf);
// Pass 1 with the fluid particles' rows left to the level's next force pass (all of pass 1 in the
// same sweep as the pair forces, Pass1InForces::full): a capillary refresh whose passes 2 and 3
// run after the force pass. Where the force pass cannot (fields across levels, or 3D, whose 17
// sums exceed a sweep's 12) it runs the whole pass 1 and returns false.
template <int D>
bool surface_sums_in_forces(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                            const CellGrid<D>& grid, const LevelColumns<D>& cols,
                            SurfaceFields<D>& sf);
// The same, packing positions and volumes into sf.own.
template <int D>
void surface_sums(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  SurfaceFields<D>& sf);

// Pass 2: normals from the corrected gradient of lambda (fluid neighbours). Needs surface_sums.
template <int D>
void surface_normals(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                     const LevelColumns<D>& cols, SurfaceFields<D>& sf);

// Pass 3: filtered curvature and the CSF acceleration from the normals in sf (fluid neighbours).
// Tests may impose sf.normal before calling it.
template <int D>
void surface_curvature_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                             const CellGrid<D>& grid, const LevelColumns<D>& cols,
                             SurfaceFields<D>& sf);

// Passes 2 and 3 together.
template <int D>
void surface_tension_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                           const CellGrid<D>& grid, const LevelColumns<D>& cols,
                           SurfaceFields<D>& sf);

// Passes 2 and 3 on the columns sf.own of the four-argument surface_sums (tests).
template <int D>
void surface_normals(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                     SurfaceFields<D>& sf) {
  surface_normals(prm, ps, grid, sf.own, sf);
}
template <int D>
void surface_curvature_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                             const CellGrid<D>& grid, SurfaceFields<D>& sf) {
  surface_curvature_force(prm, ps, grid, sf.own, sf);
}
template <int D>
void surface_tension_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                           const CellGrid<D>& grid, SurfaceFields<D>& sf) {
  surface_tension_force(prm, ps, grid, sf.own, sf);
}

}  // namespace vrsph
