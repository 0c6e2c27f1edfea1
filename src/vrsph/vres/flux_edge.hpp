// Option numerics.vres_flux_edge (not part of Ricci et al. 2024; off by default): where a level's
// face crosses a free surface, the mass points near the surface accumulate the donor's flux
// weighted by its smoothed fill f = sum_j V_j W, which falls from 1 to 0 over about one support
// round the donor's surface. The mass is right, but the outer points then create particles at a
// fraction f of the rate, so the buffer's outer rows are sparse and the level's surface forms
// inside its own equilibrium radius (a third of the fine dp on the 2D VR drop, with a curvature
// step of +13% / -8% in the first rows that pumps a translating drop's n = 2 mode:
// docs/validation.md, "Where the translating drop's oscillation gets its energy").
// With edge e > 0, a point whose fill is below e passes its flux increment to the neighbour of
// highest fill on its face (repeated while that neighbour is still below e), so that particles
// are created only inside the e contour, at the full rate; the sum of the increments is unchanged.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "vrsph/vres/region.hpp"

namespace vrsph {

// Neighbours of each mass point on its face: the other points with the same normal within 1.5 dp
// (the face lattice's nearest and diagonal neighbours), found through a hash of dp-sized cells.
template <int D>
std::vector<std::vector<std::uint32_t>> mass_point_neighbours(const std::vector<MassPoint<D>>& pts,
                                                              double dp) {
  auto cell_of = [dp](const Vec<D>& x, int k) { return std::int64_t(std::floor(x[k] / dp)); };
  auto key = [](const std::int64_t(&c)[3]) {
    return (c[0] * 1000003 + c[1]) * 1000033 + c[2];  // distinct for the few cells a face holds
  };
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells;
  for (std::uint32_t q = 0; q < pts.size(); ++q) {
    std::int64_t c[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) c[k] = cell_of(pts[q].x, k);
    cells[key(c)].push_back(q);
  }
  const double reach2 = 2.25 * dp * dp;
  std::vector<std::vector<std::uint32_t>> nb(pts.size());
  for (std::uint32_t q = 0; q < pts.size(); ++q) {
    std::int64_t c0[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) c0[k] = cell_of(pts[q].x, k);
    const int span_z = D == 3 ? 2 : 0;
    for (int dz = -span_z; dz <= span_z; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const std::int64_t c[3] = {c0[0] + dx, c0[1] + dy, c0[2] + dz};
          const auto it = cells.find(key(c));
          if (it == cells.end()) continue;
          for (std::uint32_t p : it->second)
            if (p != q && norm2(pts[p].x - pts[q].x) < reach2 && dot(pts[p].n, pts[q].n) > 0.99)
              nb[q].push_back(p);
        }
  }
  return nb;
}

// dm[q]: the flux increment of point q this step; fill[q]: its donor fill, negative where the
// point does not accumulate. Moves the increment of every point with 0 <= fill < edge to the end
// of its walk up the fill (at most kFluxEdgeHops steps to the neighbour of highest fill, while that
// is higher than the current one and the current one is below edge). Points in index order, into
// a copy, so the result does not depend on the threads.
inline constexpr int kFluxEdgeHops = 8;
inline void move_flux_inward(std::vector<double>& dm, const std::vector<double>& fill,
                             const std::vector<std::vector<std::uint32_t>>& nb, double edge) {
  if (nb.size() != dm.size() || fill.size() != dm.size())
    throw std::logic_error("move_flux_inward: the points' neighbours were not formed");
  std::vector<double> out = dm;
  for (std::size_t q = 0; q < dm.size(); ++q) {
    if (fill[q] < 0.0 || fill[q] >= edge) continue;
    std::size_t at = q;
    for (int hop = 0; hop < kFluxEdgeHops && fill[at] < edge; ++hop) {
      std::size_t best = at;
      for (std::uint32_t p : nb[at])
        if (fill[p] > fill[best]) best = p;
      if (best == at) break;
      at = best;
    }
    if (at == q) continue;
    out[at] += dm[q];
    out[q] -= dm[q];
  }
  dm = std::move(out);
}

}  // namespace vrsph
