// Candidate columns read in place: one copy of every column a pass reads, for all particles in
// the grid's sorted order (particle i at index i), swept run by run (exec/sweep.hpp,
// sweep_spans). It replaces copying each cell's candidates into a padded block
// (the former candidate blocks), which cost about 3 pair evaluations per candidate copied and
// a fifth of a 2D run (docs/validation.md, "Candidates read in place").
//
// A run [b, e) of a stencil is swept as the span [b, b + ceil8(e - b)) so that it fills whole
// sweep lanes. The up to kBlockPad - 1 candidates read past its end either lie further along the
// run's row, beyond the stencil's box of cells and so at least one support away, or are masked
// out (stencil_spans). kBlockPad dummies after the last particle keep the reads inside the
// columns.
//
// Positions are stored relative to one fixed frame (the grid's domain corner). With T = float
// each coordinate is two floats, x - origin = hi + lo: r_ij = (hi_i - hi_j) + (lo_i - lo_j) keeps
// a double difference's accuracy until its final rounding (float hi alone left errors of about
// 6e-7 r, which biased the pressure sums: docs/validation.md).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "vrsph/core/vec.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/particles/cell_grid.hpp"

namespace vrsph {

// Columns hold this many entries past the last particle, and spans are multiples of it.
inline constexpr std::size_t kBlockPad = 8;
static_assert(kBlockPad % kSweepLanes == 0, "spans must fill whole sweep lanes");
// Coordinate of the entries past the last particle: outside the support of every real particle.
inline constexpr double kFarAway = 1e15;

// Which groups of the grid a pass reads: the fluid group (fluid and buffer), walls, or both.
enum class Groups : int { fluid = 1, wall = 2, all = 3 };

// K columns of type T: 0..D-1 the positions (their high parts with T = float, whose low parts
// are the last D columns, kLo..K-1), the rest whatever the pass reads.
template <int K, int D, class T>
struct RunColumns {
  static_assert(K <= 16, "a sweep reads at most 16 columns");
  static constexpr bool kSplit = !std::is_same_v<T, double>;
  static constexpr int kLo = kSplit ? K - D : -1;  // first low-part column (-1: none)

  std::array<std::vector<T>, K> col;
  const T* base[16] = {};  // where each column starts (an absent column aliases another)
  double origin[3] = {0.0, 0.0, 0.0};
  std::uint32_t count = 0;  // particles (dummies excluded)

  // Sizes the columns to the grid's particles after a sort and writes the dummies: positions
  // kFarAway, every other column 0. absent[k]: column k is not stored; it reads column alias[k].
  void lay_out(const CellGrid<D>& grid, const std::array<bool, K>& absent = {},
               const std::array<int, K>& alias = {}) {
    count = grid.group_end(Group::wall);
    for (int k = 0; k < D; ++k) origin[k] = grid.domain_min()[k];
    for (int k = 0; k < K; ++k) {
      if (absent[k]) {
        std::vector<T>().swap(col[k]);
        continue;
      }
      col[k].resize(count + kBlockPad);
      const T v = k < D ? static_cast<T>(kFarAway) : T(0);
      std::fill(col[k].begin() + count, col[k].end(), v);
    }
    for (int k = 0; k < K; ++k) base[k] = col[absent[k] ? alias[k] : k].data();
  }

  // Writes the positions of particles a..b-1 from x, relative to the origin (hi + lo with T =
  // float), one axis at a time so that the loop vectorises.
  void put_positions(const Vec<D>* __restrict x, std::size_t a, std::size_t b) {
    for (int k = 0; k < D; ++k) {
      T* __restrict hi = col[k].data();
      T* __restrict lo = kSplit ? col[kLo + k].data() : nullptr;
      const double o = origin[k];
      for (std::size_t q = a; q < b; ++q) {
        const double rel = x[q][k] - o;
        const T h = static_cast<T>(rel);
        hi[q] = h;
        if constexpr (kSplit) lo[q] = static_cast<T>(rel - static_cast<double>(h));
      }
    }
  }

  // x_i in the columns' frame: hi[k] + lo[k] (lo = 0 with T = double).
  void self(std::uint32_t q, T (&hi)[3], T (&lo)[3]) const {
    for (int k = 0; k < 3; ++k) hi[k] = lo[k] = T(0);
    for (int k = 0; k < D; ++k) {
      hi[k] = col[k][q];
      if constexpr (kSplit) lo[k] = col[kLo + k][q];
    }
  }
};

// The most spans a stencil has: (2 reach + 1)^(D - 1) rows, reach <= 4 (cells per support).
template <int D>
inline constexpr int kMaxSpans = D == 2 ? 9 : 81;

// The first particle past each row of the stencils of one row of the table's cells, in group g
// (CellGrid::for_each_row_end): the same for every cell of that row, so kept while consecutive
// cells stay in it. Reading it from the cell table's starts where a row changes replaces a read
// of the particle cells per run, which missed the cache (docs/validation.md).
template <int D>
struct RowEnds {
  std::int64_t first = -1, last = -2;  // the table row's cells they hold for
  std::uint32_t past[kMaxSpans<D>] = {};
  void of(const CellGrid<D>& grid, std::int64_t c, Group g) {
    if (c >= first && c <= last) return;
    first = grid.row_first(c), last = first + grid.row_length() - 1;
    int r = 0;
    grid.for_each_row_end(c, g, [&](std::uint32_t p) { past[r++] = p; });
  }
};

// The spans of cell c's stencil in group g (CellGrid::for_each_run); returns their number
// (empty runs are left out). `spans` holds kMaxSpans<D> entries; `ends` the rows' ends of group
// g. A span whose candidates read past its run all lie further along the run's row of cells
// (beyond the stencil's box, so their kernel terms are zero) counts every candidate it reads
// (valid = len): no mask. The others, whose reads reach the next row or the group's end, are
// masked to the run.
template <int D>
int stencil_spans(const CellGrid<D>& grid, std::int64_t c, Group g, RowEnds<D>& ends, Span* spans) {
  ends.of(grid, c, g);
  int n = 0, r = 0;
  grid.for_each_run(c, g, [&](std::uint32_t b, std::uint32_t e) {
    const std::uint32_t past = ends.past[r++];  // particles in [e, past) lie in the run's row
    if (e <= b) return;
    constexpr auto P = static_cast<std::uint32_t>(kBlockPad);
    const std::uint32_t len = (e - b + P - 1) / P * P, last = b + len - 1;
    spans[n++] = {static_cast<std::ptrdiff_t>(b), static_cast<std::ptrdiff_t>(len),
                  static_cast<std::ptrdiff_t>(last < past ? len : e - b)};
  });
  return n;
}

// The spans of the stencil of the cell last asked for, in the groups asked for (consecutive
// particles share their cell).
template <int D>
struct StencilSpans {
  std::int64_t cell = -1;
  Groups groups = Groups::fluid;
  int count = 0;
  Span span[2 * kMaxSpans<D>];
  RowEnds<D> fluid_ends, wall_ends;
  void of(const CellGrid<D>& grid, std::int64_t c, Groups g) {
    if (c == cell && g == groups) return;
    cell = c, groups = g, count = 0;
    if (static_cast<int>(g) & static_cast<int>(Groups::fluid))
      count += stencil_spans(grid, c, Group::fluid, fluid_ends, span + count);
    if (static_cast<int>(g) & static_cast<int>(Groups::wall))
      count += stencil_spans(grid, c, Group::wall, wall_ends, span + count);
  }
};

}  // namespace vrsph
