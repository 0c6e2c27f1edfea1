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
#include "vrsph/solver/pass1_terms.hpp"

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

// A force pass can also sum surface pass 1's terms for its fluid particles (solver/pass1_terms.hpp)
// over the same candidates at the same positions, so that one sweep serves both: shifting's grad C
// and div r on the evaluations where pass 1 runs for shifting alone (surface_sums_for_shifting),
// or the whole pass 1 at a capillary refresh (surface_sums_in_forces). The whole pass fits only
// where the force pass's 2 + D sums and pass 1's (with G) fit a sweep's 12: 2D (4 + 8), not 3D
// (5 + 12).
template <int D>
inline constexpr bool kForcePassSumsPass1 = 2 + D + kPass1Terms<D, true> <= 12;

// ps.acc and ps.drho for every particle (acc = 0 on walls) from the columns `cols`, packed from
// ps (LevelColumns::pack). extra_acc (null: none) is a per-particle acceleration added to the
// fluid's, e.g. surface tension; it counts in ForceStats::max_acc.
// Buffer particles get acc = 0 and drho = 0 (their v and rho come from another level).
// pair_acc (null: none): each fluid particle's acceleration from its level's fluid and buffer
// neighbours alone (walls and extra_acc left out), from which vres/momentum.hpp measures the net
// force the buffer exerts on the fluid. pass1 (null: none): the fluid particles' pass-1 fields go
// there too, pass1->terms of them (shifting's, or the whole pass with G where kForcePassSumsPass1).
template <int D>
ForceStats compute_forces_packed(const SolverParams<D>& prm, ParticleSet<D>& ps,
                                 const CellGrid<D>& grid, const LevelColumns<D>& cols,
                                 const Vec<D>* extra_acc = nullptr, Vec<D>* pair_acc = nullptr,
                                 const Pass1Out<D>* pass1 = nullptr);

// The same, packing ps into ws first.
template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                          ForceWorkspace<D>& ws, const Vec<D>* extra_acc = nullptr,
                          Vec<D>* pair_acc = nullptr);
// The same with a workspace of its own (tests, one-off evaluations).
template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid);

}  // namespace vrsph
