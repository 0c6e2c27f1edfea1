// The force pass: one gather loop over particles that evaluates, for every fluid particle, the
// momentum and continuity right-hand sides (pressure, viscosity, density diffusion), and for every
// wall particle its continuity equation (fluid neighbours only; Crespo et al. 2007 dynamic
// boundary). Each particle writes only its own outputs: no atomics, the same result for any thread
// count. Model choices are template parameters resolved once per call (forces.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/params.hpp"

namespace vrsph {

struct ForceStats {
  double max_visc_dt = -1e300;  // max over pairs of v_ij . r_ij / (r^2 + eta^2)
  double max_acc = 0.0;         // max |a| over fluid particles (gravity excluded)
  std::uint64_t pairs = 0;      // pairs within 2h evaluated (i != j)

  // Combines the statistics of another pass (another stage or level): maxima and the pair sum.
  void merge(const ForceStats& o) {
    max_visc_dt = std::max(max_visc_dt, o.max_visc_dt);
    max_acc = std::max(max_acc, o.max_acc);
    pairs += o.pairs;
  }
};

// Neighbour data packed as separate contiguous arrays (structure of arrays) so the inner loop
// over a run of candidates j loads unit-stride vectors and the compiler can evaluate several
// pairs per instruction (`omp simd`).
template <int D>
struct NeighbourArrays {
  std::array<std::vector<double>, D> x, v;
  std::vector<double> rho, p, vol, mass;
  std::vector<double> wall_vol;  // volume seen by wall continuity: 0 for buffer particles, whose
                                 // motion is imposed and must not compress the wall

  // Copies the particle fields and fills ps.p from the EOS on the way.
  void pack(ParticleSet<D>& ps, const TaitEos& eos) {
    const std::size_t n = ps.size();
    for (int k = 0; k < D; ++k) {
      x[k].resize(n);
      v[k].resize(n);
    }
    rho.resize(n);
    p.resize(n);
    vol.resize(n);
    mass.resize(n);
    wall_vol.resize(n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < D; ++k) {
        x[k][i] = ps.pos[i][k];
        v[k][i] = ps.vel[i][k];
      }
      rho[i] = ps.rho[i];
      ps.p[i] = eos.pressure(ps.rho[i]);
      p[i] = ps.p[i];
      vol[i] = ps.mass[i] / ps.rho[i];
      mass[i] = ps.mass[i];
      wall_vol[i] = ps.kind[i] == Kind::buffer ? 0.0 : vol[i];
    }
  }
};

// Buffers a force pass reuses from call to call (no allocation once sizes settle).
template <int D>
struct ForceWorkspace {
  NeighbourArrays<D> packed;
};

// Fills ps.p from the EOS, then ps.acc and ps.drho for every particle (acc = 0 on walls).
// extra_acc (null: none) is a per-particle acceleration added to the fluid's, e.g. surface
// tension; it counts in ForceStats::max_acc. buffer_reaction: buffer particles get the
// acceleration their level's fluid and buffer neighbours exert on them (solver/momentum.hpp
// measures the coupling's net force from it); otherwise their acc is 0.
template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                          ForceWorkspace<D>& ws, const Vec<D>* extra_acc = nullptr,
                          bool buffer_reaction = false);
// The same with a workspace of its own (tests, one-off evaluations).
template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid);

}  // namespace vrsph
