// Surface pass 1's sums (solver/surface_pass.cpp) of one particle, over its blocks or over other
// levels: the terms of solver/pass1_terms.hpp.
#pragma once

#include "vrsph/exec/sweep.hpp"
#include "vrsph/solver/cross_level.hpp"
#include "vrsph/solver/pass1_terms.hpp"
#include "vrsph/solver/surface_block.hpp"

namespace vrsph::pass1 {

// Pass 1 of particle i over its block (columns x, V): the terms of solver/pass1_terms.hpp in its
// slot layout, G only with kGradW (surface tension on: pass 2 reads it; shifting alone does not).
template <int D, class T, bool kGradW>
struct Pass1Pair {
  using S = SurfaceColumns<D, 1, T>;
  static constexpr int kSums = kPass1Terms<D, kGradW>;
  PairSumsT<T> operator()(const PairGeometryT<T>& g, const Neighbour<S::K, T>& nb) const {
    PairSumsT<T> s;
    set_pass1_terms<D, kSums, 0>(g, nb[D], s);
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

}  // namespace vrsph::pass1
