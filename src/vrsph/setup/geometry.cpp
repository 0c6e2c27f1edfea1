#include "vrsph/setup/geometry.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "vrsph/core/to_vec.hpp"
#include "vrsph/setup/tank.hpp"

namespace vrsph {
namespace {

// Number of lattice steps of size dp from a to b (tolerant to rounding of the case values).
long steps_between(double a, double b, double dp) {
  return static_cast<long>(std::floor((b - a) / dp + 1e-6));
}

// Calls fn(x) for every lattice node min + k dp with x <= max on each axis. Each coordinate is
// min + k dp rounded once (std::fma), so it does not depend on whether the compiler contracts the
// product and sum: nodes meant to lie on a refinement box's face (a half-open box) must land on
// the same side in every build. Rounded twice, 0.01 + 9 x 0.01 gives 0.09999999999999999 and a
// fine level's first row can fall outside its box (docs/validation.md, "Figures formerly in code
// comments").
template <int D, class Fn>
void for_each_node(const Vec<D>& min, const Vec<D>& max, double dp, Fn&& fn) {
  std::array<long, 3> n{1, 1, 1};
  for (int k = 0; k < D; ++k) n[k] = steps_between(min[k], max[k], dp) + 1;
  for (long c = 0; c < (D == 3 ? n[2] : 1); ++c)
    for (long b = 0; b < n[1]; ++b)
      for (long a = 0; a < n[0]; ++a) {
        const std::array<long, 3> step{a, b, c};
        Vec<D> x;
        for (int k = 0; k < D; ++k)
          x[k] = std::fma(static_cast<double>(step[static_cast<std::size_t>(k)]), dp, min[k]);
        fn(x);
      }
}

// The centres of the dp cells that tile [min, max] (a box whose sides are not whole multiples of
// dp keeps the whole cells that fit, from min): the nodes of [min, max] shrunk by dp/2 on every
// face. A box thinner than one cell shrinks to an empty range, where for_each_node makes no node.
template <int D, class Fn>
void for_each_cell_centre(const Vec<D>& min, const Vec<D>& max, double dp, Fn&& fn) {
  Vec<D> lo = min, hi = max;
  for (int k = 0; k < D; ++k) {
    lo[k] += 0.5 * dp;
    hi[k] -= 0.5 * dp;
  }
  for_each_node<D>(lo, hi, dp, fn);
}

template <int D, class Fn>
void fill_ball_lattice(const Vec<D>& c, double radius, double dp, Fn&& fn) {
  const long m = static_cast<long>(std::ceil(radius / dp)) + 1;
  Vec<D> lo = c, hi = c;
  for (int k = 0; k < D; ++k) {
    lo[k] -= (m - 0.5) * dp;
    hi[k] += (m - 0.5) * dp;
  }
  for_each_node<D>(lo, hi, dp, [&](const Vec<D>& x) {
    if (norm2(x - c) < radius * radius) fn(x);
  });
}

// Concentric rings at radii (k + 1/2) dp, each with round(2 pi r / dp) equally spaced particles.
// Ring k is turned by frac(k^2 g) of its own spacing, g = (sqrt 5 - 1) / 2. Were every ring
// started at theta = 0, all rings would have a particle on the +x ray, a radially aligned seam
// that seeds every cos(n theta) shape mode of a drop. A turn linear in k (k g) only moves the
// seam: ring counts grow by about 6 per ring, so long chains of rings still line up along the
// rays at 2 pi (g + m) / 6. The quadratic sequence's increments (2k + 1) g vary irrationally,
// which leaves no chain of radially aligned particles longer than a few rings. Measured effect
// of the seam: docs/validation.md, "Figures formerly in code comments".
// on_radius ("rings_on_radius"): the rings at R - k dp instead, the outer one on R itself and
// the innermost at R - floor(R / dp) dp (a single particle when that is 0), so the particles
// stand for the disc of radius about R + dp / 2 (docs/cases.md).
template <class Fn>
void fill_circle_rings(const Vec<2>& c, double radius, double dp, bool on_radius, Fn&& fn) {
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  const long inner = static_cast<long>(std::floor(radius / dp + 1e-9));
  const long rings = on_radius ? inner + 1 : std::lround(radius / dp);
  const double r0 = radius - static_cast<double>(inner) * dp;  // on_radius only
  for (long k = 0; k < rings; ++k) {
    const double r = on_radius ? std::max(r0 + static_cast<double>(k) * dp, 0.0) : (k + 0.5) * dp;
    const long count =
        r < 1e-9 * dp ? 1 : std::max(1L, std::lround(2.0 * std::numbers::pi * r / dp));
    const double kk = static_cast<double>(k) * static_cast<double>(k) * golden;
    const double turn = kk - std::floor(kk);
    for (long q = 0; q < count; ++q) {
      const double th = 2.0 * std::numbers::pi * (q + turn) / count;
      fn(Vec<2>{{c[0] + r * std::cos(th), c[1] + r * std::sin(th)}});
    }
  }
}

// Tank: the nodes of every plate of setup/tank.hpp.
template <int D, class Fn>
void fill_tank(const Vec<D>& min, const Vec<D>& max, int layers, double dp, Fn&& fn) {
  for_each_tank_plate<D>(min, max, layers, dp, [&](const Vec<D>& lo, const Vec<D>& hi) {
    for_each_node<D>(lo, hi, dp, fn);
  });
}

// Calls fluid(block, x) for every fluid node of the case's blocks at spacing dp, then, block after
// block, wall_block() and wall(x) for every node of that wall block.
template <int D, class FluidFn, class WallBlockFn, class WallFn>
void visit_nodes(const CaseSpec& spec, double dp, FluidFn&& fluid, WallBlockFn&& wall_block,
                 WallFn&& wall) {
  for (const FluidBlock& b : spec.fluid_blocks) {
    auto add = [&](const Vec<D>& x) { fluid(b, x); };
    if (b.shape == BlockShape::box) {
      const Vec<D> lo = to_vec<D>(b.min), hi = to_vec<D>(b.max);
      if (b.fill == FillMode::cells)
        for_each_cell_centre<D>(lo, hi, dp, add);
      else
        for_each_node<D>(lo, hi, dp, add);
    } else {
      if constexpr (D == 2) {
        if (b.fill == FillMode::rings || b.fill == FillMode::rings_on_radius)
          fill_circle_rings(to_vec<2>(b.center), b.radius, dp, b.fill == FillMode::rings_on_radius,
                            add);
        else
          fill_ball_lattice<D>(to_vec<D>(b.center), b.radius, dp, add);
      } else {
        fill_ball_lattice<D>(to_vec<D>(b.center), b.radius, dp, add);
      }
    }
  }
  for (const WallBlock& w : spec.wall_blocks) {
    wall_block();
    if (w.shape == WallShape::tank)
      fill_tank<D>(to_vec<D>(w.min), to_vec<D>(w.max), w.layers, dp, wall);
    else
      for_each_node<D>(to_vec<D>(w.min), to_vec<D>(w.max), dp, wall);
  }
}

}  // namespace

// The nodes are visited twice: counted, then stored into arrays reserved to that count (grown
// one particle at a time, every array would end with up to twice the capacity it needs, which
// the run would hold to its end: 80 bytes per particle on the 2D benchmark).
template <int D>
InitialSet<D> build_particles(const CaseSpec& spec) {
  InitialSet<D> out;
  ParticleSet<D>& ps = out.particles;
  const double dp = spec.dp;
  const double mass = spec.fluid.density * std::pow(dp, D);
  std::size_t count = 0;
  visit_nodes<D>(
      spec, dp, [&](const FluidBlock&, const Vec<D>&) { ++count; }, [] {},
      [&](const Vec<D>&) { ++count; });
  ps.reserve(count);
  out.initial_pressure.reserve(count);
  std::uint64_t next_id = 0;
  visit_nodes<D>(
      spec, dp,
      [&](const FluidBlock& b, const Vec<D>& x) {
        ps.push_back(next_id++, Kind::fluid, x, to_vec<D>(b.velocity), spec.fluid.density, mass);
        out.initial_pressure.push_back(b.pressure);
      },
      [&] { out.wall_block_first.push_back(ps.size()); },
      [&](const Vec<D>& x) {
        ps.push_back(next_id++, Kind::wall, x, Vec<D>{}, spec.fluid.density, mass);
        out.initial_pressure.push_back(0.0);
      });
  const int vert = vertical_axis<D>();
  double zmin = 1e300, zmax = -1e300;
  for (const FluidBlock& b : spec.fluid_blocks) {
    const bool box = b.shape == BlockShape::box;
    zmin = std::min(zmin, box ? b.min[vert] : b.center[vert] - b.radius);
    zmax = std::max(zmax, box ? b.max[vert] : b.center[vert] + b.radius);
  }
  out.fluid_height = zmax > zmin ? zmax - zmin : 0.0;
  return out;
}

template <int D>
void apply_hydrostatic_density(ParticleSet<D>& ps, const Vec<D>& gravity, double rho0, double dp,
                               const TaitEos& eos) {
  const double g = norm(gravity);
  if (g == 0.0) return;
  const Vec<D> up = gravity * (-1.0 / g);
  // Horizontal column key: gravity is taken along the vertical axis for the column map.
  const int vert = vertical_axis<D>();
  auto column = [&](const Vec<D>& x, int dx, int dy) {
    std::array<long, 2> key{0, 0};
    int m = 0;
    for (int k = 0; k < D; ++k) {
      if (k == vert) continue;
      key[m] = std::lround(x[k] / dp) + (m == 0 ? dx : dy);
      ++m;
    }
    return key;
  };
  std::map<std::array<long, 2>, double> top;  // highest fluid particle per column
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] != Kind::fluid) continue;
    auto [it, fresh] = top.try_emplace(column(ps.pos[i], 0, 0), dot(ps.pos[i], up));
    if (!fresh) it->second = std::max(it->second, dot(ps.pos[i], up));
  }
  const int reach = 4;  // wall columns look this many dp sideways for fluid above them
  for (std::size_t i = 0; i < ps.size(); ++i) {
    double surface = -1e300;
    const int rx = ps.kind[i] == Kind::fluid ? 0 : reach;  // fluid: its own column only
    const int ry = D == 3 ? rx : 0;
    for (int dy = -ry; dy <= ry; ++dy)
      for (int dx = -rx; dx <= rx; ++dx) {
        auto it = top.find(column(ps.pos[i], dx, dy));
        if (it != top.end()) surface = std::max(surface, it->second);
      }
    if (surface == -1e300) continue;
    const double depth = surface - dot(ps.pos[i], up);
    if (depth > 0.0) ps.rho[i] = eos.density(rho0 * g * depth);
  }
}

template InitialSet<2> build_particles<2>(const CaseSpec&);
template InitialSet<3> build_particles<3>(const CaseSpec&);
template void apply_hydrostatic_density<2>(ParticleSet<2>&, const Vec<2>&, double, double,
                                           const TaitEos&);
template void apply_hydrostatic_density<3>(ParticleSet<3>&, const Vec<3>&, double, double,
                                           const TaitEos&);

}  // namespace vrsph
