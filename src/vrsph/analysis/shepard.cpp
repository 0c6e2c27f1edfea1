#include "vrsph/analysis/shepard.hpp"

#include <cmath>
#include <cstdint>

namespace vrsph {

template <int D>
ShepardSums<D> shepard_sums(const Vec<D>& x, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                            const WendlandC2<D>& kernel, const TaitEos& eos) {
  ShepardSums<D> s;
  std::int64_t c = 0;
  if (ps.size() == 0 || !grid.stencil_cell(x, c)) return s;
  grid.for_each_run(c, Group::fluid, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t j = begin; j < end; ++j) {
      if (ps.kind[j] != Kind::fluid) continue;  // buffer particles mirror another level
      const double r2 = norm2(x - ps.pos[j]);
      if (r2 >= kernel.support2) continue;
      const double vw = ps.mass_of(j) / ps.rho[j] * kernel.w(std::sqrt(r2));
      s.s += vw;
      s.p += eos.pressure(ps.rho[j]) * vw;
      s.rho += ps.rho[j] * vw;
      s.vel += ps.vel[j] * vw;
    }
  });
  return s;
}

template <int D>
FluidPoint<D> shepard_point(const ShepardSums<D>& s, int level) {
  FluidPoint<D> f;
  f.shepard = s.s;
  if (!(s.s >= kShepardInside)) return f;
  const double inv = 1.0 / s.s;
  f.level = level;
  f.p = s.p * inv;
  f.rho = s.rho * inv;
  f.vel = s.vel * inv;
  return f;
}

template ShepardSums<2> shepard_sums<2>(const Vec<2>&, const ParticleSet<2>&, const CellGrid<2>&,
                                        const WendlandC2<2>&, const TaitEos&);
template ShepardSums<3> shepard_sums<3>(const Vec<3>&, const ParticleSet<3>&, const CellGrid<3>&,
                                        const WendlandC2<3>&, const TaitEos&);
template FluidPoint<2> shepard_point<2>(const ShepardSums<2>&, int);
template FluidPoint<3> shepard_point<3>(const ShepardSums<3>&, int);

}  // namespace vrsph
