// The execution layer's vector loop: one particle i against its candidates, spans of columns read
// in place (particles/run_columns.hpp). For each candidate j it forms the pair geometry of
// core/kernel.hpp (r_ij, |r_ij|, W, F with grad_i W_ij = F r_ij, both zero outside the support and
// for j = i) and hands it to the pass's body, which returns its pair terms. The loop has no
// branch: candidates that do not interact get zero kernel values, so it vectorises on AVX2 and
// AVX-512 alike. Sums run in fixed lanes, so their order depends on nothing but the spans.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "vrsph/core/kernel.hpp"

namespace vrsph {

// The sweep runs in the arithmetic type T of its block's columns: double, or float in the mixed
// precision (core/precision.hpp), where the block's positions are relative to its origin.

// Pair (i, j) seen from i. rz = 0 in 2D.
template <class T>
struct PairGeometryT {
  T rx, ry, rz;  // r_ij = r_i - r_j
  T r2, r;       // |r_ij|^2, |r_ij|
  T w;           // W(|r_ij|), 0 outside the support
  T f;           // F(|r_ij|) = W'(r)/r, 0 outside the support: grad_i W_ij = f r_ij
  T in;          // 1 when 0 < |r_ij| < 2h, else 0 (a T, not a bool: a byte-sized member would
                 // set the vector width of the whole loop)
};
using PairGeometry = PairGeometryT<double>;

// The terms of one pair that a body returns: up to 12 sums and one maximum, zero (and -1e300)
// when the body starts. The sweep adds them to its reductions; a body names the slots it uses,
// the others cost nothing.
template <class T>
struct PairSumsT {
  T s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0, s6 = 0, s7 = 0, s8 = 0, s9 = 0, s10 = 0,
    s11 = 0;
  T max = lowest();
  static constexpr T lowest() { return sizeof(T) == sizeof(double) ? T(-1e300) : T(-1e38); }
};
using PairSums = PairSumsT<double>;

// Slot K of a body's terms, for bodies that place a group of terms at an offset.
template <int K, class T>
[[gnu::always_inline]] inline T& slot(PairSumsT<T>& s) {
  static_assert(K >= 0 && K < 12, "12 slots");
  if constexpr (K == 0)
    return s.s0;
  else if constexpr (K == 1)
    return s.s1;
  else if constexpr (K == 2)
    return s.s2;
  else if constexpr (K == 3)
    return s.s3;
  else if constexpr (K == 4)
    return s.s4;
  else if constexpr (K == 5)
    return s.s5;
  else if constexpr (K == 6)
    return s.s6;
  else if constexpr (K == 7)
    return s.s7;
  else if constexpr (K == 8)
    return s.s8;
  else if constexpr (K == 9)
    return s.s9;
  else if constexpr (K == 10)
    return s.s10;
  else
    return s.s11;
}

// Candidate j's columns, read by the sweep and handed to the body as values.
template <int K, class T = double>
struct Neighbour {
  T c[K];
  T operator[](int k) const { return c[k]; }
};

// Candidate j's columns, one load per column written out (a loop over k here could stay a loop
// inside the vectorised one).
template <int K, class T>
[[gnu::always_inline]] inline Neighbour<K, T> load_neighbour(const T* const (&col)[16],
                                                             std::ptrdiff_t j) {
  Neighbour<K, T> nb;
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
  if constexpr (K > 12) nb.c[12] = col[12][j];
  if constexpr (K > 13) nb.c[13] = col[13][j];
  if constexpr (K > 14) nb.c[14] = col[14][j];
  if constexpr (K > 15) nb.c[15] = col[15][j];
  return nb;
}

// Adds the first NS slots of t into lane l of the sums.
template <int NS, int L, class T>
[[gnu::always_inline]] inline void add_to_lane(T (&acc)[NS > 0 ? NS : 1][L], int l,
                                               const PairSumsT<T>& t) {
  if constexpr (NS > 0) acc[0][l] += t.s0;
  if constexpr (NS > 1) acc[1][l] += t.s1;
  if constexpr (NS > 2) acc[2][l] += t.s2;
  if constexpr (NS > 3) acc[3][l] += t.s3;
  if constexpr (NS > 4) acc[4][l] += t.s4;
  if constexpr (NS > 5) acc[5][l] += t.s5;
  if constexpr (NS > 6) acc[6][l] += t.s6;
  if constexpr (NS > 7) acc[7][l] += t.s7;
  if constexpr (NS > 8) acc[8][l] += t.s8;
  if constexpr (NS > 9) acc[9][l] += t.s9;
  if constexpr (NS > 10) acc[10][l] += t.s10;
  if constexpr (NS > 11) acc[11][l] += t.s11;
}

// Lanes of the sweep: candidate j adds into lane j % kSweepLanes of every sum, and the lanes are
// added in order at the end. The order of every sum is fixed by this constant, not by the vector
// width, so AVX2, AVX-512 and scalar builds give the same bits. Spans are multiples of it
// (particles/run_columns.hpp).
inline constexpr int kSweepLanes = 8;

// One chunk of kSweepLanes candidates from j0: x_i against candidate j in lane j - j0, its
// pair's terms added into the lanes acc / mx. KL >= 0: columns KL..KL+D-1 hold the low parts of
// the positions (x = hi + lo, float columns), and xl those of x_i; r_ij = (hi_i - hi_j) + (lo_i -
// lo_j). kMasked: only candidates j < valid count; the others (read past a run's end) are
// treated as outside the support whatever their positions.
// The loop over lanes has no dependence between iterations, no reduction and no branch, so the
// compiler vectorises it as it is (no `omp simd`): GCC 12 turned an `omp simd` reduction loop
// around a pass's lambda into scalar code on AVX2 (docs/validation.md, "Vectorisation of the
// passes"). The body reads values (the neighbour's columns and what its closure captured by
// value) and returns its terms by value.
template <int D, int K, int NS, bool kMax, int KL, bool kMasked, class T, class Body>
[[gnu::always_inline]] inline void sweep_chunk(const WendlandC2<D>& kernel, const T (&xi)[3],
                                               const T (&xl)[3], const T* const (&col)[16],
                                               std::ptrdiff_t j0, std::ptrdiff_t valid, Body& body,
                                               T (&acc)[NS > 0 ? NS : 1][kSweepLanes],
                                               T (&mx)[kSweepLanes]) {
  const T support2 = T(kernel.support2);
  for (int l = 0; l < kSweepLanes; ++l) {
    const std::ptrdiff_t j = j0 + l;
    const Neighbour<K, T> nb = load_neighbour<K, T>(col, j);
    PairGeometryT<T> g;
    g.rx = xi[0] - nb.c[0];
    g.ry = xi[1] - nb.c[1];
    g.rz = D == 3 ? xi[2] - nb.c[D - 1] : T(0);
    if constexpr (KL >= 0) {
      g.rx += xl[0] - nb.c[KL];
      g.ry += xl[1] - nb.c[KL + 1];
      if constexpr (D == 3) g.rz += xl[2] - nb.c[KL + D - 1];
    }
    g.r2 = g.rx * g.rx + g.ry * g.ry + g.rz * g.rz;
    bool in = (g.r2 < support2) & (g.r2 > T(0));  // `&`: both tests without a branch
    // in 32 bits, the lanes' width in float (a 64-bit compare split the vectors)
    if constexpr (kMasked) in = in & (l < static_cast<int>(valid - j0));
    g.in = in ? T(1) : T(0);
    g.r = std::sqrt(g.r2);
    // Both kernel values are evaluated for every candidate (finite even for the far dummies)
    // and then selected, so no operation sits under a condition.
    const T f = kernel.f(g.r), w = kernel.w(g.r);
    g.f = in ? f : T(0);
    g.w = in ? w : T(0);
    const PairSumsT<T> t = body(g, nb);
    add_to_lane<NS>(acc, l, t);
    if constexpr (kMax) mx[l] = mx[l] < t.max ? t.max : mx[l];
  }
}

// The lane loop shared by the sweeps: `len` candidates (a multiple of kSweepLanes) whose columns
// start at col[k], in chunks (sweep_chunk). kMask: only the first `valid` count.
template <int D, int K, int NS, bool kMax, int KL, bool kMask, class T, class Body>
[[gnu::always_inline]] inline void sweep_lanes(const WendlandC2<D>& kernel, const T (&xi)[3],
                                               const T (&xl)[3], const T* const (&col)[16],
                                               std::ptrdiff_t len, std::ptrdiff_t valid, Body& body,
                                               T (&acc)[NS > 0 ? NS : 1][kSweepLanes],
                                               T (&mx)[kSweepLanes]) {
  for (std::ptrdiff_t j0 = 0; j0 < len; j0 += kSweepLanes)
    sweep_chunk<D, K, NS, kMax, KL, kMask>(kernel, xi, xl, col, j0, valid, body, acc, mx);
}

// Adds the lanes in order: sum[k] += the total of slot k (formed in double), vmax = max(vmax,
// lanes' max) when kMax.
template <int NS, bool kMax, class T>
[[gnu::always_inline]] inline void reduce_lanes(const T (&acc)[NS > 0 ? NS : 1][kSweepLanes],
                                                const T (&mx)[kSweepLanes], double (&sum)[12],
                                                double& vmax) {
  for (int k = 0; k < NS; ++k) {
    double s = 0.0;
    for (int l = 0; l < kSweepLanes; ++l) s += acc[k][l];
    sum[k] += s;
  }
  if constexpr (kMax) {
    for (int l = 0; l < kSweepLanes; ++l) vmax = std::max(vmax, static_cast<double>(mx[l]));
  }
}

// A stretch of candidates read in place: columns from index `begin`, `len` (a multiple of
// kSweepLanes) of them read, of which the first `valid` count.
struct Span {
  std::ptrdiff_t begin = 0, len = 0, valid = 0;
};

// Sweeps x_i against the candidates of `count` spans of columns read in place (cols[k] + begin,
// particles/run_columns.hpp), columns 0..D-1 the positions, each span masked to its valid
// candidates, and calls body(geometry, neighbour) -> PairSums for each. sum[k] += slot k for the
// first NS slots; vmax = max(vmax, max) when kMax. xi_in: x_i in the columns' frame; KL >= 0:
// the low parts of the positions (sweep_chunk), xi_lo_in those of x_i. The lanes run on across
// the spans: candidate j of a span adds into lane j % kSweepLanes, and the lanes are added once
// at the end, in T, their total formed in double.
template <int D, int K, int NS, bool kMax, int KL = -1, class T, class Body>
[[gnu::always_inline]] inline void sweep_spans(const WendlandC2<D>& kernel_in, const T xi_in[3],
                                               const T* const (&cols)[16], const Span* spans,
                                               int count, Body body, double (&sum)[12],
                                               double& vmax, const T* xi_lo_in = nullptr) {
  static_assert(K <= 16 && NS <= 12, "sweep_spans reads at most 16 columns into 12 sums");
  if (count == 0) return;
  const WendlandC2<D> kernel = kernel_in;
  const T xi[3] = {xi_in[0], xi_in[1], D == 3 ? xi_in[D - 1] : T(0)};
  T xl[3] = {T(0), T(0), T(0)};
  if constexpr (KL >= 0) {
    for (int k = 0; k < D; ++k) xl[k] = xi_lo_in[k];
  }
  T acc[NS > 0 ? NS : 1][kSweepLanes] = {};
  T mx[kSweepLanes];
  for (int l = 0; l < kSweepLanes; ++l) mx[l] = PairSumsT<T>::lowest();
  for (int s = 0; s < count; ++s) {
    const T* col[16] = {};
    for (int k = 0; k < K; ++k) col[k] = cols[k] + spans[s].begin;
    if (spans[s].valid == spans[s].len)  // most spans: what they read past their run is far
      sweep_lanes<D, K, NS, kMax, KL, false>(kernel, xi, xl, col, spans[s].len, spans[s].len, body,
                                             acc, mx);
    else
      sweep_lanes<D, K, NS, kMax, KL, true>(kernel, xi, xl, col, spans[s].len, spans[s].valid, body,
                                            acc, mx);
  }
  reduce_lanes<NS, kMax>(acc, mx, sum, vmax);
}

}  // namespace vrsph
