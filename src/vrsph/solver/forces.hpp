// The force pass: one gather loop over particles that evaluates, for every fluid particle, the
// momentum and continuity right-hand sides (pressure, viscosity, density diffusion), and for every
// wall particle its continuity equation (fluid neighbours only; Crespo et al. 2007 dynamic
// boundary). Each particle writes only its own outputs: no atomics, the same result for any thread
// count. Model choices are template parameters resolved once per call (forces.cpp).
#pragma once

#include <cstdint>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/params.hpp"

namespace vrsph {

struct ForceStats {
  double max_visc_dt = -1e300;  // max over pairs of v_ij . r_ij / (r^2 + eta^2)
  double max_acc = 0.0;         // max |a| over fluid particles (gravity excluded)
  std::uint64_t pairs = 0;      // pairs within 2h evaluated (i != j)
};

// Fills ps.p from the EOS, then ps.acc and ps.drho for every particle (acc = 0 on walls).
template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid);

}  // namespace vrsph
