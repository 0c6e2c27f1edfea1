// Kernel interpolation of the fluid at an arbitrary point, Shepard-corrected (Shepard 1968; the
// probes and the interpolated lines, docs/outputs.md):
//   f(x) = sum_j f_j V_j W(x - x_j) / S(x),   S(x) = sum_j V_j W(x - x_j),   V_j = m_j / rho_j,
// over the Kind::fluid particles j of one level (walls and buffer particles left out), for f = p,
// rho and each velocity component. Dividing by S makes a constant field exact wherever S > 0,
// whatever the particle order. A linear field is exact only where the first moment
// sum_j V_j W (x_j - x) / S vanishes (at the nodes of a regular lattice); elsewhere the error is
// that moment times the gradient: below 0.01 |grad f| dp between the nodes of a lattice at
// h = 1.3 dp, about 0.1 |grad f| dp with particles 0.1 dp out of place, and of order |grad f| h
// within h of a free surface, where the support is one-sided (tests/test_shepard.cpp).
// S is about 1 inside the fluid and falls through 1/2 at a free surface (on a flat lattice face,
// near the plane dp/2 beyond the outer row): points with S < kShepardInside lie outside the fluid.
// p_j = p(rho_j) from the EOS. The grid must have been sorted since the particles last moved.
#pragma once

#include "vrsph/core/kernel.hpp"
#include "vrsph/core/vec.hpp"
#include "vrsph/output/fluid_point.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/eos.hpp"

namespace vrsph {

// Half the Shepard sum of the interior (about 1): below it a point counts as outside the fluid.
inline constexpr double kShepardInside = 0.5;

// The sums of one or more levels at a point: S and sum_j f_j V_j W for f = p, rho, v.
template <int D>
struct ShepardSums {
  double s = 0.0;
  double p = 0.0;
  double rho = 0.0;
  Vec<D> vel{};

  void add(const ShepardSums& o) {
    s += o.s;
    p += o.p;
    rho += o.rho;
    vel += o.vel;
  }
};

// The sums at x over the Kind::fluid particles of ps (zero when none is within 2h).
template <int D>
ShepardSums<D> shepard_sums(const Vec<D>& x, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                            const WendlandC2<D>& kernel, const TaitEos& eos);

// The interpolated values of sums s, attributed to `level`; outside (level -1, no values) when
// s.s < kShepardInside.
template <int D>
FluidPoint<D> shepard_point(const ShepardSums<D>& s, int level);

}  // namespace vrsph
