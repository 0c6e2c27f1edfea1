// Single-phase surface tension of Cen, Fourtakas, Lind & Rogers (2024, Comput. Phys. Commun.
// 295:109012), as extended to variable resolution by Lee et al. (conference poster), written out
// in docs/physics.md section 6. Per particle i (fluid only), in three neighbour passes:
//  1. M_i = sum_j V_j (r_j - r_i) (x) grad_i W_ij  (~ I in the bulk), L_i = M_i^-1,
//     lambda_i = smallest eigenvalue of M_i (~1 inside, ~0.5 on a flat surface);
//  2. grad lambda_i = L_i sum_j (lambda_j - lambda_i) V_j grad_i W_ij   if lambda_i >= 0.7,
//                     L_i sum_j lambda_j V_j grad_i W_ij                 otherwise;
//     n_i = -grad lambda_i / |grad lambda_i| if |grad lambda_i| > eps lambda_i / h, else 0;
//  3. kappa_i = sum_j S_ij (n_j - n_i) . (L_i grad_i W_ij) V_j, S_ij = 1 when both normals are
//     non-zero and n_i . n_j >= cos(alpha_t) (-1/2 in 2D, -1/3 in 3D);
//     phi_i = 1 / (2 sum_j W_ij V_j), delta_i = 2 max(1, phi_i) |sum_j grad_i W_ij V_j|,
//     a_st,i = -sigma kappa_i n_i delta_i / rho_i.
// The functions below are the per-particle pieces; the passes are in solver/surface_pass.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "vrsph/core/mat.hpp"
#include "vrsph/core/vec.hpp"

namespace vrsph {

enum class SurfaceRefresh : std::uint8_t { every_step, capillary };

// numerics.surface_tension, as the case gives it (sigma itself is fluid.surface_tension).
struct SurfaceTensionParams {
  double lambda_threshold = 0.7;  // step 2 (dimensionless): difference form where lambda_i >= it
  double normal_epsilon = 0.1;    // step 2, eps (dimensionless): n_i = 0 below eps lambda_i / h
  bool surface_offset = false;    // step 3: curvature_at_surface() in the force (not Cen)
  bool curvature_correction = false;  // step 3: corrected_curvature() (not Cen)
  bool zero_net_force = false;        // remove the net capillary force (closed surfaces; not Cen)
  // How often passes 2 and 3 (normals, curvature, the capillary acceleration) run (not Cen):
  // every force evaluation, or once per refresh_interval x the capillary time-step limit
  // (solver/timestep.hpp), the acceleration extrapolated in between (sim/surface_refresh.hpp).
  SurfaceRefresh refresh = SurfaceRefresh::capillary;
  // In capillary dt limits; "capillary" only. 0.25 refreshes every second step on the 2D drop at
  // dp 5e-5 and every third on the 3D drop at dp 2e-4: against every_step, mean interior within
  // 0.01% and RMSE within 1.5% in 2D, the 3D drop's parasitic speed within its draws' spread
  // (docs/validation.md, "The held acceleration extrapolated"). Held without extrapolation,
  // 0.25 raised that speed by 30%.
  double refresh_interval = 0.25;

  bool operator==(const SurfaceTensionParams&) const = default;
};

// Pair contributions of step 1, vol_f = V_j F (grad_i W_ij = F r_ij): the entry (a, b) of M_i,
// V_j (r_j - r_i)_a (grad_i W_ij)_b = -V_j F r_a r_b, and the Shepard sum V_j W_ij of phi_i.
// T: double, or float in the mixed precision's pair loops (core/precision.hpp).
template <class T>
inline T correction_matrix_pair(T vol_f, T r_a, T r_b) {
  return -vol_f * r_a * r_b;
}
template <class T>
inline T shepard_pair(T vol_j, T w) {
  return vol_j * w;
}

// Pair contribution of step 2: the factor of r_ij in (lambda_j - lambda_ref) V_j grad_i W_ij, with
// lambda_ref = lambda_i (difference form, lambda_i >= 0.7) or 0.
template <class T>
inline T lambda_gradient_pair(T lambda_j, T lambda_ref, T vol_j, T f) {
  return (lambda_j - lambda_ref) * vol_j * f;
}

// Below this smallest eigenvalue M_i is too close to singular to invert (an isolated particle or
// a thin filament); L_i = I is used instead.
inline constexpr double kMinInvertibleLambda = 0.1;

template <int D>
inline Mat<D> correction_from_m(const Mat<D>& m, double lambda) {
  return lambda >= kMinInvertibleLambda ? inverse(m) : Mat<D>::identity();
}

// Unit outward normal from the corrected gradient of lambda, or zero when the gradient is too
// weak to define one (|grad lambda| <= eps lambda / h).
template <int D>
inline Vec<D> normal_from_lambda_gradient(const Vec<D>& grad_lambda, double lambda, double eps,
                                          double h) {
  const double g = norm(grad_lambda);
  if (!(g > eps * lambda / h) || g == 0.0) return Vec<D>{};
  return grad_lambda * (-1.0 / g);
}

// cos(alpha_t) of the curvature filter S_ij.
template <int D>
constexpr double curvature_filter_cos() {
  return D == 2 ? -0.5 : -1.0 / 3.0;
}

// S_ij of step 3: both normals non-zero and n_i . n_j >= cos(alpha_t) (n_i is checked by the
// caller). Written as a value, not a branch, for the vector loop.
template <int D, class T>
inline bool curvature_filter(T n_j_norm2, T ni_dot_nj) {
  return (n_j_norm2 != T(0)) & (ni_dot_nj >= T(curvature_filter_cos<D>()));
}

// Surface delta of the single-phase colour function: 2 max(1, phi) |grad C|, phi = 1/(2 shepard).
// The factor 2 restores the missing gas half of |grad C| across a free surface.
inline double surface_delta(double grad_c_norm, double shepard) {
  const double phi = 1.0 / (2.0 * shepard);
  return 2.0 * std::max(1.0, phi) * grad_c_norm;
}

// Option `surface_offset` (not part of Cen et al. 2024): the free surface of a particle set lies
// half a spacing outside the centres of its outer particles, where the curvature is measured.
// Referring kappa to the surface, 1/r -> 1/(r + dp/2) for a circle and 2/r -> 2/(r + dp/2) for a
// sphere: kappa_s = kappa / (1 + kappa dp / (2 (D - 1))) (denominator kept >= 1/2). Without it
// the Laplace pressure carries a bias of about dp / (2R) that depends on the resolution, which
// with variable resolution gives the levels different pressures.
template <int D>
inline double curvature_at_surface(double kappa, double dp) {
  return kappa / std::max(0.5, 1.0 + kappa * dp / (2.0 * (D - 1)));
}

// Option `curvature_correction` (not part of Cen et al. 2024): the curvature sum of step 3,
// kappa_i = sum_j S_ij V_j (n_j - n_i) . G_ij with G_ij = L_i grad_i W_ij, runs only over the
// neighbours with a normal, a one-sided and truncated set near a free surface. Taylor-expanding
// the normal field of a locally spherical surface (n = x / r, principal curvature u = 1/r) about
// particle i, with d_j = r_j - r_i and e = n_i:
//   kappa_i = a_i u + b_i u^2 + O(d^3 u^3),
//   a_i = sum_j V_j (d_j . G_ij - (d_j . e)(e . G_ij))    (D - 1 for a complete stencil),
//   b_i = sum_j V_j ((3/2)(d_j . e)^2 (e . G_ij) - (d_j . e)(d_j . G_ij) - |d_j|^2 (e . G_ij) / 2)
//        (0 for a symmetric stencil).
// The corrected curvature is (D - 1) u from the root u = 2 kappa / (a + sqrt(a^2 + 4 b kappa)),
// kept uncorrected where a < (D - 1)/4 (too few neighbours with normals) or the root is complex.
// docs/validation.md ("Figures formerly in code comments") records its effect on a static circle.
template <class T = double>
struct CurvatureSumsT {
  T kappa = 0, a = 0, b = 0;
};
using CurvatureSums = CurvatureSumsT<double>;

template <int D, class T>
inline void add_curvature_pair(CurvatureSumsT<T>& s, T v_j, const Vec<D, T>& n_i,
                               const Vec<D, T>& n_j, const Vec<D, T>& d_j, const Vec<D, T>& g_ij) {
  s.kappa += v_j * dot(n_j - n_i, g_ij);
  const T de = dot(d_j, n_i), dg = dot(d_j, g_ij), eg = dot(n_i, g_ij);
  s.a += v_j * (dg - de * eg);
  s.b += v_j * (T(1.5) * de * de * eg - de * dg - T(0.5) * norm2(d_j) * eg);
}

template <int D>
inline double corrected_curvature(const CurvatureSums& s) {
  constexpr double dm1 = D - 1;
  const double disc = s.a * s.a + 4.0 * s.b * s.kappa;
  if (!(s.a > 0.25 * dm1) || !(disc >= 0.0)) return s.kappa;
  return dm1 * 2.0 * s.kappa / (s.a + std::sqrt(disc));
}

// CSF acceleration -sigma kappa n delta / rho.
template <int D>
inline Vec<D> csf_acceleration(double sigma, double kappa, const Vec<D>& n, double delta,
                               double rho) {
  return n * (-sigma * kappa * delta / rho);
}

}  // namespace vrsph
