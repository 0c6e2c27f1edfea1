// The bound that lets surface pass 2 skip particles whose normal is sure to vanish.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "vrsph/core/mat.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/cell_grid.hpp"

namespace vrsph {

// Pass 2 without its sweep where no normal can come out. In the difference form (lambda_ref =
// lambda_i) each term of sum_j (lambda_j - lambda_ref) V_j grad_i W_ij is at most
// Delta_i V_j |grad_i W_ij| long, Delta_i = max_j |lambda_j - lambda_ref| over the candidates of
// i's block (a superset of its neighbours; the float values the sweep reads), so
// |L_i grad lambda_i| <= |L_i|_F Delta_i G_i, G_i from pass 1 (over a superset of pass 2's
// neighbours). Below eps lambda_i / h the normal is zero (normal_from_lambda_gradient). The 1%
// margin covers the rounding of the sums (about 100 terms: 1e-5 in float), so a skip gives
// exactly the zero normal the sweep would. The candidates' lambda range is read before any
// gather, so a block none of whose particles needs its sweep is never gathered. It is formed in
// two stages per pass (BlockRanges): each cell's range, then for each block's first cell the
// range over the cells of its row that the block spans; a block's range is then the extreme of
// its 2 reach + 1 rows (2D; squared in 3D). One running min and max over the block's some 50
// candidates was a chain of dependent instructions that cost a third of the normals pass.
template <class Spans>
struct NormalsScratch {
  Spans spans;
  std::int64_t range_of = -1;  // the block whose candidates lo and hi span
  double lo = 0, hi = 0;
};

// Ranges of a per-particle value over the fluid group: per cell, and per block's first cell over
// the cells of its row that the block spans (CellGrid::block_row_span). Empty: (max, lowest).
// Held in double: exact for float values too.
struct BlockRanges {
  std::vector<double> cell_lo, cell_hi, row_lo, row_hi;

  template <int D, class T>
  void build(const CellGrid<D>& grid, const T* v) {
    const auto n = static_cast<std::size_t>(grid.cell_count());
    cell_lo.resize(n), cell_hi.resize(n), row_lo.resize(n), row_hi.resize(n);
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t c) {
      double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
      const auto [b, e] = grid.cell_run(c, Group::fluid);
      for (std::uint32_t j = b; j < e; ++j)
        lo = std::min(lo, double(v[j])), hi = std::max(hi, double(v[j]));
      cell_lo[c] = lo, cell_hi[c] = hi;
    });
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t c) {
      if (grid.block_first(c) != c) return;
      double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
      const auto [a, b] = grid.block_row_span(c);
      for (std::int64_t k = c + a; k <= c + b; ++k)
        lo = std::min(lo, cell_lo[k]), hi = std::max(hi, cell_hi[k]);
      row_lo[c] = lo, row_hi[c] = hi;
    });
  }
};

// Sets sc.lo, sc.hi to the range of the value of r over the fluid candidates of the block of
// `cell`, unless sc already holds that block's.
template <int D, class Spans>
void lambda_range(const CellGrid<D>& grid, std::int64_t cell, const BlockRanges& r,
                  NormalsScratch<Spans>& sc) {
  const std::int64_t b = grid.block_first(cell);
  if (b == sc.range_of) return;
  sc.range_of = b;
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  grid.for_each_stencil_row(
      b, [&](std::int64_t c) { lo = std::min(lo, r.row_lo[c]), hi = std::max(hi, r.row_hi[c]); });
  sc.lo = lo, sc.hi = hi;
}

// True when |L|_F max(hi - lambda_ref, lambda_ref - lo) G, with the margin, is below limit.
template <int D, class T>
bool normal_surely_zero(double lo, double hi, T lambda_ref, const Mat<D>& l, double grad_w,
                        double limit) {
  double l2 = 0.0;
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) l2 += l(r, c) * l(r, c);
  const double spread = std::max({hi - double(lambda_ref), double(lambda_ref) - lo, 0.0});
  return 1.01 * std::sqrt(l2) * spread * grad_w < limit;
}

}  // namespace vrsph
