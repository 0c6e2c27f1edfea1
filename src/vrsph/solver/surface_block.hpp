// The candidates of the surface passes (solver/surface_pass.cpp): which columns they read, read in
// place from the level's packed state and the pass's own columns (particles/run_columns.hpp), and
// the volume column they read.
#pragma once

#include <array>
#include <type_traits>

#include "vrsph/particles/run_columns.hpp"
#include "vrsph/solver/columns.hpp"

namespace vrsph {

// The columns of a surface pass in arithmetic type T (core/precision.hpp): the positions (D
// columns, the state's), the pass's N other columns (volume, lambda, normal components), and in
// float the positions' low parts (D columns, the state's). Every column is indexed by particle
// and holds at least kBlockPad entries past the last particle (zeros, or far away for the
// positions), which a span may read (particles/run_columns.hpp).
template <int D, int N, class T>
struct SurfaceColumns {
  static constexpr bool kFloat = std::is_same_v<T, float>;
  static constexpr int K = D + N + (kFloat ? D : 0);
  static constexpr int KL = kFloat ? D + N : -1;  // first low-part column, or none

  const StateRuns<D, T>& state;
  const T* base[16] = {};

  SurfaceColumns(const LevelColumns<D>& c, std::array<const T*, N> extra)
      : state(c.template state_of<T>()) {
    for (int k = 0; k < D; ++k) base[k] = state.base[k];
    for (int k = 0; k < N; ++k) base[D + k] = extra[k];
    if constexpr (kFloat) {
      for (int k = 0; k < D; ++k) base[KL + k] = state.base[StateRuns<D, T>::kLo + k];
    }
  }
  // x_i in the columns' frame, as hi + lo (lo 0 in double).
  void self(std::size_t i, T (&hi)[3], T (&lo)[3]) const {
    state.self(static_cast<std::uint32_t>(i), hi, lo);
  }
};

// The volume column of the surface passes: the state's, in its type; the one without buffer
// particles when the fields are summed across levels.
template <class T, int D>
const T* volume_column(const LevelColumns<D>& c) {
  const std::vector<T>& svol = [&]() -> const std::vector<T>& {
    if constexpr (std::is_same_v<T, float>)
      return c.f.svol;
    else
      return c.svol;
  }();
  return svol.empty() ? c.template state_of<T>().col[StateCol<D>::vol].data() : svol.data();
}

}  // namespace vrsph
