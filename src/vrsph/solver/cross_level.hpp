// Surface fields across a resolution boundary (numerics.vres_surface_across_levels; issue #20,
// item 1; not part of Ricci et al. 2024, where each level sums over its own fluid and buffer).
// The fluid particles of all levels tile space once (a level's fluid region is what the others
// do not own), so the surface passes of a particle near an interface can sum over the real fluid
// particles of both levels: its own level's fluid (its buffer particles enter with volume 0) and
// the other level's fluid through a CrossSource, each neighbour with its own volume. lambda, the
// normal and the curvature then come from one particle distribution on both sides of the face,
// so they are continuous across it by construction, and no buffer copy with a truncated support
// enters them. The pair terms are those of the level's own passes (solver/surface_pass.cpp),
// evaluated in the pass's arithmetic type from a geometry formed in double.
// Kernels: each particle sums with one smoothing length over all its neighbours (a gather
// kernel, set by vres/level_coupling.cpp: the coarse h near the face for the finer level's
// particles, blended to its own h further in); a pair kernel of (h_i + h_j) / 2 was measured to
// bias lambda near the face twice as much (tests/test_vres_across.cpp).
// Measured on the VR drop (docs/validation.md, issue #20): worse than the buffer-based fields,
// because nothing keeps the union of the two levels' particles regular at the face (each
// level's pressure sees its own buffer, not the other level's particles), and the union's
// irregularity gives interior particles lambda gradients, normals and capillary forces.
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

// A level's fluid as neighbours during one force evaluation (set by the coupling before the
// passes; the pointers stay valid until the next sort): another level's, or the particle's own
// level's where its kernel is wider than the level's blocks reach (`own`: walls count too in
// pass 1, as in the level's own blocks).
template <int D>
struct CrossSource {
  const ParticleSet<D>* ps = nullptr;
  const CellGrid<D>* grid = nullptr;
  const std::vector<double>* lambda = nullptr;  // its lambda (its pass 1 runs before pass 2)
  const std::vector<Vec<D>>* normal = nullptr;  // its normals (its pass 2 before pass 3)
  bool own = false;
};

// fn(j, g, V_j) for each fluid particle j of src (and, with walls, each wall particle) with
// 0 < |x - x_j| < 2h of `kernel`, in a fixed order (the source grid's runs): the geometry of
// core/kernel.hpp in type T.
template <int D, class T, class Fn>
void for_each_cross_pair(const CrossSource<D>& src, const WendlandC2<D>& kernel, const Vec<D>& x,
                         bool walls, Fn&& fn) {
  const ParticleSet<D>& ps = *src.ps;
  const double support = 2.0 * kernel.h;
  auto visit = [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t j = b; j < e; ++j) {
      if (ps.kind[j] == Kind::buffer) continue;
      const Vec<D> r = x - ps.pos[j];
      const double r2 = norm2(r);
      if (!(r2 < kernel.support2) || r2 == 0.0) continue;
      const double rr = std::sqrt(r2);
      PairGeometryT<T> g;
      g.rx = static_cast<T>(r[0]);
      g.ry = static_cast<T>(r[1]);
      g.rz = D == 3 ? static_cast<T>(r[D - 1]) : T(0);
      g.r2 = static_cast<T>(r2);
      g.r = static_cast<T>(rr);
      g.w = static_cast<T>(kernel.w(rr));
      g.f = static_cast<T>(kernel.f(rr));
      g.in = T(1);
      fn(j, g, ps.mass_of(j) / ps.rho[j]);
    }
  };
  src.grid->for_each_run_within(x, support, Group::fluid, visit);
  if (walls && src.own) src.grid->for_each_run_within(x, support, Group::wall, visit);
}

// Adds the first NS slots of t to sum (in double, as the sweep's lanes are added).
template <int NS, class T>
void add_pair_slots(double (&sum)[12], const PairSumsT<T>& t) {
  const T v[12] = {t.s0, t.s1, t.s2, t.s3, t.s4, t.s5, t.s6, t.s7, t.s8, t.s9, t.s10, t.s11};
  for (int k = 0; k < NS; ++k) sum[k] += static_cast<double>(v[k]);
}

// Sums pair(g, nb) -> PairSums over the fluid (walls: and the own level's walls) of every
// source into sum's first NS slots, with the pair kernel `kernel`, nb[D] = V_j and nb[D + 1 ...]
// from load(source, j, nb). Returns the number of pairs.
template <int D, int K, int NS, class T, class Load, class Pair>
std::size_t cross_sums(const std::vector<CrossSource<D>>& sources, const WendlandC2<D>& kernel,
                       const Vec<D>& x, bool walls, Load load, Pair pair, double (&sum)[12]) {
  std::size_t pairs = 0;
  for (const CrossSource<D>& src : sources) {
    auto add = [&](std::uint32_t j, const PairGeometryT<T>& g, double v) {
      Neighbour<K, T> nb{};
      nb.c[D] = static_cast<T>(v);
      load(src, j, nb);
      add_pair_slots<NS>(sum, pair(g, nb));
      ++pairs;
    };
    for_each_cross_pair<D, T>(src, kernel, x, walls, add);
  }
  return pairs;
}

// The other level's lambda and normal of neighbour j of a cross-level sum. A source whose field
// is not sized to its particles (its pass has not run yet: the first evaluation with local time
// stepping) counts as interior: lambda 1, normal 0.
template <int D, int K, class T>
void load_lambda(const CrossSource<D>& c, std::uint32_t j, Neighbour<K, T>& nb) {
  const std::vector<double>& l = *c.lambda;
  nb.c[D + 1] = static_cast<T>(l.size() == c.ps->size() ? l[j] : 1.0);
}
template <int D, int K, class T>
void load_normal(const CrossSource<D>& c, std::uint32_t j, Neighbour<K, T>& nb) {
  const std::vector<Vec<D>>& n = *c.normal;
  for (int k = 0; k < D; ++k)
    nb.c[D + 1 + k] = static_cast<T>(n.size() == c.ps->size() ? n[j][k] : 0.0);
}

}  // namespace vrsph
