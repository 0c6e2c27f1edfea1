// The candidate blocks of the surface passes (solver/surface_pass.cpp): which columns they hold,
// the frame of a particle in one, and the volume column they read.
#pragma once

#include <array>
#include <type_traits>

#include "vrsph/particles/candidate_block.hpp"
#include "vrsph/solver/columns.hpp"

namespace vrsph {

// The blocks of a surface pass in arithmetic type T (core/precision.hpp): the positions (D
// columns), the pass's N other columns (volume, lambda, normal components), and in float the
// positions' low parts (D columns, particles/candidate_block.hpp).
template <int D, int N, class T>
struct SurfaceBlock {
  static constexpr bool kFloat = std::is_same_v<T, float>;
  static constexpr int K = D + N + (kFloat ? D : 0);
  static constexpr int KL = kFloat ? D + N : -1;  // first low-part column, or none
  using Block = CandidateBlock<K, T>;

  const Vec<D>* x = nullptr;           // the positions (the particle set's)
  std::array<const double*, K> src{};  // the other columns in double
  std::array<const T*, K> rest{};      // the other columns in float
  std::array<double, K> pad = position_pad<K, D>();

  SurfaceBlock(const LevelColumns<D>& c, std::array<const T*, N> extra) : x(c.pos) {
    for (int k = 0; k < N; ++k) {
      if constexpr (kFloat)
        rest[D + k] = extra[k];
      else
        src[D + k] = extra[k];
    }
  }
  void gather(Block& blk, const CellGrid<D>& grid, std::int64_t cell, Groups g) const {
    blk.gather(x, src, pad, grid, cell, g, kFloat ? &rest : nullptr);
  }
};

// x_i in block blk's frame, as hi + lo (lo unused in double).
template <int D, class Block, class T>
void frame_of(const LevelColumns<D>& c, std::size_t i, const Block& blk, T (&hi)[3], T (&lo)[3]) {
  double x[3] = {0, 0, 0};
  for (int d = 0; d < D; ++d) x[d] = c.pos[i][d];
  blk.frame(x, hi, lo);
}

// The volume column of the blocks: the level's float copy in mixed precision; the one without
// buffer particles when the fields are summed across levels.
template <class T, int D>
const T* volume_column(const LevelColumns<D>& c) {
  if constexpr (std::is_same_v<T, float>)
    return c.f.svol.empty() ? c.f.vol : c.f.svol.data();
  else
    return c.svol.empty() ? c.vol : c.svol.data();
}

}  // namespace vrsph
