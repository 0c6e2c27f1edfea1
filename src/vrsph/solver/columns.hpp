// The state of one level's particles as separate contiguous columns (structure of arrays), packed
// once per force evaluation, in the grid's sorted order: every neighbour pass (forces and the
// surface passes) reads them in place, run by run (particles/run_columns.hpp).
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
  static constexpr int v = D, rho = 2 * D, p = rho + 1, vol = rho + 2, wall_vol = rho + 3,
                       count = rho + 4;
};
template <int D, class T>
inline constexpr int kStateCols = StateCol<D>::count + (std::is_same_v<T, float> ? D : 0);
template <int D, class T>
using StateRuns = RunColumns<kStateCols<D, T>, D, T>;

template <int D>
struct LevelColumns {
  // The force pass's state in the grid's sorted order, columns read in place by runs, in double
  // or (mixed precision) in float; the other stays empty. Its wall_vol column, the volume a
  // wall's continuity sum sees (vol but 0 for buffer particles), is stored only while the set
  // holds buffer particles (else it reads vol).
  StateRuns<D, double> state;
  // Weight omega_i in [0, 1] of each particle's volume and mass in every sum over neighbours
  // (vres/region.hpp, buffer_volume_weight), set by the coupling before each pack; empty: 1 for
  // all. The state's volumes carry it (a pair's mass is vol_j rho_j: the weighted mass).
  std::vector<double> weight;
  // Surface fields across levels (solver/cross_level.hpp): the surface passes then read svol,
  // vol with 0 for buffer particles, which the other level's fluid replaces in their sums.
  bool surface_without_buffers = false;
  std::vector<double> svol;
  // The same in float for the mixed precision (core/precision.hpp); empty in double precision,
  // while in mixed precision the double ones stay empty.
  struct Floats {
    StateRuns<D, float> state;
    std::vector<float> svol;
  } f;
  bool has_wall_vol = false;  // the state stores a wall_vol column (buffer particles present)

  template <class T>
  const StateRuns<D, T>& state_of() const {
    if constexpr (std::is_same_v<T, float>)
      return f.state;
    else
      return state;
  }

  // The positions and volumes only (the surface passes' needs), from a read-only particle set
  // sorted by `grid`: in float in mixed precision, in double otherwise.
  void pack_geometry(const ParticleSet<D>& ps, const CellGrid<D>& grid,
                     Precision precision = Precision::double_precision) {
    check_sorted(ps, grid);
    if (precision == Precision::mixed)
      pack_as<float, true>(ps, grid, TaitEos{}, f.state, f.svol);
    else
      pack_as<double, true>(ps, grid, TaitEos{}, state, svol);
  }

  // Copies the particle state, sorted by `grid` (its last sort), with the pressure from the EOS.
  // The density is kept as its deviation rho - rho0: differences of two densities are then
  // exact in float too.
  void pack(const ParticleSet<D>& ps, const CellGrid<D>& grid, const TaitEos& eos,
            Precision precision = Precision::double_precision) {
    check_sorted(ps, grid);
    has_wall_vol = std::find(ps.kind.begin(), ps.kind.end(), Kind::buffer) != ps.kind.end();
    if (precision == Precision::mixed)
      pack_as<float, false>(ps, grid, eos, f.state, f.svol);
    else
      pack_as<double, false>(ps, grid, eos, state, svol);
  }

 private:
  // Particles per range of the packing loops (exec::for_each_range): a few pages of each column.
  static constexpr std::int64_t kPackRange = 2048;

  // vol[q] = omega_q m_q / rho_q for q in [a, b) (weighted), rounded to T.
  template <class T>
  void pack_volumes(const ParticleSet<D>& ps, T* __restrict vol, std::size_t a,
                    std::size_t b) const {
    const double* __restrict rho = ps.rho.data();
    const double* __restrict w = weight.empty() ? nullptr : weight.data();
    if (ps.keeps_mass) {
      const double* __restrict m = ps.mass.data();
      if (w != nullptr) {
        for (std::size_t q = a; q < b; ++q) vol[q] = static_cast<T>(w[q] * (m[q] / rho[q]));
      } else {
        for (std::size_t q = a; q < b; ++q) vol[q] = static_cast<T>(m[q] / rho[q]);
      }
      return;
    }
    const double m = ps.mass_each;
    if (w != nullptr) {
      for (std::size_t q = a; q < b; ++q) vol[q] = static_cast<T>(w[q] * (m / rho[q]));
    } else {
      for (std::size_t q = a; q < b; ++q) vol[q] = static_cast<T>(m / rho[q]);
    }
  }

  // out[q] = component k of v[q], rounded to T.
  template <class T>
  static void pack_component(const Vec<D>* __restrict v, int k, T* __restrict out, std::size_t a,
                             std::size_t b) {
    for (std::size_t q = a; q < b; ++q) out[q] = static_cast<T>(v[q][k]);
  }

  // The density as its deviation rho - rho0 (exact, Sterbenz, while rho0 / 2 <= rho <= 2 rho0)
  // and the pressure from the EOS, rounded to T.
  template <class T>
  static void pack_density(const double* __restrict rho, const TaitEos& eos, T* __restrict dev,
                           T* __restrict p, std::size_t a, std::size_t b) {
    const double rho0 = eos.rho0;
    for (std::size_t q = a; q < b; ++q) dev[q] = static_cast<T>(rho[q] - rho0);
    if (eos.gamma == 7.0) {  // the branch of TaitEos::pressure, out of the loop
      for (std::size_t q = a; q < b; ++q) p[q] = static_cast<T>(eos.pressure_gamma7(rho[q]));
    } else {
      for (std::size_t q = a; q < b; ++q) p[q] = static_cast<T>(eos.pressure(rho[q]));
    }
  }

  static void check_sorted(const ParticleSet<D>& ps, const CellGrid<D>& grid) {
    if (grid.group_end(Group::wall) != ps.size())
      throw std::logic_error("LevelColumns: the particles changed since the grid's sort");
  }

  // kGeometry: the positions and volumes only (the other columns are not stored; they read the
  // volumes).
  template <class T, bool kGeometry>
  void pack_as(const ParticleSet<D>& ps, const CellGrid<D>& grid, const TaitEos& eos,
               StateRuns<D, T>& st, std::vector<T>& surface_vol) {
    using C = StateCol<D>;
    constexpr int K = kStateCols<D, T>;
    // Dummies: far away, at rest, density rho0 (deviation 0: no division by zero), no volume or
    // pressure.
    std::array<bool, K> absent{};
    std::array<int, K> alias{};
    absent[C::wall_vol] = !has_wall_vol || kGeometry, alias.fill(C::vol);
    if constexpr (kGeometry) {
      for (int k = C::v; k < C::count; ++k) absent[k] = k != C::vol;
    }
    st.lay_out(grid, absent, alias);
    const auto n = static_cast<std::int64_t>(ps.size());
    const bool buffers = has_wall_vol && !kGeometry;
    exec::for_each_range(exec::in_shares, n, kPackRange, [&](std::int64_t a, std::int64_t b) {
      const auto qa = static_cast<std::size_t>(a), qb = static_cast<std::size_t>(b);
      st.put_positions(ps.pos.data(), qa, qb);
      pack_volumes(ps, st.col[C::vol].data(), qa, qb);
      if constexpr (kGeometry) return;
      for (int k = 0; k < D; ++k) pack_component(ps.vel.data(), k, st.col[C::v + k].data(), qa, qb);
      pack_density(ps.rho.data(), eos, st.col[C::rho].data(), st.col[C::p].data(), qa, qb);
      if (buffers) {
        T* __restrict wall_vol = st.col[C::wall_vol].data();
        const T* __restrict vol = st.col[C::vol].data();
        for (std::size_t q = qa; q < qb; ++q)
          wall_vol[q] = static_cast<T>(
              wall_continuity_volume(static_cast<double>(vol[q]), ps.kind[q] == Kind::buffer));
      }
    });
    const T* vol_col = st.col[C::vol].data();
    // padded as the state's columns (particles/run_columns.hpp)
    surface_vol.assign(surface_without_buffers ? n + kBlockPad : 0, T(0));
    if (surface_without_buffers) {
      exec::for_each(exec::in_shares, static_cast<std::int64_t>(n), [&](std::int64_t i) {
        surface_vol[i] = ps.kind[i] == Kind::buffer ? T(0) : vol_col[i];
      });
    }
  }
};

}  // namespace vrsph
