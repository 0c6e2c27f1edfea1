// Density diffusion in the continuity equation (delta-SPH), one fluid pair seen from i,
// inv_r2eta = 1 / (r^2 + (0.1 h)^2), rij_dot_gradw = r_ij . grad_i W_ij = F r^2 (< 0):
//  - Molteni & Colagrossi (2009):
//      D_i += 2 delta h c0 V_j (rho_i - rho_j) (r_ij . grad_i W_ij) / (r^2 + eta^2);
//    a particle denser than its neighbours loses density.
//  - Fourtakas et al. (2019): Molteni with the hydrostatic part removed,
//      (rho_i - rho_j) -> (rho_i - rho_j) + rho^H_ij,
//      rho^H_ij = rho0 [(1 + rho0 g z_ij / B)^(1/gamma) - 1],
//    z_ij = z_i - z_j measured against gravity. Wall pairs take no part (as DualSPHysics' "full"
//    variant): the force pass leaves them out.
#pragma once

#include "vrsph/physics/eos.hpp"

namespace vrsph {

enum class DiffusionModel { none, molteni, fourtakas };

// numerics.density_diffusion, as the case gives it.
struct DiffusionParams {
  DiffusionModel model = DiffusionModel::molteni;
  double delta = 0.1;  // delta-SPH coefficient delta (dimensionless)

  bool operator==(const DiffusionParams&) const = default;
};

// The model on one level, with the numbers the force pass reads.
struct DiffusionLevel : DiffusionParams {
  double two_delta_h_c0 = 0.0;   // 2 delta h c0 (m^2/s)
  double rho0_g_over_b = 0.0;    // rho0 |g| / B (1/m): Fourtakas
  double inv_gamma = 1.0 / 7.0;  // 1 / gamma of the EOS (dimensionless): Fourtakas
};

// g: |gravity| (m/s^2); h: smoothing length (m).
inline DiffusionLevel diffusion_level(const DiffusionParams& p, const TaitEos& eos, double g,
                                      double h) {
  DiffusionLevel d{p};
  d.two_delta_h_c0 = 2.0 * p.delta * h * eos.c0;
  d.rho0_g_over_b = eos.rho0 * g / eos.b;
  d.inv_gamma = 1.0 / eos.gamma;
  return d;
}

// The pair functions take the pass's arithmetic type T (double or float). rho_i - rho_j is
// passed as one value: the mixed precision forms it from deviations rho - rho0, exactly.
template <class T>
inline T molteni_diffusion_pair(T two_delta_h_c0, T vol_j, T rho_i_minus_j, T rij_dot_gradw,
                                T inv_r2eta) {
  return two_delta_h_c0 * vol_j * rho_i_minus_j * rij_dot_gradw * inv_r2eta;
}

// (1 + x)^a - 1 for the tiny x of the hydrostatic density difference across one support
// (|x| = rho0 g |z_ij| / B <= 2 gamma g h / c0^2, about 1e-4 in practice): the binomial series to
// fifth order, with a truncation below 2e-11 of the result for |x| <= fourtakas_series_bound. The
// set-up refuses cases beyond that bound.
template <class T>
inline T binomial_series_minus_one(T x, T a) {
  const T c1 = a;
  const T c2 = c1 * (a - T(1)) / T(2);
  const T c3 = c2 * (a - T(2)) / T(3);
  const T c4 = c3 * (a - T(3)) / T(4);
  const T c5 = c4 * (a - T(4)) / T(5);
  return x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5))));
}
inline constexpr double fourtakas_series_bound = 1.0e-2;

// rho^H_ij of Fourtakas et al. (2019); rho0_g_over_b = rho0 |g| / B.
template <class T>
inline T hydrostatic_density_difference(T rho0, T rho0_g_over_b, T inv_gamma, T z_ij) {
  return rho0 * binomial_series_minus_one(rho0_g_over_b * z_ij, inv_gamma);
}

template <class T>
inline T fourtakas_diffusion_pair(T two_delta_h_c0, T vol_j, T rho_i_minus_j, T rho_h,
                                  T rij_dot_gradw, T inv_r2eta) {
  return two_delta_h_c0 * vol_j * (rho_i_minus_j + rho_h) * rij_dot_gradw * inv_r2eta;
}

}  // namespace vrsph
