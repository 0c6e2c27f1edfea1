// Candidate neighbours of one cell, for the vector loops of every neighbour pass. The particles
// of the cell stencil's runs (CellGrid::for_each_run) are copied, column by column, into one
// contiguous block padded to a multiple of kBlockPad with inert dummies, so that each particle of
// the cell sweeps a single unit-stride loop with no remainder. All particles of a cell share the
// block (particles are sorted by cell, so consecutive particles reuse it): the copy is amortised.
// Columns 0..D-1 hold the positions; the rest are whatever the pass reads (velocity, density,
// volume, lambda, normal, ...), each with the value its dummies take.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "vrsph/particles/cell_grid.hpp"

namespace vrsph {

inline constexpr std::size_t kBlockPad = 8;
// Dummy coordinate: outside the support of every real particle, so every kernel term is zero.
inline constexpr double kFarAway = 1e15;

// Which groups of the grid a block takes: the fluid group (fluid and buffer), walls, or both.
enum class Groups : int { fluid = 1, wall = 2, all = 3 };

template <int K>
struct CandidateBlock {
  std::array<std::vector<double>, K> col;
  std::size_t len = 0;     // padded length
  std::int64_t cell = -1;  // cell the block was gathered for (-1: none yet)
  Groups groups = Groups::fluid;

  // Gathers the columns src[k] (each of the grid's particle count) of the particles in the
  // stencil of cell c, unless the block already holds that cell and groups. pad[k]: the value of
  // column k on the dummies.
  template <int D>
  void gather(const std::array<const double*, K>& src, const std::array<double, K>& pad,
              const CellGrid<D>& grid, std::int64_t c, Groups g) {
    c = grid.block_first(c);
    if (c == cell && g == groups) return;
    cell = c;
    groups = g;
    std::size_t n = 0, runs = 0;
    for_each_group_run(grid, c, g, [&](std::uint32_t b, std::uint32_t e) {
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
      copy_run(src, b, e, src_size, at);
      at += e - b;
    });
    for (int k = 0; k < K; ++k) std::fill(col[k].begin() + at, col[k].begin() + len, pad[k]);
  }

 private:
  // Copies src[k][b, e) to col[k] at `at`. Runs are short (a few cells), so a call of memmove
  // per run and column would cost more than the copy: whole chunks of kBlockPad values are
  // copied with fixed-size moves instead, overshooting the run's end by less than a chunk (the
  // next run or the padding overwrites it). Only a run whose last chunk would read past the
  // source arrays is copied element by element.
  void copy_run(const std::array<const double*, K>& src, std::size_t b, std::size_t e,
                std::size_t src_size, std::size_t at) {
    constexpr std::size_t P = kBlockPad;
    const std::size_t chunks = (e - b + P - 1) / P;
    if (b + chunks * P <= src_size) {
      for (int k = 0; k < K; ++k) {
        const double* from = src[k] + b;
        double* to = col[k].data() + at;
        for (std::size_t q = 0; q < chunks; ++q)
          std::memcpy(to + q * P, from + q * P, sizeof(double) * P);
      }
    } else {
      for (int k = 0; k < K; ++k) std::copy(src[k] + b, src[k] + e, col[k].begin() + at);
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
