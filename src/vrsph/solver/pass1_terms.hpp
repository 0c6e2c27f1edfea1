// Surface pass 1's pair terms in one slot layout, shared by the pass itself
// (solver/surface_pass.cpp) and by the force pass (solver/forces.cpp), which can sum them in the
// same sweep as the pair forces (Pass1InForces). The layout puts shifting's sums first, so that a
// sweep for shifting alone takes the first D + 1 terms and a sweep for the whole pass takes them
// all:
//   grad C = sum_j V_j grad_i W_ij                         slots 0 .. D-1
//   div r = -sum_j V_j r_ij . grad_i W_ij                  slot D
//   M = -sum_j V_j r_ij (x) grad_i W_ij (Cen et al. 2024)  xx, xy, yy (2D); xx, xy, yy, xz, yz, zz
//   Shepard sum_j V_j W_ij (the particle's own term apart)
//   G = sum_j V_j |grad_i W_ij| (surface tension only: it bounds pass 2's sum)
// Every term is V_j times a function of the pair geometry (physics/shifting.hpp,
// physics/surface_tension.hpp), so a slot's sum is the same wherever the sweep puts it.
#pragma once

#include <cstddef>
#include <utility>

#include "vrsph/core/mat.hpp"
#include "vrsph/core/vec.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/surface_tension.hpp"

namespace vrsph {

// What a level's next force pass sums of surface pass 1 for its fluid particles (the pass itself
// then covers the other particles only): nothing; shifting's grad C and div r (an evaluation
// without a capillary refresh); or all of it (a refresh whose passes 2 and 3 wait for the force
// pass: sim/simulation_surface.cpp).
enum class Pass1InForces { none, shifting, full };

// Terms of the layout above: shifting's, and the whole pass with or without G.
template <int D>
inline constexpr int kShiftingTerms = D + 1;
template <int D, bool kGradW>
inline constexpr int kPass1Terms = D + 1 + D*(D + 1) / 2 + 1 + (kGradW ? 1 : 0);

// Sets the first N terms of the layout, for candidate j of volume vol_j, into slots kFirst ..
// kFirst + N - 1 of s. Terms past N are not formed.
template <int D, int N, int kFirst, class T>
[[gnu::always_inline]] inline void set_pass1_terms(const PairGeometryT<T>& g, T vol_j,
                                                   PairSumsT<T>& s) {
  static_assert(N <= kPass1Terms<D, true> && kFirst + N <= 12, "pass 1 has at most 12 terms");
  const T vf = vol_j * g.f;
  T t[12] = {};
  t[0] = colour_gradient_pair(vf, g.rx);
  t[1] = colour_gradient_pair(vf, g.ry);
  if constexpr (D == 3) t[2] = colour_gradient_pair(vf, g.rz);
  t[D] = position_divergence_pair(vf, g.r2);
  constexpr int m = D + 1;
  t[m] = correction_matrix_pair(vf, g.rx, g.rx);
  t[m + 1] = correction_matrix_pair(vf, g.rx, g.ry);
  t[m + 2] = correction_matrix_pair(vf, g.ry, g.ry);
  if constexpr (D == 3) {
    t[m + 3] = correction_matrix_pair(vf, g.rx, g.rz);
    t[m + 4] = correction_matrix_pair(vf, g.ry, g.rz);
    t[m + 5] = correction_matrix_pair(vf, g.rz, g.rz);
  }
  constexpr int shep = m + D * (D + 1) / 2;
  t[shep] = shepard_pair(vol_j, g.w);
  t[shep + 1] = -vf * g.r;  // F <= 0: V_j |grad_i W_ij| = -V_j F r
  [&]<int... k>(std::integer_sequence<int, k...>) { ((slot<kFirst + k>(s) = t[k]), ...); }
  (std::make_integer_sequence<int, N>{});
}

// V_i W(0), particle i's own term of the Shepard sum: its volume m_i / rho_i, times its weight
// where the level's columns carry weights (solver/columns.hpp).
template <class Particles, class Columns>
double shepard_self(const Particles& ps, const Columns& cols, std::size_t i, double w0) {
  const double vol_i = ps.mass_of(i) / ps.rho[i] * (cols.weight.empty() ? 1.0 : cols.weight[i]);
  return shepard_pair(vol_i, w0);
}

// Where pass 1 writes the fields of a particle (SurfaceFields' arrays), from the sums of the first
// `terms` terms of the layout: grad C and div r always; with the whole pass also M's smallest
// eigenvalue lambda, L = M^-1 (or I), the Shepard sum with the particle's own term and, where
// grad_w is not null, G.
template <int D>
struct Pass1Out {
  Vec<D>* grad_c = nullptr;
  double* div_r = nullptr;
  double* lambda = nullptr;
  Mat<D>* l_corr = nullptr;
  double* shepard = nullptr;
  double* grad_w = nullptr;
  int terms = kShiftingTerms<D>;

  // s: the sums in layout order; shepard_self = V_i W(0) of the particle's kernel.
  void store(std::size_t i, const double* s, double shepard_self) const {
    for (int k = 0; k < D; ++k) grad_c[i][k] = s[k];
    div_r[i] = s[D];
    if (terms == kShiftingTerms<D>) return;
    constexpr int m = D + 1;
    Mat<D> mat;
    mat(0, 0) = s[m], mat(0, 1) = mat(1, 0) = s[m + 1], mat(1, 1) = s[m + 2];
    if constexpr (D == 3) {
      mat(0, 2) = mat(2, 0) = s[m + 3], mat(1, 2) = mat(2, 1) = s[m + 4], mat(2, 2) = s[m + 5];
    }
    const double lam = min_eigenvalue(mat);
    lambda[i] = lam;
    l_corr[i] = correction_from_m(mat, lam);
    constexpr int shep = m + D * (D + 1) / 2;
    shepard[i] = shepard_self + s[shep];
    if (grad_w != nullptr) grad_w[i] = s[shep + 1];
  }
};

}  // namespace vrsph
