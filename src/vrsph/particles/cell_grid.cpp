#include "vrsph/particles/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vrsph {

template <int D>
CellGrid<D>::CellGrid(const Vec<D>& domain_min, const Vec<D>& domain_max, double support,
                      int cells_per_support)
    : min_(domain_min), max_(domain_max), reach_(cells_per_support) {
  cell_size_ = support / cells_per_support;
  inv_cell_ = 1.0 / cell_size_;
  ncell_total_ = 1;
  for (int k = 0; k < D; ++k) {
    const double extent = max_[k] - min_[k];
    if (!(extent > 0.0)) throw std::invalid_argument("cell grid: empty domain");
    n_[k] = static_cast<std::int64_t>(std::ceil(extent * inv_cell_)) + 2 * reach_ + 1;
    ncell_total_ *= n_[k];
  }
  if (ncell_total_ > (std::int64_t{1} << 31)) {
    throw std::invalid_argument("cell grid: domain too large for its cell size (over 2^31 cells)");
  }
}

// Lays the cell table over the cells the particles occupy now (plus `reach` ghost cells), so
// the table, and the cost of clearing and scanning it, follows the particles, not the domain.
template <int D>
void CellGrid<D>::fit_to(const ParticleSet<D>& ps) {
  std::array<std::int64_t, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int k = 0; k < D; ++k) {
    lo[k] = std::numeric_limits<std::int64_t>::max();
    hi[k] = std::numeric_limits<std::int64_t>::min();
  }
  std::int64_t lo0 = lo[0], lo1 = lo[1], lo2 = lo[2], hi0 = hi[0], hi1 = hi[1], hi2 = hi[2];
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static) reduction(min : lo0, lo1, lo2) reduction(max : hi0, hi1, hi2)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto& x = ps.pos[i];
    if (!inside(x)) continue;
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int k = 0; k < D; ++k) c[k] = static_cast<std::int64_t>((x[k] - min_[k]) * inv_cell_);
    lo0 = std::min(lo0, c[0]), hi0 = std::max(hi0, c[0]);
    lo1 = std::min(lo1, c[1]), hi1 = std::max(hi1, c[1]);
    lo2 = std::min(lo2, c[2]), hi2 = std::max(hi2, c[2]);
  }
  lo = {lo0, lo1, lo2};
  hi = {hi0, hi1, hi2};
  ncell_total_ = 1;
  for (int k = 0; k < D; ++k) {
    if (hi[k] < lo[k]) lo[k] = hi[k] = 0;  // no particle inside
    lo_[k] = lo[k] - reach_;
    n_[k] = hi[k] - lo[k] + 1 + 2 * reach_;
    ncell_total_ *= n_[k];
  }
  stride_ = {1, n_[0], n_[0] * n_[1]};
  begin_.assign(2 * static_cast<std::size_t>(ncell_total_) + 1, 0);
}

template <int D>
bool CellGrid<D>::inside(const Vec<D>& x) const {
  for (int k = 0; k < D; ++k) {
    if (!(x[k] >= min_[k] && x[k] <= max_[k])) return false;  // NaN counts as outside
  }
  return true;
}

template <int D>
std::int64_t CellGrid<D>::cell_of(const Vec<D>& x) const {
  std::int64_t c = 0;
  for (int k = 0; k < D; ++k) {
    const auto ck = static_cast<std::int64_t>((x[k] - min_[k]) * inv_cell_) - lo_[k];
    c += ck * stride_[k];
  }
  return c;
}

template <int D>
bool CellGrid<D>::stencil_cell(const Vec<D>& x, std::int64_t& c) const {
  c = 0;
  for (int k = 0; k < D; ++k) {
    const double a = std::floor((x[k] - min_[k]) * inv_cell_);
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
// Gathers a through perm into scratch. Called inside a parallel region: the loop is shared
// among the threads, and the caller swaps a and scratch after the region's barrier.
template <class T>
void permute_into(const std::vector<T>& a, const std::vector<std::uint32_t>& perm,
                  std::vector<T>& scratch) {
  const auto n = static_cast<std::int64_t>(perm.size());
#pragma omp for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) scratch[i] = a[perm[i]];
}
}  // namespace

template <int D>
std::size_t CellGrid<D>::key(std::int64_t cell, Kind k) const {
  return static_cast<std::size_t>(cell + static_cast<std::int64_t>(group_of(k)) * ncell_total_);
}

template <int D>
std::vector<std::uint64_t> CellGrid<D>::sort(ParticleSet<D>& ps) {
  const std::size_t n = ps.size();
  std::vector<std::uint64_t> lost;
  pcell_.resize(n);
  fit_to(ps);
  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < ni; ++i) {
    pcell_[i] = inside(ps.pos[i]) ? static_cast<std::int64_t>(key(cell_of(ps.pos[i]), ps.kind[i])) : -1;
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {  // histogram (serial: cheap, and no atomics)
    if (pcell_[i] < 0) {
      lost.push_back(ps.id[i]);
      continue;
    }
    ++begin_[static_cast<std::size_t>(pcell_[i])];
    ++kept;
  }
  // Inclusive prefix sum: begin_[k] = end of key k; the reverse scatter below walks it back to
  // the start of key k, keeping particles of a cell in their previous relative order (stable).
  for (std::size_t k = 1; k < begin_.size(); ++k) begin_[k] += begin_[k - 1];
  perm_.resize(kept);
  for (std::size_t i = n; i-- > 0;) {
    if (pcell_[i] < 0) continue;
    perm_[--begin_[static_cast<std::size_t>(pcell_[i])]] = static_cast<std::uint32_t>(i);
  }
  // One parallel region gathers every carried array of the field list through the
  // permutation into its twin in scratch_; after the swap scratch_ holds the previous storage,
  // so nothing is allocated once the sizes have settled. Every thread walks the same list, so
  // the work-shared loops line up.
  using PS = ParticleSet<D>;
  PS::zip_fields([kept](std::string_view, FieldRole role, auto&, auto& s) {
    if (carried(role)) s.resize(kept);
  }, ps, scratch_);
  cell_scratch_.resize(kept);
#pragma omp parallel
  {
    PS::zip_fields([this](std::string_view, FieldRole role, const auto& a, auto& s) {
      if (carried(role)) permute_into(a, perm_, s);
    }, ps, scratch_);
    permute_into(pcell_, perm_, cell_scratch_);
  }
  // Derived fields (p, acc, drho) are recomputed after every sort: only resized.
  PS::zip_fields([kept](std::string_view, FieldRole role, auto& a, auto& s) {
    if (carried(role)) a.swap(s);
    else a.resize(kept);
  }, ps, scratch_);
  pcell_.swap(cell_scratch_);
  // pcell_ held sort keys; particle_cells() gives cells, without the wall group's offset.
  const auto wall_begin = static_cast<std::int64_t>(group_begin(Group::wall));
  const auto n_kept = static_cast<std::int64_t>(kept);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = wall_begin; i < n_kept; ++i) pcell_[i] -= ncell_total_;
  return lost;
}

template class CellGrid<2>;
template class CellGrid<3>;

}  // namespace vrsph
