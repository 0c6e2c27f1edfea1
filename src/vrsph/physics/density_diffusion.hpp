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

#include <array>

#include "vrsph/physics/eos.hpp"

namespace vrsph {

enum class DiffusionModel { none, molteni, fourtakas };

// numerics.density_diffusion, as the case gives it.
struct DiffusionParams {
  DiffusionModel model = DiffusionModel::molteni;
  double delta = 0.1;  // delta-SPH coefficient delta (dimensionless)

  bool operator==(const DiffusionParams&) const = default;
};

// (1 + x)^a - 1 for the tiny x of the hydrostatic density difference across one support
// (|x| = rho0 g |z_ij| / B <= 2 gamma g h / c0^2, about 1e-4 in practice) is the binomial series
// sum_n c_n x^n, c_1 = a, c_n = c_{n-1} (a - n + 1) / n. Its coefficients for n = 1..5.
inline std::array<double, 5> binomial_coefficients(double a) {
  std::array<double, 5> c{};
  c[0] = a;
  for (int n = 2; n <= 5; ++n) c[n - 1] = c[n - 2] * (a - (n - 1)) / n;
  return c;
}
// The set-up refuses cases with |x| beyond this bound anywhere in a support.
inline constexpr double fourtakas_series_bound = 1.0e-2;

// rho^H_ij of Fourtakas et al. (2019) as a polynomial in z_ij:
//   rho^H(z) = rho0 sum_n c_n (rho0 g z / B)^n = sum_n k_n z^n,  k_n = rho0 c_n (rho0 g / B)^n,
// folded once per level, so that a pair forms it in a few multiply-adds. In double to fifth order
// (truncation below 2e-11 of the result for |x| <= fourtakas_series_bound); in float to third
// order: the next term is below 2e-7 of the result at the bound (a few ulp of float) and below
// 1e-12 at the |x| of 1e-4 of practical cases, where the second-order term still counts (4e-5).
template <class T>
struct HydrostaticSeries {
  static constexpr int kTerms = sizeof(T) < sizeof(double) ? 3 : 5;
  T k[kTerms] = {};
  HydrostaticSeries() = default;
  explicit HydrostaticSeries(const std::array<double, 5>& coefficients) {
    for (int n = 0; n < kTerms; ++n) k[n] = static_cast<T>(coefficients[n]);
  }
  // rho^H for z_ij (m); Horner from the highest term.
  T operator()(T z) const {
    T sum = k[kTerms - 1];
    for (int n = kTerms - 2; n >= 0; --n) sum = k[n] + z * sum;
    return z * sum;
  }
};

// The model on one level, with the numbers the force pass reads.
struct DiffusionLevel : DiffusionParams {
  double two_delta_h_c0 = 0.0;  // 2 delta h c0 (m^2/s)
  double rho0_g_over_b = 0.0;   // rho0 |g| / B (1/m): Fourtakas (the set-up's bound on |x|)
  // k_n of rho^H(z) = sum_n k_n z^n (HydrostaticSeries above), from rho0, rho0 g / B and 1/gamma.
  std::array<double, 5> hydrostatic{};

  // Sets the two Fourtakas numbers above from the EOS and |gravity| g (m/s^2), together.
  void set_hydrostatic(const TaitEos& eos, double g);
};

// The polynomial's coefficients k_n = rho0 c_n (rho0 g / B)^n for the level's numbers.
inline std::array<double, 5> hydrostatic_coefficients(double rho0, double rho0_g_over_b,
                                                      double inv_gamma) {
  std::array<double, 5> k = binomial_coefficients(inv_gamma);
  double power = rho0;
  for (double& kn : k) {
    power *= rho0_g_over_b;
    kn *= power;
  }
  return k;
}

inline void DiffusionLevel::set_hydrostatic(const TaitEos& eos, double g) {
  rho0_g_over_b = eos.rho0 * g / eos.b;
  hydrostatic = hydrostatic_coefficients(eos.rho0, rho0_g_over_b, 1.0 / eos.gamma);
}

// g: |gravity| (m/s^2); h: smoothing length (m).
inline DiffusionLevel diffusion_level(const DiffusionParams& p, const TaitEos& eos, double g,
                                      double h) {
  DiffusionLevel d{p};
  d.two_delta_h_c0 = 2.0 * p.delta * h * eos.c0;
  d.set_hydrostatic(eos, g);
  return d;
}

// The pair functions take the pass's arithmetic type T (double or float). rho_i - rho_j is
// passed as one value: the mixed precision forms it from deviations rho - rho0, exactly.
template <class T>
inline T molteni_diffusion_pair(T two_delta_h_c0, T vol_j, T rho_i_minus_j, T rij_dot_gradw,
                                T inv_r2eta) {
  return two_delta_h_c0 * vol_j * rho_i_minus_j * rij_dot_gradw * inv_r2eta;
}

template <class T>
inline T fourtakas_diffusion_pair(T two_delta_h_c0, T vol_j, T rho_i_minus_j, T rho_h,
                                  T rij_dot_gradw, T inv_r2eta) {
  return two_delta_h_c0 * vol_j * (rho_i_minus_j + rho_h) * rij_dot_gradw * inv_r2eta;
}

}  // namespace vrsph
