// Uniform cell grid for neighbour search, DualSPHysics style: particles are counting-sorted by
// cell (x fastest, then y, then z) and every particle array is permuted together, so the
// neighbours of a particle lie in 2*reach+1 contiguous runs (one per row of cells) in 2D and
// (2*reach+1)^2 in 3D. The grid carries `reach` ghost cells on every side so stencils never
// need clipping. Cell size = 2h / cells_per_support (1: "full" cells, 2: "half" cells).
// Wall particles are sorted into a block of their own after the fluid (and buffer) block, as
// DualSPHysics does, so a pass can visit fluid and wall neighbours separately without a test
// per pair: for_each_run(c, Group::fluid, fn) and for_each_run(c, Group::wall, fn).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "vrsph/core/vec.hpp"
#include "vrsph/particles/key_sort.hpp"
#include "vrsph/particles/particles.hpp"

namespace vrsph {

// Cells of one row that share a candidate block in a grid built without further choice
// (CellGrid::block_width).
inline constexpr int kDefaultCellsPerBlock = 2;

// The cells a simulation uses unless told otherwise, by dimension, chosen by measurement
// (docs/validation.md, "Cells by dimension"): in 2D full cells (2h) whose blocks each hold one
// cell's stencil (3 runs per block, shared by about 7 particles at h = 1.3 dp); in 3D half cells
// (h) with blocks of two cells of a row (a full cell's 27-cell stencil holds 2.4 times the
// neighbours, against 1.6 for the half cells' block).
struct CellLayout {
  int cells_per_support = 0;  // cells per 2h (1 full, 2 half); 0: the dimension's default
  int cells_per_block = 0;    // cells of a row that share a block; 0: the dimension's default
};
template <int D>
constexpr CellLayout resolve_cell_layout(CellLayout asked) {
  const CellLayout def = D == 2 ? CellLayout{1, 1} : CellLayout{2, 2};
  if (asked.cells_per_support == 0) asked.cells_per_support = def.cells_per_support;
  if (asked.cells_per_block == 0) asked.cells_per_block = def.cells_per_block;
  return asked;
}

enum class Group : int { fluid = 0, wall = 1 };  // fluid group includes buffer particles

// The most cells a grid's domain may span (the cell table itself covers the occupied cells).
inline constexpr std::int64_t kMaxDomainCells = std::int64_t{1} << 40;

inline Group group_of(Kind k) { return k == Kind::wall ? Group::wall : Group::fluid; }

template <int D>
class CellGrid {
 public:
  CellGrid() = default;
  // domain_min/max bound the region particles may occupy; support = 2h. Cells are laid from
  // `origin` (default: domain_min), which may lie inside the domain: cells then extend below it.
  CellGrid(const Vec<D>& domain_min, const Vec<D>& domain_max, double support,
           int cells_per_support);
  CellGrid(const Vec<D>& domain_min, const Vec<D>& domain_max, double support,
           int cells_per_support, const Vec<D>& origin);

  bool inside(const Vec<D>& x) const;
  // For a query point anywhere (also beyond the particle cloud or the domain): the cell c whose
  // stencil (for_each_run) holds every particle within `reach` cells of x. False when no
  // particle can be that close. Valid after a sort.
  bool stencil_cell(const Vec<D>& x, std::int64_t& c) const;
  std::int64_t cell_of(const Vec<D>& x) const;  // linear index; x inside, after a sort

  // Sorts all particle arrays by cell (stable), after deleting particles outside the domain.
  // Returns the ids of the deleted particles. With step_copies false the step copies (pos0,
  // vel0, rho0) are dead, as after a single-level run's corrector (the next predictor writes
  // them): they are resized like the derived arrays, not gathered.
  std::vector<std::uint64_t> sort(ParticleSet<D>& ps, bool step_copies = true);
  // Reorders an array kept beside the particle arrays as the last sort reordered them (a per-
  // particle field that is not in the field list). An array not sized to the particles sorted
  // last is left alone. Instantiated for double and Vec<D>.
  template <class T>
  void carry(std::vector<T>& a);

  // Calls fn(begin, end) for each contiguous run of particles of group g in the stencil around
  // cell c (c from particle_cells(), i.e. without the group offset).
  template <class Fn>
  void for_each_run(std::int64_t c, Group g, Fn&& fn) const {
    auto run = [&](std::uint32_t b, std::uint32_t e, std::int64_t) { fn(b, e); };
    for_each_row(c, g, -reach_, reach_, run);
  }
  // fn(past) for each row of the stencil around cell c, in for_each_run's order: past, the first
  // particle of group g beyond the row's last cell of the table (the group's end for the table's
  // last row). The same for every cell of c's row of the table.
  template <class Fn>
  void for_each_row_end(std::int64_t c, Group g, Fn&& fn) const {
    const std::int64_t next_row = c - c % n_[0] + n_[0] - c;  // from c to the next row's start
    const std::int64_t base = static_cast<std::int64_t>(g) * ncell_total_ + next_row;
    for_each_stencil_row(c, [&](std::int64_t row) {  // for_each_row's order of rows
      fn(static_cast<std::uint32_t>(starts_[base + row]));
    });
  }
  // The first cell of c's row of the table.
  std::int64_t row_first(std::int64_t c) const { return c - c % n_[0]; }

  // Calls fn(begin, end) for runs of particles of group g that hold every particle within
  // `radius` of x, for any radius (also beyond the stencil's reach) and any x: the rows of cells
  // the box x +- radius overlaps, clipped to the table. Valid after a sort.
  template <class Fn>
  void for_each_run_within(const Vec<D>& x, double radius, Group g, Fn&& fn) const {
    std::int64_t a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      const double lo = (x[k] - radius - origin_[k]) * inv_cell_;
      const double hi = (x[k] + radius - origin_[k]) * inv_cell_;
      if (!(lo < 1e15 && hi > -1e15)) return;  // NaN or absurdly far
      a[k] = std::max<std::int64_t>(static_cast<std::int64_t>(std::floor(lo)) - lo_[k], 0);
      b[k] = std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(hi)) - lo_[k], n_[k] - 1);
      if (a[k] > b[k]) return;
    }
    const std::int64_t base = static_cast<std::int64_t>(g) * ncell_total_;
    for (std::int64_t z = a[2]; z <= b[2]; ++z) {
      for (std::int64_t y = a[1]; y <= b[1]; ++y) {
        const std::int64_t row = base + y * stride_[1] + z * stride_[2];
        fn(starts_[row + a[0]], starts_[row + b[0] + 1]);
      }
    }
  }

  // Blocks of `block_width` neighbouring cells of one row, over which pass 2's bound takes
  // lambda's range (solver/normal_bound.hpp): the block of cell c starts at block_first(c), and
  // for_each_block_run visits the runs of the union of the stencils of its cells, clipped to the
  // row (the cells clipped off are ghost cells, which hold no particle).
  int block_width() const { return block_width_; }
  void set_block_width(int w) { block_width_ = w < 1 ? 1 : w; }
  std::int64_t block_first(std::int64_t c) const { return c - (c % n_[0]) % block_width_; }
  template <class Fn>
  void for_each_block_run(std::int64_t c0, Group g, Fn&& fn) const {
    const auto [lo, hi] = block_row_span(c0);
    auto run = [&](std::uint32_t b, std::uint32_t e, std::int64_t) { fn(b, e); };
    for_each_row(c0, g, lo, hi, run);
  }

  // Per-cell reductions over a block's stencil (solver/normal_bound.hpp): the particles of
  // group g in cell c; the offsets [lo, hi] within c's row of the cells that block c0's runs
  // span (as for_each_block_run clips them); fn(cell) for the cell of c's column in each row of
  // its stencil (c + dy stride_y + dz stride_z).
  std::pair<std::uint32_t, std::uint32_t> cell_run(std::int64_t c, Group g) const {
    const std::int64_t k = c + static_cast<std::int64_t>(g) * ncell_total_;
    return {starts_[k], starts_[k + 1]};
  }
  std::pair<std::int64_t, std::int64_t> block_row_span(std::int64_t c0) const {
    const std::int64_t x0 = c0 % n_[0];
    return {std::max<std::int64_t>(x0 - reach_, 0) - x0,
            std::min<std::int64_t>(x0 + block_width_ - 1 + reach_, n_[0] - 1) - x0};
  }
  template <class Fn>
  void for_each_stencil_row(std::int64_t c, Fn&& fn) const {
    const int rz = D == 3 ? reach_ : 0;
    for (int dz = -rz; dz <= rz; ++dz)
      for (int dy = -reach_; dy <= reach_; ++dy) fn(c + dy * stride_[1] + dz * stride_[D - 1]);
  }

  // Whether the last sort found every particle in its cell and so left the arrays as they were.
  bool last_sort_skipped() const { return unmoved_; }
  // Cell of each particle after the last sort (same order as the particle arrays).
  const std::vector<std::uint32_t>& particle_cells() const { return pcell_; }
  std::int64_t cell_count() const { return ncell_total_; }
  // Index range of group g after the last sort: fluid first, then walls.
  std::uint32_t group_begin(Group g) const {
    return starts_[static_cast<std::size_t>(g) * ncell_total_];
  }
  std::uint32_t group_end(Group g) const {
    return starts_[(static_cast<std::size_t>(g) + 1) * ncell_total_];
  }
  double cell_size() const { return cell_size_; }
  std::int64_t row_length() const { return n_[0]; }  // cells of a row of the table
  int reach() const { return reach_; }
  const Vec<D>& domain_min() const { return min_; }
  const Vec<D>& domain_max() const { return max_; }

 private:
  // fn(begin, end, offset) for the cells c + offset + lo .. c + offset + hi of every row of the
  // stencil around cell c, offset the row's distance from c's row in cells.
  template <class Fn>
  void for_each_row(std::int64_t c, Group g, std::int64_t lo, std::int64_t hi, Fn& fn) const {
    c += static_cast<std::int64_t>(g) * ncell_total_;
    if constexpr (D == 2) {
      for (int dy = -reach_; dy <= reach_; ++dy) {
        const std::int64_t offset = dy * stride_[1], row = c + offset;
        fn(starts_[row + lo], starts_[row + hi + 1], offset);
      }
    } else {
      for (int dz = -reach_; dz <= reach_; ++dz) {
        for (int dy = -reach_; dy <= reach_; ++dy) {
          const std::int64_t offset = dy * stride_[1] + dz * stride_[2], row = c + offset;
          fn(starts_[row + lo], starts_[row + hi + 1], offset);
        }
      }
    }
  }

  std::uint32_t key(std::int64_t cell, Kind k) const;
  // Absolute cell coordinate of x along axis k (floor: also below the origin).
  std::int64_t cell_coord(const Vec<D>& x, int k) const {
    const double a = (x[k] - origin_[k]) * inv_cell_;
    return static_cast<std::int64_t>(a >= 0.0 ? a : std::floor(a));
  }
  // The table cells of x[0..count) (cell_of) into out, in a loop the compiler vectorises: exact
  // for positions inside the table (every particle inside the domain after fit_to), clamped to
  // it for the others (which then land in a ghost cell, where no particle was sorted).
  void table_cells(const Vec<D>* __restrict x, std::size_t count,
                   std::uint32_t* __restrict out) const;
  void fit_to(const ParticleSet<D>& ps);
  // Whether every particle of ps is still in the cell the last sort gave it (none created or
  // deleted since). Then the occupied cells, and so the table fit_to would lay, are the same too.
  bool unmoved_since_sort(const ParticleSet<D>& ps) const;

  Vec<D> min_{}, max_{};
  Vec<D> origin_{};  // where cell 0 starts
  double cell_size_ = 0.0;
  double inv_cell_ = 0.0;
  int reach_ = 1;
  int block_width_ = kDefaultCellsPerBlock;
  std::array<std::int64_t, 3> lo_{0, 0, 0};      // absolute cell coordinate of table cell 0
  std::array<std::int64_t, 3> n_{1, 1, 1};       // cells per axis, ghosts included
  std::array<std::int64_t, 3> stride_{1, 1, 1};  // linear index strides
  std::int64_t ncell_total_ = 0;
  KeyStarts starts_;                  // starts_[k]..starts_[k+1]: particles of key k = c + g*ncells
  std::vector<std::uint32_t> pcell_;  // cell of each particle, then (during a sort) its key
  std::vector<std::uint32_t> perm_;
  std::size_t sorted_count_ = 0;  // particles before the last sort (what carry() accepts)
  bool unmoved_ = false;          // the last sort found every particle in its cell: no permutation
  std::vector<std::uint32_t> dropped_;
  KeySort keysort_;
  // Gather targets (spare_for): of the sort and of carry(), for the vector and double arrays.
  // The sort swaps in the storage of the derived arrays acc and drho; it gathers the id and kind
  // arrays through the double spare's storage and copies them back (no spare of their own).
  std::vector<Vec<D>> spare_vec_;
  std::vector<double> spare_f64_;
  std::vector<Vec<D>>& spare_for(const std::vector<Vec<D>>&) { return spare_vec_; }
  std::vector<double>& spare_for(const std::vector<double>&) { return spare_f64_; }
};

}  // namespace vrsph
