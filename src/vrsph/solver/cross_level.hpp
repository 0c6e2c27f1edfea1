// Surface fields across a resolution boundary (numerics.vres_surface_across_levels; issue #20,
// item 1; not part of Ricci et al. 2024, where each level sums over its own fluid and buffer).
// The fluid particles of all levels tile space once (a level's fluid region is what the others
// do not own), so the surface passes of a particle near an interface can sum over the real fluid
// particles of both levels: its own level's fluid (its buffer particles enter with volume 0) and
// the other level's fluid through a CrossSource, each neighbour with its own volume and the pair
// with the mean smoothing length h_ij = (h_i + h_j) / 2 (the kernel's support 2 h_ij). lambda, the
// normal and the curvature then come from one particle distribution on both sides of the face,
// so they are continuous across it by construction, and no buffer copy with a truncated support
// enters them. The pair terms are those of the level's own passes (solver/surface_pass.cpp),
// evaluated in the pass's arithmetic type from a geometry formed in double.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "vrsph/core/kernel.hpp"
#include "vrsph/core/vec.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"

namespace vrsph {

// Another level's fluid as neighbours of this level's particles during one force evaluation
// (set by the coupling before the passes; the pointers stay valid until the next sort).
template <int D>
struct CrossSource {
  const ParticleSet<D>* ps = nullptr;
  const CellGrid<D>* grid = nullptr;
  const std::vector<double>* lambda = nullptr;  // its lambda (its pass 1 runs before pass 2)
  const std::vector<Vec<D>>* normal = nullptr;  // its normals (its pass 2 before pass 3)
  WendlandC2<D> kernel;                         // of h_ij
};

// fn(j, g, V_j) for each fluid particle j of src with 0 < |x - x_j| < 2 h_ij, in a fixed order
// (the source grid's runs): the geometry of core/kernel.hpp in type T, W and F of h_ij.
template <int D, class T, class Fn>
void for_each_cross_pair(const CrossSource<D>& src, const Vec<D>& x, Fn&& fn) {
  const ParticleSet<D>& ps = *src.ps;
  const double support = 2.0 * src.kernel.h;
  src.grid->for_each_run_within(x, support, Group::fluid, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t j = b; j < e; ++j) {
      if (ps.kind[j] != Kind::fluid) continue;
      const Vec<D> r = x - ps.pos[j];
      const double r2 = norm2(r);
      if (!(r2 < src.kernel.support2) || r2 == 0.0) continue;
      const double rr = std::sqrt(r2);
      PairGeometryT<T> g;
      g.rx = static_cast<T>(r[0]);
      g.ry = static_cast<T>(r[1]);
      g.rz = D == 3 ? static_cast<T>(r[D - 1]) : T(0);
      g.r2 = static_cast<T>(r2);
      g.r = static_cast<T>(rr);
      g.w = static_cast<T>(src.kernel.w(rr));
      g.f = static_cast<T>(src.kernel.f(rr));
      g.in = T(1);
      fn(j, g, ps.mass[j] / ps.rho[j]);
    }
  });
}

// Adds the first NS slots of t to sum (in double, as the sweep's lanes are added).
template <int NS, class T>
void add_pair_slots(double (&sum)[12], const PairSumsT<T>& t) {
  const T v[12] = {t.s0, t.s1, t.s2, t.s3, t.s4, t.s5, t.s6, t.s7, t.s8, t.s9, t.s10, t.s11};
  for (int k = 0; k < NS; ++k) sum[k] += static_cast<double>(v[k]);
}

// Sums pair(g, nb) -> PairSums over the fluid of every source into sum's first NS slots, with
// nb[D] = V_j and nb[D + 1 ...] from load(source, j, nb). Returns the number of pairs.
template <int D, int K, int NS, class T, class Load, class Pair>
std::size_t cross_sums(const std::vector<CrossSource<D>>& sources, const Vec<D>& x, Load load,
                       Pair pair, double (&sum)[12]) {
  std::size_t pairs = 0;
  for (const CrossSource<D>& src : sources) {
    for_each_cross_pair<D, T>(src, x, [&](std::uint32_t j, const PairGeometryT<T>& g, double v) {
      Neighbour<K, T> nb{};
      nb.c[D] = static_cast<T>(v);
      load(src, j, nb);
      add_pair_slots<NS>(sum, pair(g, nb));
      ++pairs;
    });
  }
  return pairs;
}

}  // namespace vrsph
