// Continuity equation of weakly compressible SPH (Monaghan 1992), one pair seen from i:
//   (drho_i/dt) += rho_i V_j v_ij . grad_i W_ij = rho_i V_j F (v_ij . r_ij),
// v_ij = v_i - v_j, grad_i W_ij = F r_ij. Walls use the same term over their fluid neighbours
// (physics/walls.hpp).
#pragma once

namespace vrsph {

template <class T>
inline T continuity_pair(T rho_i, T vol_j, T f, T vij_dot_rij) {
  return rho_i * vol_j * f * vij_dot_rij;
}

}  // namespace vrsph
