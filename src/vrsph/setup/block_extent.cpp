#include "vrsph/setup/block_extent.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vrsph/core/to_vec.hpp"
#include "vrsph/setup/tank.hpp"

namespace vrsph {
namespace {

// The nodes of a box min..max (lattice) or of its dp cells (cells): first node and count per axis.
struct NodeBox {
  Vec3d first{};
  Vec3d count{};
};

NodeBox node_box(const Vec3d& min, const Vec3d& max, double dp, int dim, bool cells) {
  NodeBox nb;
  for (int k = 0; k < dim; ++k) {
    const double off = cells ? 0.5 * dp : 0.0;
    nb.first[k] = min[k] + off;
    nb.count[k] = nodes_between(min[k] + off, max[k] - off, dp);
  }
  return nb;
}

Extent extent_of(const NodeBox& nb, double dp, int dim) {
  Extent e;
  for (int k = 0; k < dim; ++k) {
    e.lo[k] = nb.first[k];
    e.hi[k] = nb.first[k] + (nb.count[k] - 1.0) * dp;  // below lo when there is no node
  }
  return e;
}

double count_of(const NodeBox& nb, int dim) {
  double n = 1.0;
  for (int k = 0; k < dim; ++k) n *= nb.count[k];
  return n;
}

// The union of the plates of a tank (setup/tank.hpp) and their node count.
template <int D>
void tank_plates(const WallBlock& w, double dp, Extent& e, double& count) {
  for (int k = 0; k < D; ++k) {
    e.lo[k] = 1e300;
    e.hi[k] = -1e300;
  }
  count = 0.0;
  for_each_tank_plate<D>(to_vec<D>(w.min), to_vec<D>(w.max), w.layers, dp,
                         [&](const Vec<D>& lo, const Vec<D>& hi) {
                           Vec3d a{}, b{};
                           for (int k = 0; k < D; ++k) a[k] = lo[k], b[k] = hi[k];
                           const NodeBox nb = node_box(a, b, dp, D, false);
                           const double n = count_of(nb, D);
                           if (n <= 0.0) return;
                           count += n;
                           const Extent pe = extent_of(nb, dp, D);
                           for (int k = 0; k < D; ++k) {
                             e.lo[k] = std::min(e.lo[k], pe.lo[k]);
                             e.hi[k] = std::max(e.hi[k], pe.hi[k]);
                           }
                         });
}

void tank(const WallBlock& w, double dp, int dim, Extent& e, double& count) {
  if (dim == 2)
    tank_plates<2>(w, dp, e, count);
  else
    tank_plates<3>(w, dp, e, count);
}

}  // namespace

double nodes_between(double a, double b, double dp) {
  // geometry.cpp: floor((b - a) / dp + 1e-6) steps, tolerant to the rounding of case values
  return std::max(0.0, std::floor((b - a) / dp + 1e-6) + 1.0);
}

Extent fluid_extent(const FluidBlock& b, double dp, int dim) {
  if (b.shape == BlockShape::box) {
    return extent_of(node_box(b.min, b.max, dp, dim, b.fill == FillMode::cells), dp, dim);
  }
  Extent e;
  for (int k = 0; k < dim; ++k) {
    e.lo[k] = b.center[k] - b.radius;
    e.hi[k] = b.center[k] + b.radius;
  }
  return e;
}

Extent wall_extent(const WallBlock& w, double dp, int dim) {
  if (w.shape == WallShape::box) return extent_of(node_box(w.min, w.max, dp, dim, false), dp, dim);
  Extent e;
  double n = 0.0;
  tank(w, dp, dim, e, n);
  return e;
}

double fluid_count(const FluidBlock& b, double dp, int dim) {
  if (b.shape == BlockShape::box) {
    return count_of(node_box(b.min, b.max, dp, dim, b.fill == FillMode::cells), dim);
  }
  const double r = b.radius / dp;
  return dim == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

double wall_count(const WallBlock& w, double dp, int dim) {
  if (w.shape == WallShape::box) return count_of(node_box(w.min, w.max, dp, dim, false), dim);
  Extent e;
  double n = 0.0;
  tank(w, dp, dim, e, n);
  return n;
}

double largest_extent(const Extent& e, int dim) {
  double l = 0.0;
  for (int k = 0; k < dim; ++k) l = std::max(l, e.hi[k] - e.lo[k]);
  return l;
}

Extent case_extent(const CaseSpec& spec, double dp, bool with_walls) {
  Extent u;
  for (int k = 0; k < 3; ++k) u.lo[k] = 1e300, u.hi[k] = -1e300;
  auto add = [&](const Extent& e) {
    for (int k = 0; k < spec.dimension; ++k) {
      if (e.hi[k] < e.lo[k]) return;  // a block without particles
    }
    for (int k = 0; k < spec.dimension; ++k) {
      u.lo[k] = std::min(u.lo[k], e.lo[k]);
      u.hi[k] = std::max(u.hi[k], e.hi[k]);
    }
  };
  for (const FluidBlock& b : spec.fluid_blocks) add(fluid_extent(b, dp, spec.dimension));
  if (with_walls) {
    for (const WallBlock& w : spec.wall_blocks) add(wall_extent(w, dp, spec.dimension));
  }
  return u;
}

void grow_default_domain(Vec3d& lo, Vec3d& hi, int dim, double fluid_extent, const Vec3d& up,
                         double h, Vec3d& cell_origin) {
  for (int k = 0; k < dim; ++k) {
    const double ext = hi[k] - lo[k];
    const double earlier = std::max(0.1 * ext, 4.0 * h);
    const double m = std::max(earlier, fluid_extent);
    const double below = up[k] < -0.5 ? 0.5 * ext : 0.0;
    cell_origin[k] = lo[k] - (earlier + below);
    lo[k] -= m + below;
    hi[k] += m + (up[k] > 0.5 ? 0.5 * ext : 0.0);
  }
}

Extent default_domain_extent(const CaseSpec& spec) {
  const int dim = spec.dimension;
  Extent e = case_extent(spec, spec.dp, true);
  const double fluid = largest_extent(case_extent(spec, spec.dp, false), dim);
  Vec3d up{}, origin{};
  double g2 = 0.0;
  for (int k = 0; k < dim; ++k) g2 += spec.fluid.gravity[k] * spec.fluid.gravity[k];
  for (int k = 0; k < dim && g2 > 0.0; ++k) up[k] = -spec.fluid.gravity[k] / std::sqrt(g2);
  grow_default_domain(e.lo, e.hi, dim, fluid, up, spec.h_over_dp * spec.dp, origin);
  return e;
}

}  // namespace vrsph
