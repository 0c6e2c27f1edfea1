// Pair terms of the weakly compressible momentum and continuity equations (PHYSICS.md section 2).
// Each function is one pair (i, j) seen from i: no loops, no allocation, no state, so the same
// maths serves every back end. Notation: r_ij = r_i - r_j, v_ij = v_i - v_j, grad_w = grad_i W_ij
// = F(r) r_ij, vol_j = m_j / rho_j, eta2 = (0.1 h)^2.
#pragma once

#include <cmath>

#include "vrsph/core/vec.hpp"

namespace vrsph {

// Continuity, drho_i/dt contribution: rho_i V_j v_ij . grad_i W_ij.
template <int D>
inline double continuity_term(double rho_i, double vol_j, const Vec<D>& v_ij,
                              const Vec<D>& grad_w) {
  return rho_i * vol_j * dot(v_ij, grad_w);
}

// Pressure gradient, symmetric form (DualSPHysics): -m_j (p_i + p_j)/(rho_i rho_j) grad_i W_ij.
// Returns the scalar that multiplies grad_w.
inline double pressure_coef(double m_j, double p_i, double p_j, double rho_i, double rho_j) {
  return -m_j * (p_i + p_j) / (rho_i * rho_j);
}

// Laminar viscosity (Lo & Shao 2002): m_j 4 nu (r_ij . grad_w) / ((rho_i + rho_j)(r^2 + eta^2)) v_ij.
// Returns the scalar that multiplies v_ij.
inline double laminar_visc_coef(double m_j, double nu, double rij_dot_gradw, double rho_i,
                                double rho_j, double r2, double eta2) {
  return m_j * 4.0 * nu * rij_dot_gradw / ((rho_i + rho_j) * (r2 + eta2));
}

// Artificial viscosity (Monaghan 1992), active only for approaching pairs (v_ij . r_ij < 0):
//   Pi_ij = -alpha c0 mu_ij / rho_bar,  mu_ij = h v_ij.r_ij / (r^2 + eta^2),
//   contribution -m_j Pi_ij grad_w. Returns the scalar that multiplies grad_w.
inline double artificial_visc_coef(double m_j, double alpha_c0_h, double vij_dot_rij,
                                   double rho_i, double rho_j, double r2, double eta2) {
  if (vij_dot_rij >= 0.0) return 0.0;
  const double mu = vij_dot_rij / (r2 + eta2);  // h is folded into alpha_c0_h
  const double pi_ij = -alpha_c0_h * mu / (0.5 * (rho_i + rho_j));
  return -m_j * pi_ij;
}

// Density diffusion, Molteni & Colagrossi (2009):
//   D_i += 2 delta h c0 V_j (rho_i - rho_j) (r_ij . grad_w) / (r^2 + eta^2).
// r_ij . grad_w < 0, so a particle denser than its neighbours loses density.
inline double molteni_diffusion(double two_delta_h_c0, double vol_j, double rho_i, double rho_j,
                                double rij_dot_gradw, double r2, double eta2) {
  return two_delta_h_c0 * vol_j * (rho_i - rho_j) * rij_dot_gradw / (r2 + eta2);
}

// (1 + x)^a - 1 for the tiny x of the hydrostatic density difference across one kernel support
// (|x| = rho0 g |z_ij| / B <= 2 gamma g h / c0^2, about 1e-4 in practice): the binomial series to
// fifth order. For |x| <= 1e-2 the truncation is below 2e-11 of the result; the set-up checks
// that bound at set-up (fourtakas_series_bound) and the run refuses cases beyond it.
inline double binomial_series_minus_one(double x, double a) {
  const double c1 = a;
  const double c2 = c1 * (a - 1.0) / 2.0;
  const double c3 = c2 * (a - 2.0) / 3.0;
  const double c4 = c3 * (a - 3.0) / 4.0;
  const double c5 = c4 * (a - 4.0) / 5.0;
  return x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5))));
}
inline constexpr double fourtakas_series_bound = 1.0e-2;

// Density diffusion, Fourtakas et al. (2019): Molteni with the hydrostatic part removed,
//   (rho_i - rho_j) -> (rho_i - rho_j) + rho^H_ij,  rho^H_ij = rho0 [(1 + rho0 g z_ij / B)^(1/gamma) - 1],
// z_ij = z_i - z_j the height difference (against gravity), g = |gravity|. Wall pairs are skipped
// by the caller. rho0_g_over_b = rho0 |g| / B.
inline double fourtakas_diffusion(double two_delta_h_c0, double vol_j, double rho_i, double rho_j,
                                  double rho0, double rho0_g_over_b, double inv_gamma,
                                  double z_ij, double rij_dot_gradw, double r2, double eta2) {
  const double rho_h = rho0 * binomial_series_minus_one(rho0_g_over_b * z_ij, inv_gamma);
  return two_delta_h_c0 * vol_j * ((rho_i - rho_j) + rho_h) * rij_dot_gradw / (r2 + eta2);
}

// Signed pair contribution to the viscous/convective time-step limit (Monaghan & Kos 1999):
// max over pairs of v_ij . r_ij / (r^2 + eta^2).
inline double dt_visc_measure(double vij_dot_rij, double r2, double eta2) {
  return vij_dot_rij / (r2 + eta2);
}

}  // namespace vrsph
