// The geometry checks of a parsed case (case_checks.hpp). Figures come from block_extent.hpp:
// where the fill will put particles, computed without making any.
#include "vrsph/setup/case_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "vrsph/setup/block_extent.hpp"

namespace vrsph::case_detail {
namespace {

const char* axis_name(int k) { return k == 0 ? "x" : k == 1 ? "y" : "z"; }

bool is_round(const FluidBlock& b) { return b.shape != BlockShape::box; }

// A computed vector for messages, 6 significant digits.
std::string vec_g(const Vec3d& v, int dim) {
  std::string out = "[";
  for (int k = 0; k < dim; ++k) out += fmt::format("{}{:.6g}", k ? ", " : "", v[k]);
  return out + "]";
}

// A box fluid block filled with cells holds none when thinner than dp on some axis.
void check_not_empty(const TableReader& r, const FluidBlock& b, const CaseSpec& spec, bool only) {
  const int dim = spec.dimension;
  if (is_round(b) || fluid_count(b, spec.dp, dim) > 0.0) return;
  int k = 0;
  while (k + 1 < dim && b.max[k] - b.min[k] >= spec.dp) ++k;
  r.fail("max", fmt::format("the box holds no particle at resolution.dp = {:g} m: it is {:g} m "
                            "thick along {}, less than one cell of dp (fill = \"cells\"){}",
                            spec.dp, b.max[k] - b.min[k], axis_name(k),
                            only ? "; the case has no fluid particle" : ""));
}

// The particles of a block (extent e) lie inside [domain]; `what` names them in the reason.
void check_inside(const TableReader& r, const Extent& e, const CaseSpec& spec,
                  std::string_view lo_key, std::string_view hi_key, const std::string& what) {
  const int dim = spec.dimension;
  const Vec3d& dmin = *spec.domain_min;
  const Vec3d& dmax = *spec.domain_max;
  for (int k = 0; k < dim; ++k) {
    if (e.hi[k] < e.lo[k]) return;  // no particle
  }
  const char* fix = "its particles there would be dropped (enlarge [domain] or move the block)";
  for (int k = 0; k < dim; ++k) {
    if (e.lo[k] < dmin[k]) {
      r.fail(lo_key, fmt::format("{} reach {} = {:g} m, outside the domain (domain.min = {}): {}",
                                 what, axis_name(k), e.lo[k], vec_text(dmin, dim), fix));
    }
    if (e.hi[k] > dmax[k]) {
      r.fail(hi_key, fmt::format("{} reach {} = {:g} m, outside the domain (domain.max = {}): {}",
                                 what, axis_name(k), e.hi[k], vec_text(dmax, dim), fix));
    }
  }
}

// The extent of a fluid block's shape (its particles lie within it at every level's dp).
Extent shape_extent(const FluidBlock& b, int dim) {
  Extent e;
  for (int k = 0; k < dim; ++k) {
    e.lo[k] = is_round(b) ? b.center[k] - b.radius : b.min[k];
    e.hi[k] = is_round(b) ? b.center[k] + b.radius : b.max[k];
  }
  return e;
}

// Distance from x to the box e (0 inside).
double distance_to(const Vec3d& x, const Extent& e, int dim) {
  double d2 = 0.0;
  for (int k = 0; k < dim; ++k) {
    const double d = std::max({e.lo[k] - x[k], x[k] - e.hi[k], 0.0});
    d2 += d * d;
  }
  return std::sqrt(d2);
}

// True when particles of blocks a and b would come within about dp/2 of each other: round
// shapes that overlap (touching is fine: two drops side by side), a round shape reaching into a
// box, or boxes whose nodes come closer than dp/2 on every axis (lattice boxes sharing a face
// both put a row of nodes on it).
bool blocks_overlap(const FluidBlock& a, const FluidBlock& b, double dp, int dim) {
  const double tol = 0.01 * dp;
  if (is_round(a) && is_round(b)) {
    double d2 = 0.0;
    for (int k = 0; k < dim; ++k) d2 += (a.center[k] - b.center[k]) * (a.center[k] - b.center[k]);
    return std::sqrt(d2) < a.radius + b.radius - tol;
  }
  if (is_round(a) || is_round(b)) {
    const FluidBlock& round = is_round(a) ? a : b;
    const FluidBlock& box = is_round(a) ? b : a;
    return distance_to(round.center, shape_extent(box, dim), dim) < round.radius - tol;
  }
  const Extent ea = fluid_extent(a, dp, dim), eb = fluid_extent(b, dp, dim);
  for (int k = 0; k < dim; ++k) {
    if (!(eb.lo[k] < ea.hi[k] + 0.5 * dp - tol && ea.lo[k] < eb.hi[k] + 0.5 * dp - tol))
      return false;
  }
  return true;
}

void check_fluid_blocks(std::span<const TableReader> readers, const CaseSpec& spec) {
  const int dim = spec.dimension;
  const auto& blocks = spec.fluid_blocks;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const TableReader& r = readers[i];
    const FluidBlock& b = blocks[i];
    check_not_empty(r, b, spec, blocks.size() == 1);
    if (spec.domain_min) {
      const char* lo = is_round(b) ? "center" : "min";
      const char* hi = is_round(b) ? "center" : "max";
      check_inside(r, shape_extent(b, dim), spec, lo, hi, "the block's particles");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (!blocks_overlap(blocks[j], b, spec.dp, dim)) continue;
      r.fail(is_round(b) ? "center" : "min",
             fmt::format("overlaps fluid_block.{}: particles of the two blocks would lie within "
                         "dp/2 of each other, some on top of each other (move the block; lattice "
                         "boxes that share a face both fill it: start one dp further, or use "
                         "fill = \"cells\")",
                         j));
    }
  }
}

// Tank walls: layers x dp >= 2h; box walls: as many nodes as that along every axis (unless the
// block says thin = true).
void check_wall_thickness(const TableReader& r, const WallBlock& w, const CaseSpec& spec) {
  if (w.thin) return;                        // asked for: a replica of another code's case
  const double need = 2.0 * spec.h_over_dp;  // the support 2h in units of dp
  const double support = need * spec.dp;
  const auto min_nodes = static_cast<long>(std::ceil(need - 1e-9));
  if (w.shape == WallShape::tank) {
    r.require("layers", w.layers >= need - 1e-9,
              fmt::format("{} layers x dp = {:g} m are thinner than the kernel support 2h = {:g} m "
                          "(h = {:g} dp): fluid near the wall would see through it (give layers "
                          ">= {})",
                          w.layers, w.layers * spec.dp, support, spec.h_over_dp, min_nodes));
    return;
  }
  for (int k = 0; k < spec.dimension; ++k) {
    const double n = nodes_between(w.min[k], w.max[k], spec.dp);
    r.require(
        "max", n >= need - 1e-9,
        fmt::format("the box is {} node(s) x dp = {:g} m thick along {}, thinner than the "
                    "kernel support 2h = {:g} m: fluid near it would see through it (give "
                    "it >= {} nodes, max - min >= {:g} m)",
                    n, n * spec.dp, axis_name(k), support, min_nodes, (min_nodes - 1) * spec.dp));
  }
}

void check_walls(std::span<const TableReader> readers, const CaseSpec& spec) {
  for (std::size_t i = 0; i < spec.wall_blocks.size(); ++i) {
    const TableReader& r = readers[i];
    const WallBlock& w = spec.wall_blocks[i];
    check_wall_thickness(r, w, spec);
    if (!spec.domain_min) continue;
    const std::string what = w.shape == WallShape::tank
                                 ? fmt::format("the tank's {} layers", w.layers)
                                 : std::string("the block's particles");
    check_inside(r, wall_extent(w, spec.dp, spec.dimension), spec, "min", "max", what);
  }
}

// Without [domain]: each refinement box inside the default domain (block_extent.hpp), computed
// from where the particles will be.
void check_refinements_in_default_domain(std::span<const TableReader> readers,
                                         const CaseSpec& spec) {
  if (spec.domain_min || spec.refinements.empty()) return;
  const int dim = spec.dimension;
  const Extent all = default_domain_extent(spec);
  const std::string reason = fmt::format(
      "refinement box must lie inside the domain; without [domain] that is the particles' "
      "bounding box plus a margin, {} .. {} (set [domain] min and max to choose it)",
      vec_g(all.lo, dim), vec_g(all.hi, dim));
  for (std::size_t i = 0; i < spec.refinements.size(); ++i) {
    for (int k = 0; k < dim; ++k) {
      readers[i].require("min", spec.refinements[i].min[k] >= all.lo[k], reason);
      readers[i].require("max", spec.refinements[i].max[k] <= all.hi[k], reason);
    }
  }
}

}  // namespace

void check_geometry(const GeometryReaders& r, const CaseSpec& spec) {
  check_fluid_blocks(r.fluid, spec);
  check_walls(r.wall, spec);
  check_refinements_in_default_domain(r.refinement, spec);
}

}  // namespace vrsph::case_detail
