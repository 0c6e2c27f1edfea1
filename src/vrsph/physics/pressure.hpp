// Pressure gradient of the weakly compressible momentum equation, symmetric form (Monaghan 1992;
// as DualSPHysics), one pair (i, j) seen from i:
//   (dv_i/dt)_p += -m_j (p_i + p_j) / (rho_i rho_j) grad_i W_ij = -(p_i + p_j) V_j / rho_i F r_ij,
// V_j = m_j / rho_j. Antisymmetric in (i, j) with equal masses, so a level's fluid pairs exchange
// momentum exactly. The function returns the factor of F r_ij.
#pragma once

namespace vrsph {

template <class T>
inline T pressure_pair(T p_i, T p_j, T vol_j, T inv_rho_i) {
  return -(p_i + p_j) * vol_j * inv_rho_i;
}

}  // namespace vrsph
