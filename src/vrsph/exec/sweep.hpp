// The execution layer's vector loop: one particle i against a block of candidates
// (particles/candidate_block.hpp). For each candidate j it forms the pair geometry of
// core/kernel.hpp (r_ij, |r_ij|, W, F with grad_i W_ij = F r_ij, both zero outside the support and
// for j = i) and hands it to the pass's body, which adds its pair terms into named sums. The loop
// has no branch: candidates that do not interact get zero kernel values, so it vectorises
// (`omp simd`) on AVX2 and AVX-512 alike. Sums are OpenMP simd reductions (a sum's order is fixed
// by the block and the vector width, not by the thread count).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "vrsph/core/kernel.hpp"

namespace vrsph {

// Pair (i, j) seen from i. rz = 0 in 2D.
struct PairGeometry {
  double rx, ry, rz;  // r_ij = r_i - r_j
  double r2, r;       // |r_ij|^2, |r_ij|
  double w;           // W(|r_ij|), 0 outside the support
  double f;           // F(|r_ij|) = W'(r)/r, 0 outside the support: grad_i W_ij = f r_ij
  bool in;            // 0 < |r_ij| < 2h
};

// The running sums a body adds to: up to 12 sums and one maximum (reductions need named
// scalars; a body names the slots it uses, the others cost nothing).
struct PairSums {
  double &s0, &s1, &s2, &s3, &s4, &s5, &s6, &s7, &s8, &s9, &s10, &s11;
  double& max;
};

// Sweeps x_i against the first `len` entries of the position columns xj[0..D-1] and calls
// body(geometry, j, sums). sum[k] += slot k, vmax = max(vmax, the max slot).
template <int D, class Body>
inline void sweep_pairs(const WendlandC2<D>& kernel, const double xi[3], const double* const xj[3],
                        std::ptrdiff_t len, Body&& body, double (&sum)[12], double& vmax) {
  const double support2 = kernel.support2;
  const double *x0 = xj[0], *x1 = xj[1], *x2 = xj[D - 1];
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0, s6 = 0, s7 = 0, s8 = 0, s9 = 0, s10 = 0,
         s11 = 0, mx = -1e300;
#pragma omp simd reduction(+ : s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11) reduction(max : mx)
  for (std::ptrdiff_t j = 0; j < len; ++j) {
    PairGeometry g;
    g.rx = xi[0] - x0[j];
    g.ry = xi[1] - x1[j];
    g.rz = D == 3 ? xi[2] - x2[j] : 0.0;
    g.r2 = g.rx * g.rx + g.ry * g.ry + g.rz * g.rz;
    g.in = (g.r2 < support2) & (g.r2 > 0.0);  // `&`: both tests without a branch
    g.r = std::sqrt(g.r2);
    g.f = g.in ? kernel.f(g.r) : 0.0;
    g.w = g.in ? kernel.w(g.r) : 0.0;
    PairSums s{s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11, mx};
    body(g, j, s);
  }
  const double all[12] = {s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11};
  for (int k = 0; k < 12; ++k) sum[k] += all[k];
  vmax = std::max(vmax, mx);
}

}  // namespace vrsph
