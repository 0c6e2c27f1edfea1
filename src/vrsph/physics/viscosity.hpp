// Viscous terms of the momentum equation, one pair (i, j) seen from i, eta2 = (0.1 h)^2,
// inv_r2eta = 1 / (r^2 + eta2) and inv_rho_sum = 1 / (rho_i + rho_j) (both from
// pair_reciprocals). Written without branches (select, not return) so the force loop
// vectorises under the default trapping-math rules.
//  - Laminar (Lo & Shao 2002; Morris et al. 1997):
//      (dv_i/dt) += 4 nu m_j (r_ij . grad_i W_ij) / ((rho_i + rho_j)(r^2 + eta^2)) v_ij;
//    laminar_viscosity_pair returns the factor of v_ij.
//  - Artificial (Monaghan 1992), for approaching pairs only (v_ij . r_ij < 0):
//      Pi_ij = -alpha c0 mu_ij / rho_bar_ij,  mu_ij = h v_ij . r_ij / (r^2 + eta^2),
//      (dv_i/dt) += -m_j Pi_ij grad_i W_ij;
//    artificial_viscosity_pair returns the factor of grad_i W_ij (h folded into alpha_c0_h).
//  - Viscous time-step measure (Monaghan & Kos 1999): the largest v_ij . r_ij / (r^2 + eta^2) over
//    the pairs within the support sets dt_visc = h / (c0 + h max).
#pragma once

namespace vrsph {

enum class ViscosityModel { laminar, artificial };

// numerics.viscosity, as the case gives it.
struct ViscosityParams {
  ViscosityModel model = ViscosityModel::laminar;
  double alpha = 0.01;  // artificial viscosity coefficient alpha (dimensionless); artificial only

  bool operator==(const ViscosityParams&) const = default;
};

// The model on one level, with the numbers the force pass reads.
struct ViscosityLevel : ViscosityParams {
  double nu = 0.0;          // kinematic viscosity applied (m^2/s): the fluid's if laminar, else 0
  double alpha_c0_h = 0.0;  // alpha c0 h (m^2/s): artificial
};

// nu_fluid: fluid.kinematic_viscosity (m^2/s); c0: speed of sound (m/s); h: smoothing length (m).
inline ViscosityLevel viscosity_level(const ViscosityParams& p, double nu_fluid, double c0,
                                      double h) {
  ViscosityLevel v{p};
  v.nu = p.model == ViscosityModel::laminar ? nu_fluid : 0.0;
  v.alpha_c0_h = p.alpha * c0 * h;
  return v;
}

// The two reciprocals of a pair's viscous and diffusive terms from one division,
// 1 / ((r^2 + eta2)(rho_i + rho_j)): the force loop is bound by the divider (a division costs as
// much as eight multiplications), and three divisions per pair became one.
// The pair functions take the pass's arithmetic type T (double, or float in the mixed
// precision of core/precision.hpp); every argument has that type.
template <class T>
struct PairReciprocals {
  T inv_r2eta;    // 1 / (r^2 + eta2)
  T inv_rho_sum;  // 1 / (rho_i + rho_j)
};
template <class T>
inline PairReciprocals<T> pair_reciprocals(T r2, T eta2, T rho_i, T rho_j) {
  const T r2eta = r2 + eta2, rho_sum = rho_i + rho_j;
  const T d = T(1) / (r2eta * rho_sum);
  return {d * rho_sum, d * r2eta};
}

template <class T>
inline T laminar_viscosity_pair(T m_j, T nu, T rij_dot_gradw, T inv_r2eta, T inv_rho_sum) {
  return m_j * T(4) * nu * rij_dot_gradw * inv_r2eta * inv_rho_sum;
}

template <class T>
inline T artificial_viscosity_pair(T m_j, T alpha_c0_h, T vij_dot_rij, T inv_r2eta, T inv_rho_sum) {
  const T mu = vij_dot_rij * inv_r2eta;
  const T pi_ij = -alpha_c0_h * mu * (T(2) * inv_rho_sum);  // rho_bar_ij = (rho_i + rho_j) / 2
  const T approaching = vij_dot_rij < T(0) ? T(1) : T(0);   // a factor, not a branch
  return approaching * (-m_j * pi_ij);
}

template <class T>
inline T viscous_dt_measure(T vij_dot_rij, T inv_r2eta) {
  return vij_dot_rij * inv_r2eta;
}

}  // namespace vrsph
