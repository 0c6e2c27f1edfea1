// The state of one level's particles as separate contiguous columns (structure of arrays), packed
// once per force evaluation: the force pass reads its columns in place, run by run
// (particles/run_columns.hpp); the surface passes copy positions and volumes into candidate
// blocks (particles/candidate_block.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "vrsph/core/precision.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/particles/run_columns.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/physics/walls.hpp"

namespace vrsph {

// Columns of the force pass's state: positions, velocities, then the scalars (densities as
// deviations rho - rho0); float columns add the low parts of the positions as their last D.
template <int D>
struct StateCol {
  static constexpr int v = D, rho = 2 * D, p = rho + 1, vol = rho + 2, mass = rho + 3,
                       wall_vol = rho + 4, count = rho + 5;
};
template <int D, class T>
inline constexpr int kStateCols = StateCol<D>::count + (std::is_same_v<T, float> ? D : 0);
template <int D, class T>
using StateRuns = RunColumns<kStateCols<D, T>, D, T>;

template <int D>
struct LevelColumns {
  // The positions are not copied for the surface passes: their blocks read the particle set's
  // own array, which no pass of the evaluation moves or resizes (set by pack and pack_geometry).
  const Vec<D>* pos = nullptr;
  // The force pass's state in the grid's sorted order, columns read in place by runs, in double
  // or (mixed precision) in float; the other stays empty. Its wall_vol column, the volume a
  // wall's continuity sum sees (vol but 0 for buffer particles), is stored only while the set
  // holds buffer particles (else it reads vol).
  StateRuns<D, double> state;
  // The volumes vol = m / rho by particle index that the surface passes' blocks read: the
  // state's vol column after pack, geometry_vol after pack_geometry.
  const double* vol = nullptr;
  std::vector<double> geometry_vol;
  // Weight omega_i in [0, 1] of each particle's volume and mass in every sum over neighbours
  // (vres/region.hpp, buffer_volume_weight), set by the coupling before each pack; empty: 1 for
  // all. vol and mass below already carry it.
  std::vector<double> weight;
  // Surface fields across levels (solver/cross_level.hpp): the surface passes then read svol,
  // vol with 0 for buffer particles, which the other level's fluid replaces in their sums.
  bool surface_without_buffers = false;
  std::vector<double> svol;
  // The same in float for the mixed precision (core/precision.hpp); empty in double precision,
  // while in mixed precision the double ones stay empty.
  struct Floats {
    StateRuns<D, float> state;
    const float* vol = nullptr;
    std::vector<float> geometry_vol, svol;
  } f;
  bool has_wall_vol = false;  // the state stores a wall_vol column (buffer particles present)

  template <class T>
  const StateRuns<D, T>& state_of() const {
    if constexpr (std::is_same_v<T, float>)
      return f.state;
    else
      return state;
  }

  // Volumes only besides the positions (the surface passes' needs), from a read-only particle
  // set: in float in mixed precision, in double otherwise.
  void pack_geometry(const ParticleSet<D>& ps, Precision precision = Precision::double_precision) {
    const std::size_t n = ps.size();
    pos = ps.pos.data();
    const bool floats = precision == Precision::mixed;
    if (floats)
      f.geometry_vol.resize(n), f.vol = f.geometry_vol.data();
    else
      geometry_vol.resize(n), vol = geometry_vol.data();
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
      const double vol_i = weighted(i, ps.mass[i] / ps.rho[i]);
      if (floats)
        f.geometry_vol[i] = static_cast<float>(vol_i);
      else
        geometry_vol[i] = vol_i;
    });
  }

  // Copies the particle state, sorted by `grid` (its last sort), with the pressure from the EOS.
  // The density is kept as its deviation rho - rho0: differences of two densities are then
  // exact in float too.
  void pack(const ParticleSet<D>& ps, const CellGrid<D>& grid, const TaitEos& eos,
            Precision precision = Precision::double_precision) {
    if (grid.group_end(Group::wall) != ps.size())
      throw std::logic_error("LevelColumns::pack: the particles changed since the grid's sort");
    pos = ps.pos.data();
    has_wall_vol = std::find(ps.kind.begin(), ps.kind.end(), Kind::buffer) != ps.kind.end();
    if (precision == Precision::mixed)
      f.vol = pack_as<float>(ps, grid, eos, f.state, f.svol);
    else
      vol = pack_as<double>(ps, grid, eos, state, svol);
  }

 private:
  double weighted(std::int64_t i, double x) const {
    return weight.empty() ? x : weight[static_cast<std::size_t>(i)] * x;
  }

  // Returns the volume column.
  template <class T>
  const T* pack_as(const ParticleSet<D>& ps, const CellGrid<D>& grid, const TaitEos& eos,
                   StateRuns<D, T>& st, std::vector<T>& surface_vol) {
    using C = StateCol<D>;
    constexpr int K = kStateCols<D, T>;
    // Dummies: far away, at rest, density rho0 (deviation 0: no division by zero), no volume,
    // mass or pressure.
    std::array<bool, K> absent{};
    std::array<int, K> alias{};
    absent[C::wall_vol] = !has_wall_vol, alias[C::wall_vol] = C::vol;
    st.lay_out(grid, std::array<double, K>{}, absent, alias);
    const std::size_t n = ps.size();
    const bool buffers = has_wall_vol;
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
      st.put_position(i, ps.pos[i]);
      for (int k = 0; k < D; ++k) st.col[C::v + k][i] = static_cast<T>(ps.vel[i][k]);
      const double vol_i = weighted(i, ps.mass[i] / ps.rho[i]);
      // exact (Sterbenz) while rho0 / 2 <= rho <= 2 rho0
      st.col[C::rho][i] = static_cast<T>(ps.rho[i] - eos.rho0);
      st.col[C::p][i] = static_cast<T>(eos.pressure(ps.rho[i]));
      st.col[C::vol][i] = static_cast<T>(vol_i);
      st.col[C::mass][i] = static_cast<T>(weighted(i, ps.mass[i]));
      if (buffers)
        st.col[C::wall_vol][i] =
            static_cast<T>(wall_continuity_volume(vol_i, ps.kind[i] == Kind::buffer));
    });
    const T* vol_col = st.col[C::vol].data();
    surface_vol.resize(surface_without_buffers ? n : 0);
    if (surface_without_buffers) {
      exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
        surface_vol[i] = ps.kind[i] == Kind::buffer ? T(0) : vol_col[i];
      });
    }
    return vol_col;
  }
};

}  // namespace vrsph
