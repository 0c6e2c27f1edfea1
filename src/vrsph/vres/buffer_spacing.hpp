// Buffer particles kept apart (numerics.vres_buffer_spacing; not part of Ricci, Vacondio &
// Tafuni 2024). A buffer particle moves with the velocity interpolated from the donor level
// (vres/coupling.hpp), which is smooth over the donor's 2 h, twice its own level's spacing, and
// feels no pressure of its own level: two buffer particles that come close (the start transient
// of the donor moves neighbouring rings by different amounts) stay close for a long time. When
// one of them enters the fluid zone the pair's pressure throws it out, a spike of the parasitic
// speed (docs/validation.md, "Where the VR drop's remaining spikes come from").
//
// The remedy: every buffer particle closer than s dp to another particle of its level moves
// away from it by the shortfall, d_i = sum_j w_j (s dp - r_ij) e_ij, e_ij = (x_i - x_j) / r_ij,
// with w_j = 1/2 for another buffer particle (each of the two moves half) and 1 for a fluid or
// wall particle (which stay). A buffer particle holds no state of its own (its density and
// velocity are interpolated again at its new place right after), so the move changes no
// conserved quantity. Gather form over the level's grid as last sorted: each buffer particle
// reads the others' positions before any moves, so the result does not depend on the threads.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/within.hpp"
#include "vrsph/solver/level.hpp"

namespace vrsph {

// The displacement of buffer particle i (Level's grid as last sorted; i below the sorted count).
template <int D>
Vec<D> buffer_spacing_shift(const Level<D>& L, std::size_t i, double d_min) {
  const ParticleSet<D>& ps = L.ps;
  const double d2 = d_min * d_min;
  Vec<D> d{};
  const std::int64_t c = L.grid.particle_cells()[i];
  auto at = [&](std::uint32_t j) { return ps.pos[j]; };
  for (Group g : {Group::fluid, Group::wall}) {
    for_each_within(L.grid, c, g, ps.pos[i], d2, at,
                    [&](std::uint32_t j, const Vec<D>& r, double r2) {
                      if (j == i || r2 == 0.0) return;
                      const double dist = std::sqrt(r2);
                      const double w = ps.kind[j] == Kind::buffer ? 0.5 : 1.0;
                      d += r * (w * (d_min - dist) / dist);
                    });
  }
  return d;
}

// Moves the buffer particles of level L apart (s in dp of the level; s <= 0: nothing). Returns
// how many moved. Call while the level's grid matches its particles (before any creation or
// deletion since the last sort).
template <int D>
std::size_t space_buffers(Level<D>& L, double s) {
  ParticleSet<D>& ps = L.ps;
  if (s <= 0.0) return 0;
  if (L.grid.particle_cells().size() != ps.size())
    throw std::logic_error("space_buffers: the particles changed since the grid's sort");
  const double d_min = s * L.prm.dp;
  std::vector<Vec<D>> shift(ps.size());
  exec::for_each_dynamic(static_cast<std::int64_t>(ps.size()), 256, [&](std::int64_t ii) {
    const auto i = static_cast<std::size_t>(ii);
    shift[i] = ps.kind[i] == Kind::buffer ? buffer_spacing_shift(L, i, d_min) : Vec<D>{};
  });
  struct None {};
  struct Moved {
    std::size_t n = 0;
    void merge(const Moved& o) { n += o.n; }
  };
  const Moved moved = exec::for_each_gather<None, Moved>(static_cast<std::int64_t>(ps.size()), 1024,
                                                         [&](std::int64_t i, None&, Moved& acc) {
                                                           if (norm2(shift[i]) == 0.0) return;
                                                           ps.pos[i] += shift[i];
                                                           ++acc.n;
                                                         });
  return moved.n;
}

}  // namespace vrsph
