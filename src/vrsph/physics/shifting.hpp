// Particle shifting (docs/physics.md section 7), in the corrector from half-step positions:
//   grad C_i = sum_j V_j grad_i W_ij,  div r_i = -sum_j V_j r_ij . grad_i W_ij (~D in the bulk)
//   Skillen et al. (2013, CMAME 265:163): dr_i = -A h |v_i| dt grad C_i   (A = 2)
//   Lind et al. (2012, JCP 231:1499):      dr_i = -A h^2 grad C_i          (A = 0.05 here)
// Free surface (both): dr_i = 0 if div r_i < T, else dr_i *= (div r_i - T)/(D - T), T = 1.5 (2D),
// 2.75 (3D); then each component is clamped to +-0.1 dp. Fields are not Taylor-corrected.
#pragma once

#include <algorithm>

#include "vrsph/core/vec.hpp"

namespace vrsph {

enum class ShiftingModel { none, lind, skillen };

// numerics.shifting, as the case gives it.
struct ShiftingParams {
  ShiftingModel model = ShiftingModel::none;
  double coefficient = 0.05;       // A (dimensionless): 0.05 for lind, 2 for skillen by default
  double surface_threshold = 1.5;  // T (dimensionless): no shift where div r < T; 2.75 in 3D

  bool on() const { return model != ShiftingModel::none; }  // the particles are shifted
  bool operator==(const ShiftingParams&) const = default;
};

// The model on one level, with the lengths the displacement needs.
struct ShiftingLevel : ShiftingParams {
  double h = 0.0;   // smoothing length (m)
  double dp = 0.0;  // particle spacing (m): each component of dr is kept within 0.1 dp
};

inline ShiftingLevel shifting_level(const ShiftingParams& p, double h, double dp) {
  ShiftingLevel s{p};
  s.h = h;
  s.dp = dp;
  return s;
}

// Pair contributions of the two sums, with vol_f = V_j F (grad_i W_ij = F r_ij):
// grad C_i += V_j F r_ij (component r_a of r_ij), div r_i += -V_j F r^2.
template <class T>
inline T colour_gradient_pair(T vol_f, T r_a) {
  return vol_f * r_a;
}
template <class T>
inline T position_divergence_pair(T vol_f, T r2) {
  return -vol_f * r2;
}

template <int D>
inline Vec<D> shifting_displacement(const ShiftingLevel& s, const Vec<D>& grad_c, double div_r,
                                    double speed, double dt) {
  if (!s.on() || div_r < s.surface_threshold) return Vec<D>{};
  const double scale =
      s.model == ShiftingModel::lind ? s.coefficient * s.h * s.h : s.coefficient * s.h * speed * dt;
  const double surface = (div_r - s.surface_threshold) / (D - s.surface_threshold);
  Vec<D> dr = grad_c * (-scale * surface);
  const double cap = 0.1 * s.dp;
  for (int k = 0; k < D; ++k) dr[k] = std::clamp(dr[k], -cap, cap);
  return dr;
}

}  // namespace vrsph
