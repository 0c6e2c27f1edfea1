// The force pass: one gather pass over particles that evaluates, for every fluid particle, the
// momentum and continuity right-hand sides (pressure, viscosity, density diffusion), and for every
// wall particle its continuity equation (fluid neighbours only; Crespo et al. 2007 dynamic
// boundary). Each particle writes only its own outputs: no atomics, the same result for any thread
// count. The pair maths are the functions of physics/; model choices are template parameters
// resolved once per call (forces.cpp).
#pragma once

#include <algorithm>
#include <cstdint>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/columns.hpp"
#include "vrsph/solver/params.hpp"

namespace vrsph {

struct ForceStats {
  double max_visc_dt = -1e300;  // max over pairs of v_ij . r_ij / (r^2 + eta^2)
  double max_acc = 0.0;         // max |a| over fluid particles (gravity excluded)
  std::uint64_t pairs = 0;      // pairs within 2h evaluated (i != j)

  // Combines the statistics of another pass (another stage, level or thread): maxima and the
  // pair sum, so the result does not depend on the order.
  void merge(const ForceStats& o) {
    max_visc_dt = std::max(max_visc_dt, o.max_visc_dt);
    max_acc = std::max(max_acc, o.max_acc);
    pairs += o.pairs;
  }
};

// Buffers a force pass reuses from call to call (no allocation once sizes settle).
template <int D>
using ForceWorkspace = LevelColumns<D>;

// Where a force pass also writes particle shifting's sums of its fluid particles
// (physics/shifting.hpp): grad C_i = sum_j V_j grad_i W_ij and div r_i = -sum_j V_j r_ij . grad_i
// W_ij over fluid and wall neighbours, as surface pass 1 sums them (solver/surface_pass.hpp), in
// the same order over the same candidates. One sweep then serves both on the evaluations where
// pass 1 runs for shifting alone (surface_sums_for_shifting).
template <int D>
struct ShiftingSums {
  Vec<D>* grad_c = nullptr;
  double* div_r = nullptr;
};

// ps.acc and ps.drho for every particle (acc = 0 on walls) from the columns `cols`, packed from
// ps (LevelColumns::pack). extra_acc (null: none) is a per-particle acceleration added to the
// fluid's, e.g. surface tension; it counts in ForceStats::max_acc.
// buffer_reaction: buffer particles get the acceleration their level's fluid and buffer
// neighbours exert on them (vres/momentum.hpp measures the coupling's net force from it);
// otherwise their acc is 0. shift (null: none): the fluid particles' shifting sums go there too.
template <int D>
ForceStats compute_forces_packed(const SolverParams<D>& prm, ParticleSet<D>& ps,
                                 const CellGrid<D>& grid, const LevelColumns<D>& cols,
                                 const Vec<D>* extra_acc = nullptr, bool buffer_reaction = false,
                                 const ShiftingSums<D>* shift = nullptr);

// The same, packing ps into ws first.
template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                          ForceWorkspace<D>& ws, const Vec<D>* extra_acc = nullptr,
                          bool buffer_reaction = false);
// The same with a workspace of its own (tests, one-off evaluations).
template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid);

}  // namespace vrsph
