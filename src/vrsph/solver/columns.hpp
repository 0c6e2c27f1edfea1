// The state of one level's particles as separate contiguous columns (structure of arrays), packed
// once per force evaluation and read by every neighbour pass of that evaluation through candidate
// blocks (particles/candidate_block.hpp): the surface passes and the force pass share one copy.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "vrsph/core/precision.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/physics/walls.hpp"

namespace vrsph {

template <int D>
struct LevelColumns {
  // The positions are not copied: the blocks read the particle set's own array, which no pass of
  // the evaluation moves or resizes (set by pack and pack_geometry).
  const Vec<D>* pos = nullptr;
  std::array<std::vector<double>, D> v;       // velocity
  std::vector<double> rho_dev, p, vol, mass;  // rho - rho0, p from the EOS, vol = m / rho
  // Weight omega_i in [0, 1] of each particle's volume and mass in every sum over neighbours
  // (vres/region.hpp, buffer_volume_weight), set by the coupling before each pack; empty: 1 for
  // all. vol and mass below already carry it.
  std::vector<double> weight;
  // Surface fields across levels (solver/cross_level.hpp): the surface passes then read svol,
  // vol with 0 for buffer particles, which the other level's fluid replaces in their sums.
  bool surface_without_buffers = false;
  std::vector<double> svol;
  // The volume seen by a wall's continuity sum (solver/forces.cpp): vol but 0 for buffer
  // particles, so empty (the passes read vol) while the set holds no buffer particle.
  std::vector<double> wall_vol;
  // Float copies of the non-position columns, for the mixed precision's candidate blocks
  // (core/precision.hpp); empty in double precision, while in mixed precision the double
  // columns stay empty.
  struct Floats {
    std::array<std::vector<float>, D> v;
    std::vector<float> rho_dev, p, vol, mass, wall_vol, svol;
  } f;

  // Volumes only besides the positions (the surface passes' needs), from a read-only particle
  // set: in float in mixed precision, in double otherwise.
  void pack_geometry(const ParticleSet<D>& ps, Precision precision = Precision::double_precision) {
    const std::size_t n = ps.size();
    pos = ps.pos.data();
    const bool floats = precision == Precision::mixed;
    if (floats)
      f.vol.resize(n);
    else
      vol.resize(n);
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
      const double vol_i = weighted(i, ps.mass[i] / ps.rho[i]);
      if (floats)
        f.vol[i] = static_cast<float>(vol_i);
      else
        vol[i] = vol_i;
    });
  }

  // Copies the particle state, with the pressure from the EOS. The density is kept as
  // its deviation rho - rho0: differences of two densities are then exact in float too. In mixed
  // precision the passes read only the float columns besides the positions, so the double
  // columns are left empty.
  void pack(const ParticleSet<D>& ps, const TaitEos& eos,
            Precision precision = Precision::double_precision) {
    const std::size_t n = ps.size();
    pos = ps.pos.data();
    if (precision == Precision::mixed) {
      pack_floats(ps, eos);
      return;
    }
    for (int k = 0; k < D; ++k) v[k].resize(n);
    for (auto* c : {&rho_dev, &p, &vol, &mass}) c->resize(n);
    const bool buffers = has_buffer(ps);
    wall_vol.resize(buffers ? n : 0);
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
      for (int k = 0; k < D; ++k) v[k][i] = ps.vel[i][k];
      rho_dev[i] = ps.rho[i] - eos.rho0;  // exact (Sterbenz) while rho0 / 2 <= rho <= 2 rho0
      p[i] = eos.pressure(ps.rho[i]);
      vol[i] = weighted(i, ps.mass[i] / ps.rho[i]);
      mass[i] = weighted(i, ps.mass[i]);
      if (buffers) wall_vol[i] = wall_continuity_volume(vol[i], ps.kind[i] == Kind::buffer);
    });
    svol.resize(surface_without_buffers ? n : 0);
    if (surface_without_buffers) {
      exec::for_each(static_cast<std::int64_t>(n),
                     [&](std::int64_t i) { svol[i] = ps.kind[i] == Kind::buffer ? 0.0 : vol[i]; });
    }
  }

 private:
  double weighted(std::int64_t i, double x) const {
    return weight.empty() ? x : weight[static_cast<std::size_t>(i)] * x;
  }
  void pack_floats(const ParticleSet<D>& ps, const TaitEos& eos) {
    const std::size_t n = ps.size();
    for (int k = 0; k < D; ++k) f.v[k].resize(n);
    for (auto* c : {&f.rho_dev, &f.p, &f.vol, &f.mass}) c->resize(n);
    const bool buffers = has_buffer(ps);
    f.wall_vol.resize(buffers ? n : 0);
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
      for (int k = 0; k < D; ++k) f.v[k][i] = static_cast<float>(ps.vel[i][k]);
      const double vol_i = weighted(i, ps.mass[i] / ps.rho[i]);
      f.rho_dev[i] = static_cast<float>(ps.rho[i] - eos.rho0);
      f.p[i] = static_cast<float>(eos.pressure(ps.rho[i]));
      f.vol[i] = static_cast<float>(vol_i);
      f.mass[i] = static_cast<float>(weighted(i, ps.mass[i]));
      if (buffers)
        f.wall_vol[i] =
            static_cast<float>(wall_continuity_volume(vol_i, ps.kind[i] == Kind::buffer));
    });
    f.svol.resize(surface_without_buffers ? n : 0);
    if (surface_without_buffers) {
      exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
        f.svol[i] = ps.kind[i] == Kind::buffer ? 0.0f : f.vol[i];
      });
    }
  }

  static bool has_buffer(const ParticleSet<D>& ps) {
    return std::find(ps.kind.begin(), ps.kind.end(), Kind::buffer) != ps.kind.end();
  }
};

}  // namespace vrsph
