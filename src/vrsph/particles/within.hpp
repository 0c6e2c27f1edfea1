// The particles of one group of a cell's stencil that lie within a distance of a point, for the
// passes that visit a few points each (buffer values, buffer spacing, the room for a new
// particle) rather than every particle against its stencil (solver/, with packed columns).
#pragma once

#include <algorithm>
#include <cstdint>

#include "vrsph/core/vec.hpp"
#include "vrsph/particles/cell_grid.hpp"

namespace vrsph {

// The particles of one group of a cell's stencil within reach of x, listed in pieces of at most
// kWithinPiece indices in index order: fn(kept, n) for each piece. The indices within reach are
// listed without a branch, then handed over. About two thirds of a 2D stencil's candidates lie
// beyond a kernel support, in no pattern a branch predictor could learn: one test-and-branch per
// candidate cost more than the sums of the candidates kept.
inline constexpr std::uint32_t kWithinPiece = 64;

template <int D, class Pos, class Fn>
inline void for_each_within_piece(const CellGrid<D>& grid, std::int64_t c, Group g, const Vec<D>& x,
                                  double reach2, Pos&& pos, Fn&& fn) {
  std::uint32_t kept[kWithinPiece];
  grid.for_each_run(c, g, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t b = begin; b < end; b += kWithinPiece) {
      const std::uint32_t e = std::min(end, b + kWithinPiece);
      std::uint32_t n = 0;
      for (std::uint32_t j = b; j < e; ++j) {
        kept[n] = j;
        n += norm2(x - pos(j)) < reach2 ? 1u : 0u;
      }
      if (n > 0) fn(static_cast<const std::uint32_t*>(kept), n);
    }
  });
}

// Calls fn(j, r, r2), r = x - pos(j), for the particles j of group g in the stencil of cell c
// that lie within reach (r2 < reach2), in index order.
template <int D, class Pos, class Fn>
inline void for_each_within(const CellGrid<D>& grid, std::int64_t c, Group g, const Vec<D>& x,
                            double reach2, Pos&& pos, Fn&& fn) {
  for_each_within_piece(grid, c, g, x, reach2, pos,
                        [&](const std::uint32_t* kept, std::uint32_t n) {
                          for (std::uint32_t k = 0; k < n; ++k) {
                            const std::uint32_t j = kept[k];
                            const Vec<D> r = x - pos(j);
                            fn(j, r, norm2(r));
                          }
                        });
}

}  // namespace vrsph
