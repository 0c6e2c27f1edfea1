// Surface pass 1's pair terms and sums (solver/surface_pass.cpp): the correction matrix M, grad C,
// div r, the Shepard sum and G of one particle, over its blocks or over other levels.
#pragma once

#include "vrsph/core/mat.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/surface_tension.hpp"
#include "vrsph/solver/cross_level.hpp"
#include "vrsph/solver/surface_block.hpp"

namespace vrsph::pass1 {

// Pass 1 of particle i over its block (columns x, V): M in s0..s2 (xx, xy, yy), grad C in s3, s4,
// div r in s5, the Shepard sum in s6, G = sum_j V_j |grad_i W_ij| in s7 (2D) or s11 (3D) and, in
// 3D only, M in s7..s9 (xz, yz, zz) and grad C in s10 (2D sums no zeros). G only with kGradW
// (surface tension on: pass 2 reads it; shifting alone does not).
template <int D, class T, bool kGradW>
struct Pass1Pair {
  using S = SurfaceColumns<D, 1, T>;
  static constexpr int kSums = (D == 3 ? 11 : 7) + (kGradW ? 1 : 0);
  PairSumsT<T> operator()(const PairGeometryT<T>& g, const Neighbour<S::K, T>& nb) const {
    PairSumsT<T> s;
    const T vol_j = nb[D];
    const T vf = vol_j * g.f;
    s.s0 = correction_matrix_pair(vf, g.rx, g.rx);
    s.s1 = correction_matrix_pair(vf, g.rx, g.ry);
    s.s2 = correction_matrix_pair(vf, g.ry, g.ry);
    s.s3 = colour_gradient_pair(vf, g.rx);
    s.s4 = colour_gradient_pair(vf, g.ry);
    s.s5 = position_divergence_pair(vf, g.r2);
    s.s6 = shepard_pair(vol_j, g.w);
    if constexpr (D == 3) {
      s.s7 = correction_matrix_pair(vf, g.rx, g.rz);
      s.s8 = correction_matrix_pair(vf, g.ry, g.rz);
      s.s9 = correction_matrix_pair(vf, g.rz, g.rz);
      s.s10 = colour_gradient_pair(vf, g.rz);
      if constexpr (kGradW) s.s11 = -vf * g.r;  // F <= 0: V_j |grad_i W_ij| = -V_j F r
    } else if constexpr (kGradW) {
      s.s7 = -vf * g.r;
    }
    return s;
  }
};

template <int D, class T, bool kGradW>
void pass1_particle(const SolverParams<D>& prm, const SurfaceColumns<D, 1, T>& src,
                    const StencilSpans<D>& sp, const T (&xi)[3], const T (&xi_lo)[3],
                    double (&sum)[12]) {
  using P = Pass1Pair<D, T, kGradW>;
  double unused = -1e300;
  sweep_spans<D, P::S::K, P::kSums, false, P::S::KL>(prm.kernel, xi, src.base, sp.span, sp.count,
                                                     P{}, sum, unused, xi_lo);
}

// Pass 1's sums of particle x over the levels of `sources` with `kernel` (solver/cross_level.hpp;
// walls: the own level's walls too); returns the number of neighbours.
template <int D, class T, bool kGradW>
std::size_t pass1_across(const std::vector<CrossSource<D>>& sources, const WendlandC2<D>& kernel,
                         const Vec<D>& x, bool walls, double (&sum)[12]) {
  using P = Pass1Pair<D, T, kGradW>;
  auto no_more = [](const CrossSource<D>&, std::uint32_t, Neighbour<P::S::K, T>&) {};
  return cross_sums<D, P::S::K, P::kSums, T>(sources, kernel, x, walls, no_more, P{}, sum);
}
template <int D, class T>
std::size_t pass1_across(bool grad_w, const std::vector<CrossSource<D>>& sources,
                         const WendlandC2<D>& kernel, const Vec<D>& x, bool walls,
                         double (&sum)[12]) {
  return grad_w ? pass1_across<D, T, true>(sources, kernel, x, walls, sum)
                : pass1_across<D, T, false>(sources, kernel, x, walls, sum);
}

// M_i and grad C_i from the pass-1 slots.
template <int D>
void assemble_pass1(const double (&s)[12], Mat<D>& m, Vec<D>& grad_c) {
  m(0, 0) = s[0], m(0, 1) = m(1, 0) = s[1], m(1, 1) = s[2];
  grad_c[0] = s[3], grad_c[1] = s[4];
  if constexpr (D == 3) {
    m(0, 2) = m(2, 0) = s[7], m(1, 2) = m(2, 1) = s[8], m(2, 2) = s[9];
    grad_c[2] = s[10];
  }
}

}  // namespace vrsph::pass1
