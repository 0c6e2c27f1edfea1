// Candidate neighbours of one cell, for the vector loops of every neighbour pass. The particles
// of the cell stencil's runs (CellGrid::for_each_run) are copied, column by column, into one
// contiguous block padded to a multiple of kBlockPad with inert dummies, so that each particle of
// the cell sweeps a single unit-stride loop with no remainder. All particles of a cell share the
// block (particles are sorted by cell, so consecutive particles reuse it): the copy is amortised.
// Columns 0..D-1 hold the positions, read from the particle set's own position array (no packed
// copy of it); the rest are whatever the pass reads (velocity, density, volume, lambda, normal,
// ...), each with the value its dummies take.
// The columns hold the pass's arithmetic type T. With T = float (mixed precision) the positions
// are stored relative to the block's origin, one of its candidates, each as two floats: the
// last D columns hold the low parts, x - origin = hi + lo, so that r_ij = (hi_i - hi_j) +
// (lo_i - lo_j) keeps the accuracy of a double difference until its final rounding (float hi
// alone left errors of about 6e-7 r, which biased the pressure sums: docs/validation.md).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "vrsph/core/vec.hpp"
#include "vrsph/particles/cell_grid.hpp"

namespace vrsph {

inline constexpr std::size_t kBlockPad = 8;
// Dummy coordinate: outside the support of every real particle, so every kernel term is zero.
inline constexpr double kFarAway = 1e15;

// Which groups of the grid a block takes: the fluid group (fluid and buffer), walls, or both.
enum class Groups : int { fluid = 1, wall = 2, all = 3 };

template <int K, class T = double>
struct CandidateBlock {
  static constexpr bool kRelative = !std::is_same_v<T, double>;
  std::array<std::vector<T>, K> col;
  double origin[3] = {0.0, 0.0, 0.0};  // position columns hold x - origin (0 for T = double)
  std::size_t len = 0;                 // padded length
  std::int64_t cell = -1;              // first cell of the block gathered (-1: none yet)
  std::int64_t requested = -1;         // the cell last asked for, which maps to `cell`
  Groups groups = Groups::fluid;

  // Gathers the positions x and the columns src[k], k >= D (each of the grid's particle count;
  // src[k < D] is not read) of the particles in the stencil of cell c, unless the block already
  // holds that cell and groups. pad[k]: the value of column k on the dummies. With T = float the
  // non-position columns come from the float sources rest[k] instead of src. A null source
  // leaves its column unset: the pass does not read it.
  template <int D>
  void gather(const Vec<D>* x, const std::array<const double*, K>& src,
              const std::array<double, K>& pad, const CellGrid<D>& grid, std::int64_t c, Groups g,
              const std::array<const T*, K>* rest = nullptr) {
    if (c == requested && g == groups) return;  // consecutive particles share their cell
    requested = c;
    c = grid.block_first(c);
    if (c == cell && g == groups) return;
    cell = c;
    groups = g;
    std::size_t n = 0, runs = 0;
    [[maybe_unused]] bool first = true;
    for_each_group_run(grid, c, g, [&](std::uint32_t b, std::uint32_t e) {
      if constexpr (kRelative) {
        if (first && e > b) {  // the origin: the first candidate (the runs' order is fixed)
          for (int k = 0; k < D; ++k) origin[k] = x[b][k];
          first = false;
        }
      }
      n += e - b;
      ++runs;
    });
    len = (n + kBlockPad - 1) / kBlockPad * kBlockPad;
    const std::size_t room = n + runs * kBlockPad;  // each run may overshoot by a chunk
    if (col[0].size() < room) {
      for (auto& v : col) v.resize(room);
    }
    const std::size_t src_size = grid.group_end(Group::wall);
    std::size_t at = 0;
    for_each_group_run(grid, c, g, [&](std::uint32_t b, std::uint32_t e) {
      copy_run<D>(x, src, rest, b, e, src_size, at);
      at += e - b;
    });
    for (int k = 0; k < K; ++k)
      std::fill(col[k].begin() + at, col[k].begin() + len, static_cast<T>(pad[k]));
  }

  // x_i in the block's frame, as hi + lo (lo = 0 for T = double).
  void frame(const double x[3], T hi[3], T lo[3]) const {
    for (int k = 0; k < 3; ++k) {
      const double rel = x[k] - origin[k];
      // Through memory: GCC 12 (-O3) otherwise took double(float(rel)) for rel here, which
      // made lo 0 and put x_i off its own entry in the block.
      volatile T h = static_cast<T>(rel);
      hi[k] = h;
      lo[k] = static_cast<T>(rel - static_cast<double>(hi[k]));
    }
  }

 private:
  // Copies column k of particles [b, e) to col[k] at `at`. Runs are short (a few cells), so a
  // call of memmove per run and column would cost more than the copy: whole chunks of kBlockPad
  // values are copied with fixed-size moves instead, overshooting the run's end by less than a
  // chunk (the next run or the padding overwrites it). Only a run whose last chunk would read
  // past the source arrays is copied element by element. The positions are read across the
  // particle set's array of vectors (with T = float converted on the way, minus the origin);
  // with T = float the rest is copied from the float sources.
  template <int D>
  void copy_run(const Vec<D>* x, const std::array<const double*, K>& src,
                const std::array<const T*, K>* rest, std::size_t b, std::size_t e,
                std::size_t src_size, std::size_t at) {
    constexpr std::size_t P = kBlockPad;
    const std::size_t chunks = (e - b + P - 1) / P;
    const bool whole = b + chunks * P <= src_size;
    const std::size_t len = whole ? chunks * P : e - b;
    // One loop over the particles for all D coordinates: it reads the array of vectors in
    // order (a loop per coordinate read it with stride D, which GCC 12 vectorised poorly).
    const Vec<D>* from_x = x + b;
    T* to[D];
    [[maybe_unused]] T* lo[D];
    double o[D];
    for (int k = 0; k < D; ++k) {
      to[k] = col[k].data() + at;
      if constexpr (kRelative) lo[k] = col[K - D + k].data() + at;
      o[k] = origin[k];
    }
    for (std::size_t q = 0; q < len; ++q) {
      for (int k = 0; k < D; ++k) {
        if constexpr (kRelative) {
          const double rel = from_x[q][k] - o[k];
          to[k][q] = static_cast<T>(rel);
          lo[k][q] = static_cast<T>(rel - static_cast<double>(to[k][q]));
        } else {
          to[k][q] = from_x[q][k];
        }
      }
    }
    for (int k = D; k < K; ++k) {
      if constexpr (kRelative) {
        if (k >= K - D) continue;  // the low parts, written with the positions
      }
      T* to = col[k].data() + at;
      const T* from = nullptr;
      if constexpr (kRelative)
        from = (*rest)[k];
      else
        from = src[k];
      if (from == nullptr) continue;
      from += b;
      if (whole) {
        for (std::size_t q = 0; q < chunks; ++q)
          std::memcpy(to + q * P, from + q * P, sizeof(T) * P);
      } else {
        std::copy(from, from + (e - b), to);
      }
    }
  }

  template <int D, class Fn>
  static void for_each_group_run(const CellGrid<D>& grid, std::int64_t c, Groups g, Fn&& fn) {
    if (static_cast<int>(g) & static_cast<int>(Groups::fluid))
      grid.for_each_block_run(c, Group::fluid, fn);
    if (static_cast<int>(g) & static_cast<int>(Groups::wall))
      grid.for_each_block_run(c, Group::wall, fn);
  }
};

// Pad values of a block whose first D columns are positions and the rest take `rest`.
template <int K, int D>
constexpr std::array<double, K> position_pad(double rest = 0.0) {
  std::array<double, K> p{};
  for (int k = 0; k < K; ++k) p[static_cast<std::size_t>(k)] = k < D ? kFarAway : rest;
  return p;
}

}  // namespace vrsph
