// Particle shifting (PHYSICS.md section 4), applied in the corrector from the half-step positions:
//   grad C_i = sum_j V_j grad_i W_ij,  div r_i = -sum_j V_j r_ij . grad_i W_ij (~D in the bulk)
//   Skillen et al. (2013, CMAME 265:163): dr_i = -A h |v_i| dt grad C_i   (A = 2)
//   Lind et al. (2012, JCP 231:1499):      dr_i = -A h^2 grad C_i          (A = 0.05 here)
// Free surface (both): dr_i = 0 if div r_i < T, else dr_i *= (div r_i - T)/(D - T), T = 1.5 (2D),
// 2.75 (3D); then each component is clamped to +-0.1 dp. Fields are not Taylor-corrected.
#pragma once

#include <algorithm>

#include "vrsph/core/vec.hpp"
#include "vrsph/setup/case_spec.hpp"

namespace vrsph {

struct ShiftingParams {
  ShiftingModel model = ShiftingModel::none;
  double coefficient = 0.0;  // A
  double threshold = 1.5;    // T
  double h = 0.0;
  double dp = 0.0;
};

template <int D>
inline Vec<D> shifting_displacement(const ShiftingParams& s, const Vec<D>& grad_c, double div_r,
                                    double speed, double dt) {
  if (s.model == ShiftingModel::none || div_r < s.threshold) return Vec<D>{};
  const double scale = s.model == ShiftingModel::lind ? s.coefficient * s.h * s.h
                                                      : s.coefficient * s.h * speed * dt;
  const double surface = (div_r - s.threshold) / (D - s.threshold);
  Vec<D> dr = grad_c * (-scale * surface);
  const double cap = 0.1 * s.dp;
  for (int k = 0; k < D; ++k) dr[k] = std::clamp(dr[k], -cap, cap);
  return dr;
}

// Shift of a buffer particle (PHYSICS.md section 5): without its component along the unit normal
// n_f of the nearest interface face and, where the particle has a free-surface normal n_s (zero
// elsewhere), without its component along n_s either. Buffer velocities are interpolated from the
// other level, so nothing pulls a buffer particle back once shifting has moved it: the Lind and
// Skillen shifts of the rows next to a free surface point outwards (grad C points inwards), and
// a buffer kept them would move its surface rows out of the donor level's free surface, with every
// step adding to it. The two directions are made orthonormal (Gram-Schmidt) before they are
// removed; where the surface crosses the interface (n_s normal to n_f in 2D) nothing is left.
template <int D>
inline Vec<D> buffer_shift(Vec<D> dr, const Vec<D>& n_face, const Vec<D>& n_surface) {
  dr -= dot(dr, n_face) * n_face;
  Vec<D> e = n_surface - dot(n_surface, n_face) * n_face;
  const double e2 = norm2(e);
  if (e2 > 1e-12) dr -= (dot(dr, e) / e2) * e;
  return dr;
}

}  // namespace vrsph
