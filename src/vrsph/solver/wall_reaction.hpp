// The force of the fluid on the wall particles (the series' wall<N>_f columns): for wall particle
// i, the pressure and viscous pair terms of the force pass seen from i,
//   F_i = m_i sum_j [ -(p_i + p_j) V_j / rho_i grad_i W_ij + viscous_ij ],
// over its Kind::fluid neighbours j (buffer particles, which mirror another level, and walls left
// out), with the pair functions of physics/pressure.hpp and physics/viscosity.hpp. Those pair
// terms are antisymmetric once multiplied by the masses, m_i a_ij = -m_j a_ji, so F_i is exactly
// minus the force that i exerts on the fluid in the force pass (forces.cpp): the momentum the
// fluid gives the wall. A separate pass over the wall particles only, run at output times, so the
// force pass keeps its cost. The pressures come from the EOS; the grid must be sorted.
#pragma once

#include <cstdint>
#include <vector>

#include "vrsph/solver/level.hpp"

namespace vrsph {

// The ids [first, end) of one wall block's particles in a level (walls keep their ids).
struct IdRange {
  std::uint64_t first = 0;
  std::uint64_t end = 0;
  bool holds(std::uint64_t id) const { return id >= first && id < end; }
};

// force[i] = F_i for every wall particle i of ps, 0 for the others (force resized to ps.size()).
template <int D>
void wall_reaction_forces(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                          const CellGrid<D>& grid, std::vector<Vec<D>>& force);

// The sum of F_i over the wall particles whose id lies in blocks[b], for each b (N; per metre of
// depth in 2D), summed in particle order.
template <int D>
std::vector<Vec<D>> wall_block_forces(const Level<D>& L, const std::vector<IdRange>& blocks);

}  // namespace vrsph
