// The state of one level's particles as separate contiguous columns (structure of arrays), packed
// once per force evaluation and read by every neighbour pass of that evaluation through candidate
// blocks (particles/candidate_block.hpp): the surface passes and the force pass share one copy.
#pragma once

#include <array>
#include <vector>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/physics/walls.hpp"

namespace vrsph {

template <int D>
struct LevelColumns {
  std::array<std::vector<double>, D> x, v;  // position, velocity
  std::vector<double> rho, p, vol, mass;    // p from the EOS, vol = m / rho
  std::vector<double> wall_vol;             // the volume seen by a wall's continuity sum

  // Positions and volumes only (the surface passes' needs), from a read-only particle set.
  void pack_geometry(const ParticleSet<D>& ps) {
    const std::size_t n = ps.size();
    for (int k = 0; k < D; ++k) x[k].resize(n);
    vol.resize(n);
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
      for (int k = 0; k < D; ++k) x[k][i] = ps.pos[i][k];
      vol[i] = ps.mass[i] / ps.rho[i];
    });
  }

  // Copies the particle state and fills ps.p from the EOS on the way.
  void pack(ParticleSet<D>& ps, const TaitEos& eos) {
    const std::size_t n = ps.size();
    for (int k = 0; k < D; ++k) {
      x[k].resize(n);
      v[k].resize(n);
    }
    for (auto* c : {&rho, &p, &vol, &mass, &wall_vol}) c->resize(n);
    ps.p.resize(n);
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t i) {
      for (int k = 0; k < D; ++k) {
        x[k][i] = ps.pos[i][k];
        v[k][i] = ps.vel[i][k];
      }
      rho[i] = ps.rho[i];
      ps.p[i] = eos.pressure(ps.rho[i]);
      p[i] = ps.p[i];
      vol[i] = ps.mass[i] / ps.rho[i];
      mass[i] = ps.mass[i];
      wall_vol[i] = wall_continuity_volume(vol[i], ps.kind[i] == Kind::buffer);
    });
  }
};

}  // namespace vrsph
