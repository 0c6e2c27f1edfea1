// The execution layer's vector loop: one particle i against a block of candidates
// (particles/candidate_block.hpp). For each candidate j it forms the pair geometry of
// core/kernel.hpp (r_ij, |r_ij|, W, F with grad_i W_ij = F r_ij, both zero outside the support and
// for j = i) and hands it to the pass's body, which adds its pair terms into named sums. The loop
// has no branch: candidates that do not interact get zero kernel values, so it vectorises
// (`omp simd`) on AVX2 and AVX-512 alike. Sums are OpenMP simd reductions (a sum's order is fixed
// by the block and the vector width, not by the thread count).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "vrsph/core/kernel.hpp"

namespace vrsph {

// Pair (i, j) seen from i. rz = 0 in 2D.
struct PairGeometry {
  double rx, ry, rz;  // r_ij = r_i - r_j
  double r2, r;       // |r_ij|^2, |r_ij|
  double w;           // W(|r_ij|), 0 outside the support
  double f;           // F(|r_ij|) = W'(r)/r, 0 outside the support: grad_i W_ij = f r_ij
  double in;          // 1 when 0 < |r_ij| < 2h, else 0 (a double, not a bool: a byte-sized
                      // member would set the vector width of the whole loop)
};

// The terms of one pair that a body returns: up to 12 sums and one maximum, zero (and -1e300)
// when the body starts. The sweep adds them to its reductions; a body names the slots it uses,
// the others cost nothing.
struct PairSums {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0, s6 = 0, s7 = 0, s8 = 0, s9 = 0, s10 = 0,
         s11 = 0;
  double max = -1e300;
};

// Candidate j's columns, read by the sweep and handed to the body as values.
template <int K>
struct Neighbour {
  double c[K];
  double operator[](int k) const { return c[k]; }
};

// Sweeps x_i against the `len` candidates of a block whose columns 0..D-1 are positions, and
// calls body(geometry, neighbour) -> PairSums for each. sum[k] += slot k for the first NS slots,
// vmax = max(vmax, max) when kMax.
// What makes the loop vectorise with GCC (each was measured; docs/validation.md): the body reads
// only values (the neighbour's columns, and what its closure captured by value), never a
// pointer, reference or a captured reference, and returns its terms by value. A body that
// reads a column through a pointer, or adds into references to the sums, compiles to the
// scalar loop.
template <int D, int K, int NS, bool kMax, class Body>
[[gnu::always_inline]] inline void sweep_pairs(const WendlandC2<D>& kernel_in,
                                               const double xi_in[3],
                                               const std::array<std::vector<double>, K>& cols,
                                               std::ptrdiff_t len, Body body, double (&sum)[12],
                                               double& vmax) {
  const WendlandC2<D> kernel = kernel_in;  // local copies: nothing in the loop can alias them
  const double xi[3] = {xi_in[0], xi_in[1], D == 3 ? xi_in[D - 1] : 0.0};
  static_assert(K <= 12, "sweep_pairs reads at most 12 columns");
  const double* col[12] = {};
  for (int k = 0; k < K; ++k) col[k] = cols[k].data();
  const double support2 = kernel.support2;
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0, s6 = 0, s7 = 0, s8 = 0, s9 = 0, s10 = 0,
         s11 = 0, mx = -1e300;
#pragma omp simd reduction(+ : s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11) reduction(max : mx)
  for (std::ptrdiff_t j = 0; j < len; ++j) {
    // One load per column, written out (a loop over k here can survive as a loop inside the
    // vectorised loop, and then the sweep falls back to scalar code).
    Neighbour<K> nb;
    if constexpr (K > 0) nb.c[0] = col[0][j];
    if constexpr (K > 1) nb.c[1] = col[1][j];
    if constexpr (K > 2) nb.c[2] = col[2][j];
    if constexpr (K > 3) nb.c[3] = col[3][j];
    if constexpr (K > 4) nb.c[4] = col[4][j];
    if constexpr (K > 5) nb.c[5] = col[5][j];
    if constexpr (K > 6) nb.c[6] = col[6][j];
    if constexpr (K > 7) nb.c[7] = col[7][j];
    if constexpr (K > 8) nb.c[8] = col[8][j];
    if constexpr (K > 9) nb.c[9] = col[9][j];
    if constexpr (K > 10) nb.c[10] = col[10][j];
    if constexpr (K > 11) nb.c[11] = col[11][j];
    PairGeometry g;
    g.rx = xi[0] - nb.c[0];
    g.ry = xi[1] - nb.c[1];
    g.rz = D == 3 ? xi[2] - nb.c[D - 1] : 0.0;
    g.r2 = g.rx * g.rx + g.ry * g.ry + g.rz * g.rz;
    const bool in = (g.r2 < support2) & (g.r2 > 0.0);  // `&`: both tests without a branch
    g.in = in ? 1.0 : 0.0;
    g.r = std::sqrt(g.r2);
    // Both kernel values are evaluated for every candidate (finite even for the far dummies) and
    // then selected: an operation inside the condition would be a branch the default
    // trapping-math rules do not let the compiler turn into a select.
    const double f = kernel.f(g.r), w = kernel.w(g.r);
    g.f = in ? f : 0.0;
    g.w = in ? w : 0.0;
    const PairSums t = body(g, nb);
    // Only the NS slots the body uses: adding a zero is not free (x + 0 is not x for x = -0).
    if constexpr (NS > 0) s0 += t.s0;
    if constexpr (NS > 1) s1 += t.s1;
    if constexpr (NS > 2) s2 += t.s2;
    if constexpr (NS > 3) s3 += t.s3;
    if constexpr (NS > 4) s4 += t.s4;
    if constexpr (NS > 5) s5 += t.s5;
    if constexpr (NS > 6) s6 += t.s6;
    if constexpr (NS > 7) s7 += t.s7;
    if constexpr (NS > 8) s8 += t.s8;
    if constexpr (NS > 9) s9 += t.s9;
    if constexpr (NS > 10) s10 += t.s10;
    if constexpr (NS > 11) s11 += t.s11;
    if constexpr (kMax) mx = std::max(mx, t.max);
  }
  const double all[12] = {s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11};
  for (int k = 0; k < 12; ++k) sum[k] += all[k];
  vmax = std::max(vmax, mx);
}

}  // namespace vrsph
