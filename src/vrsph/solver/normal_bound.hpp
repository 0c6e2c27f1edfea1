// The bound that lets surface pass 2 skip particles whose normal is sure to vanish.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "vrsph/core/mat.hpp"
#include "vrsph/particles/cell_grid.hpp"

namespace vrsph {

// Pass 2 without its sweep where no normal can come out. In the difference form (lambda_ref =
// lambda_i) each term of sum_j (lambda_j - lambda_ref) V_j grad_i W_ij is at most
// Delta_i V_j |grad_i W_ij| long, Delta_i = max_j |lambda_j - lambda_ref| over the candidates of
// i's block (a superset of its neighbours; the float values the sweep reads), so
// |L_i grad lambda_i| <= |L_i|_F Delta_i G_i, G_i from pass 1 (over a superset of pass 2's
// neighbours). Below eps lambda_i / h the normal is zero (normal_from_lambda_gradient). The 1%
// margin covers the rounding of the sums (about 100 terms: 1e-5 in float), so a skip gives
// exactly the zero normal the sweep would. The candidates' lambda range is read once per block,
// from the level's lambda column through the block's runs, before any gather: a block none of
// whose particles needs its sweep is never gathered.
template <class T, class Block>
struct NormalsScratch {
  Block blk;
  std::int64_t range_of = -1;  // the block whose candidates lo and hi span
  T lo = 0, hi = 0;
};

// Sets sc.lo, sc.hi to the range of lambda over the fluid candidates of the block of `cell`,
// unless sc already holds that block's.
template <int D, class T, class Block>
void lambda_range(const CellGrid<D>& grid, std::int64_t cell, const T* lambda,
                  NormalsScratch<T, Block>& sc) {
  const std::int64_t b = grid.block_first(cell);
  if (b == sc.range_of) return;
  sc.range_of = b;
  T lo = std::numeric_limits<T>::max(), hi = std::numeric_limits<T>::lowest();
  grid.for_each_block_run(b, Group::fluid, [&](std::uint32_t s, std::uint32_t e) {
    for (std::uint32_t j = s; j < e; ++j)
      lo = std::min(lo, lambda[j]), hi = std::max(hi, lambda[j]);
  });
  sc.lo = lo, sc.hi = hi;
}

// True when |L|_F max(hi - lambda_ref, lambda_ref - lo) G, with the margin, is below limit.
template <int D, class T>
bool normal_surely_zero(T lo, T hi, T lambda_ref, const Mat<D>& l, double grad_w, double limit) {
  double l2 = 0.0;
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) l2 += l(r, c) * l(r, c);
  const double spread =
      std::max({double(hi) - double(lambda_ref), double(lambda_ref) - double(lo), 0.0});
  return 1.01 * std::sqrt(l2) * spread * grad_w < limit;
}

}  // namespace vrsph
