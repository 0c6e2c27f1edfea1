#include "vrsph/particles/cell_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "vrsph/exec/parallel.hpp"

namespace vrsph {

template <int D>
CellGrid<D>::CellGrid(const Vec<D>& domain_min, const Vec<D>& domain_max, double support,
                      int cells_per_support)
    : CellGrid(domain_min, domain_max, support, cells_per_support, domain_min) {}

template <int D>
CellGrid<D>::CellGrid(const Vec<D>& domain_min, const Vec<D>& domain_max, double support,
                      int cells_per_support, const Vec<D>& origin)
    : min_(domain_min), max_(domain_max), origin_(origin), reach_(cells_per_support) {
  cell_size_ = support / cells_per_support;
  inv_cell_ = 1.0 / cell_size_;
  ncell_total_ = 1;
  for (int k = 0; k < D; ++k) {
    const double extent = max_[k] - min_[k];
    if (!(extent > 0.0)) throw std::invalid_argument("cell grid: empty domain");
    const double cells = std::ceil(extent * inv_cell_) + 2 * reach_ + 1;
    if (!(cells <= static_cast<double>(kMaxDomainCells)))
      throw std::invalid_argument(
          "cell grid: domain too large for its cell size (over 2^40 cells)");
    n_[k] = static_cast<std::int64_t>(cells);
    ncell_total_ *= n_[k];
  }
  // The table is laid over the occupied cells only (fit_to), so the domain may hold many more;
  // sim/preflight.cpp refuses a case beyond this bound before it is filled.
  if (!(ncell_total_ <= kMaxDomainCells)) {
    throw std::invalid_argument("cell grid: domain too large for its cell size (over 2^40 cells)");
  }
}

namespace {
// The extent of the particles inside the domain, merged over threads: minima and maxima of each
// coordinate, the same for any thread count. NaN coordinates count as outside.
struct Extent {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  std::array<double, 3> lo{kInf, kInf, kInf};
  std::array<double, 3> hi{-kInf, -kInf, -kInf};
  void merge(const Extent& o) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], o.lo[k]), hi[k] = std::max(hi[k], o.hi[k]);
  }
};
struct NoScratch {};
// Particles per range of fit_to's loop and of the sort's cell loops.
constexpr std::int64_t kExtentRange = 4096;
constexpr std::int64_t kCellRange = 2048;
}  // namespace

// Lays the cell table over the cells the particles occupy now (plus `reach` ghost cells), so
// the table, and the cost of clearing and scanning it, follows the particles, not the domain.
// A cell coordinate is a non-decreasing function of the position (cell_coord), so the occupied
// cells run from the cell of the smallest coordinate to that of the largest: one vectorised
// minimum and maximum over the positions instead of a cell per particle.
template <int D>
void CellGrid<D>::fit_to(const ParticleSet<D>& ps) {
  const auto n = static_cast<std::int64_t>(ps.size());
  const Extent e = exec::for_each_gather<NoScratch, Extent>(
      (n + kExtentRange - 1) / kExtentRange, 1, [&](std::int64_t r, NoScratch&, Extent& acc) {
        const Vec<D>* __restrict x = ps.pos.data();
        // kLanes running extents, lane l taking every kLanes-th particle: element-wise selects
        // that vectorise (a single running minimum is a reduction, which stays scalar)
        constexpr int kLanes = 8;
        double lo[D][kLanes], hi[D][kLanes];
        for (int k = 0; k < D; ++k) {
          for (int l = 0; l < kLanes; ++l) lo[k][l] = Extent::kInf, hi[k][l] = -Extent::kInf;
        }
        const std::int64_t first = r * kExtentRange, end = std::min(n, first + kExtentRange);
        auto take = [&](std::int64_t q, int l) {
          const bool in = inside(x[q]);
          for (int k = 0; k < D; ++k) {
            lo[k][l] = in & (x[q][k] < lo[k][l]) ? x[q][k] : lo[k][l];
            hi[k][l] = in & (x[q][k] > hi[k][l]) ? x[q][k] : hi[k][l];
          }
        };
        std::int64_t q0 = first;
        for (; q0 + kLanes <= end; q0 += kLanes) {
          for (int l = 0; l < kLanes; ++l) take(q0 + l, l);
        }
        for (std::int64_t q = q0; q < end; ++q) take(q, static_cast<int>(q - q0));
        Extent mine;
        for (int k = 0; k < D; ++k) {
          mine.lo[k] = *std::min_element(lo[k], lo[k] + kLanes);
          mine.hi[k] = *std::max_element(hi[k], hi[k] + kLanes);
        }
        acc.merge(mine);
      });
  const bool any = e.lo[0] <= e.hi[0];
  std::array<std::int64_t, 3> lo{0, 0, 0}, hi{0, 0, 0};  // axes beyond D stay at 0
  for (int k = 0; k < D && any; ++k) {
    Vec<D> x_lo, x_hi;
    x_lo[k] = e.lo[k], x_hi[k] = e.hi[k];
    lo[k] = cell_coord(x_lo, k), hi[k] = cell_coord(x_hi, k);
  }
  ncell_total_ = 1;
  for (int k = 0; k < D; ++k) {
    if (hi[k] < lo[k]) lo[k] = hi[k] = 0;  // no particle inside
    lo_[k] = lo[k] - reach_;
    n_[k] = hi[k] - lo[k] + 1 + 2 * reach_;
    ncell_total_ *= n_[k];
  }
  // Keys and particle cells are 32-bit (the key kDropped excluded): a table this large would
  // take 32 GB.
  if (2 * ncell_total_ >= std::int64_t{KeySort::kDropped}) {
    throw std::runtime_error(fmt::format(
        "cell grid: the particles span {} cells of {:g} m, more than the 2^31 a cell table holds",
        ncell_total_, cell_size_));
  }
  stride_ = {1, n_[0], n_[0] * n_[1]};
}

// cell_of for a range: floor(a) - lo_k is exact in double (two integers below 2^53), equal to the
// truncation cell_coord takes for a >= 0, and clamped to the table before it becomes an integer.
template <int D>
void CellGrid<D>::table_cells(const Vec<D>* __restrict x, std::size_t count,
                              std::uint32_t* __restrict out) const {
  double o[D], lo[D], top[D];
  std::uint32_t stride[D];
  for (int k = 0; k < D; ++k) {
    o[k] = origin_[k], lo[k] = static_cast<double>(lo_[k]);
    top[k] = static_cast<double>(n_[k] - 1);
    stride[k] = static_cast<std::uint32_t>(stride_[k]);  // the table holds under 2^31 cells
  }
  const double inv = inv_cell_;
  for (std::size_t q = 0; q < count; ++q) {
    std::uint32_t c = 0;
    for (int k = 0; k < D; ++k) {
      double t = std::floor((x[q][k] - o[k]) * inv) - lo[k];
      t = std::min(std::max(t, 0.0), top[k]);
      c += static_cast<std::uint32_t>(static_cast<std::int32_t>(t)) * stride[k];
    }
    out[q] = c;
  }
}

template <int D>
bool CellGrid<D>::inside(const Vec<D>& x) const {
  bool in = true;  // `&`, no early return: the loops over particles that call it vectorise
  for (int k = 0; k < D; ++k) in = in & (x[k] >= min_[k]) & (x[k] <= max_[k]);  // NaN: outside
  return in;
}

template <int D>
std::int64_t CellGrid<D>::cell_of(const Vec<D>& x) const {
  std::int64_t c = 0;
  for (int k = 0; k < D; ++k) {
    const std::int64_t ck = cell_coord(x, k) - lo_[k];
    c += ck * stride_[k];
  }
  return c;
}

template <int D>
bool CellGrid<D>::stencil_cell(const Vec<D>& x, std::int64_t& c) const {
  c = 0;
  for (int k = 0; k < D; ++k) {
    const double a = std::floor((x[k] - origin_[k]) * inv_cell_);
    if (!(a > -1e15 && a < 1e15)) return false;  // NaN or absurdly far
    const std::int64_t t = static_cast<std::int64_t>(a) - lo_[k];
    if (t < 0 || t >= n_[k]) return false;  // more than `reach` cells from every particle
    // occupied cells lie in [reach, n - 1 - reach]: the clamped stencil still covers those
    // within reach of t
    c += std::clamp<std::int64_t>(t, reach_, n_[k] - 1 - reach_) * stride_[k];
  }
  return true;
}

namespace {
// Gathers a through perm into scratch (the caller swaps them afterwards).
template <class T>
void permute_into(const std::vector<T>& a, const std::vector<std::uint32_t>& perm,
                  std::vector<T>& scratch) {
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(perm.size()),
                 [&](std::int64_t i) { scratch[i] = a[perm[i]]; });
}

// Gathers a through perm in place, by way of the storage of `room` (at least as many bytes):
// element by element into room's bytes, then back into a. Saves a spare array of T.
template <class T>
void permute_through(std::vector<T>& a, const std::vector<std::uint32_t>& perm,
                     std::vector<double>& room) {
  static_assert(std::is_trivially_copyable_v<T> && sizeof(T) <= sizeof(double));
  const std::size_t n = perm.size();
  if (room.size() < n) room.resize(n);
  auto* bytes = reinterpret_cast<unsigned char*>(room.data());
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(n), [&](std::int64_t i) {
    std::memcpy(bytes + static_cast<std::size_t>(i) * sizeof(T), &a[perm[i]], sizeof(T));
  });
  a.resize(n);
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(n), [&](std::int64_t i) {
    std::memcpy(&a[i], bytes + static_cast<std::size_t>(i) * sizeof(T), sizeof(T));
  });
}
}  // namespace

template <int D>
std::uint32_t CellGrid<D>::key(std::int64_t cell, Kind k) const {
  return static_cast<std::uint32_t>(cell + static_cast<std::int64_t>(group_of(k)) * ncell_total_);
}

template <int D>
bool CellGrid<D>::unmoved_since_sort(const ParticleSet<D>& ps) const {
  if (ps.size() == 0 || pcell_.size() != ps.size()) return false;
  // The wall group's runs start where the fluid group's end: a particle in the other group's
  // part of the table (particles created and deleted in equal numbers since the sort shift the
  // indices) is not where the table puts it, even where its cell is.
  const std::int64_t walls_from = starts_[static_cast<std::size_t>(ncell_total_)];
  // A particle off the table gets a ghost cell from table_cells, never the cell it was sorted in.
  const auto n = static_cast<std::int64_t>(ps.size());
  return !exec::any_of((n + kCellRange - 1) / kCellRange, 1, [&](std::int64_t r) {
    const std::int64_t a = r * kCellRange, b = std::min(n, a + kCellRange);
    std::uint32_t cell[kCellRange];
    table_cells(ps.pos.data() + a, static_cast<std::size_t>(b - a), cell);
    bool moved = false;
    for (std::int64_t i = a; i < b; ++i) {
      const bool group_moved = (ps.kind[i] == Kind::wall) != (i >= walls_from);
      moved = moved | group_moved | !inside(ps.pos[i]) | (cell[i - a] != pcell_[i]);
    }
    return moved;
  });
}

// A particle's key is its cell and its group (fluid and buffer particles share one; nobody changes
// group between sorts), so where no particle left its cell the table fit_to would lay is the same
// and the stable sort would be the identity: both are skipped, and carry() has nothing to do. A
// drop at rest moves a particle across a cell boundary only every few steps.
template <int D>
std::vector<std::uint64_t> CellGrid<D>::sort(ParticleSet<D>& ps, bool step_copies) {
  const std::size_t n = ps.size();
  sorted_count_ = n;
  unmoved_ = unmoved_since_sort(ps);
  if (unmoved_) return {};
  fit_to(ps);
  std::vector<std::uint64_t> lost;
  pcell_.resize(n);
  exec::for_each_range(
      static_cast<std::int64_t>(n), kCellRange, [&](std::int64_t a, std::int64_t b) {
        table_cells(ps.pos.data() + a, b - a, pcell_.data() + a);
        for (std::int64_t i = a; i < b; ++i)
          pcell_[i] = inside(ps.pos[i]) ? key(pcell_[i], ps.kind[i]) : KeySort::kDropped;
      });
  keysort_.sort(pcell_, 2 * static_cast<std::size_t>(ncell_total_), starts_, perm_, dropped_);
  for (std::uint32_t i : dropped_) lost.push_back(ps.id[i]);
  const std::size_t kept = perm_.size();
  // Every carried array of the field list is gathered through the permutation into a spare
  // array of its element type, and the two swap: the spare then holds the array's previous
  // storage, ready for the next array of that type. The spares of the vector and double arrays
  // are the storage of the derived arrays acc and drho, which every sort leaves to be
  // recomputed; the id and kind arrays are gathered through the double spare's storage and
  // copied back (permute_through), so they need no spare of their own (9 B per particle).
  using PS = ParticleSet<D>;
  spare_vec_.swap(ps.acc);  // lent for the sort; carry()'s spares wait in acc and drho meanwhile
  spare_f64_.swap(ps.drho);
  const auto gathered = [step_copies](FieldRole role) {
    return carried(role) && (step_copies || role != FieldRole::step_copy);
  };
  PS::zip_fields(
      [&](std::string_view, FieldRole role, auto& a) {
        if (!gathered(role)) return;  // derived fields (acc, drho), dead copies: resized below
        using T = typename std::decay_t<decltype(a)>::value_type;
        if constexpr (std::is_same_v<T, std::uint64_t> || std::is_same_v<T, Kind>) {
          permute_through(a, perm_, spare_f64_);  // ids and kinds
        } else {
          auto& spare = spare_for(a);
          spare.resize(kept);
          permute_into(a, perm_, spare);
          a.swap(spare);
        }
      },
      ps);
  spare_vec_.swap(ps.acc);  // acc and drho take the storage the gathers left over
  spare_f64_.swap(ps.drho);
  PS::zip_fields(
      [&](std::string_view, FieldRole role, auto& a) {
        if (!gathered(role)) a.resize(kept);  // recomputed (rewritten) before they are read
      },
      ps);
  // The cell of each particle in its new place, from its position (the same function that gave
  // its key: no gather of the keys through the permutation).
  pcell_.resize(kept);
  exec::for_each_range(static_cast<std::int64_t>(kept), kCellRange,
                       [&](std::int64_t a, std::int64_t b) {
                         table_cells(ps.pos.data() + a, b - a, pcell_.data() + a);
                       });
  return lost;
}

template <int D>
template <class T>
void CellGrid<D>::carry(std::vector<T>& a) {
  if (unmoved_ || a.size() != sorted_count_) return;
  auto& spare = spare_for(a);
  spare.resize(perm_.size());
  permute_into(a, perm_, spare);
  a.swap(spare);
}

template class CellGrid<2>;
template class CellGrid<3>;
template void CellGrid<2>::carry(std::vector<double>&);
template void CellGrid<2>::carry(std::vector<Vec<2>>&);
template void CellGrid<3>::carry(std::vector<double>&);
template void CellGrid<3>::carry(std::vector<Vec<3>>&);

}  // namespace vrsph
