// The set-up estimate against the fill it stands for (setup/block_extent.hpp): counts and
// extents computed without making particles equal those of build_particles for boxes and walls
// (to within the outer row for round blocks), and the default domain's margin.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "vrsph/setup/block_extent.hpp"
#include "vrsph/setup/geometry.hpp"

namespace {

using namespace vrsph;

CaseSpec spec_of(int dim, double dp) {
  CaseSpec s;
  s.dimension = dim;
  s.dp = dp;
  return s;
}

FluidBlock box(const Vec3d& min, const Vec3d& max, FillMode fill = FillMode::lattice) {
  FluidBlock b;
  b.shape = BlockShape::box;
  b.min = min;
  b.max = max;
  b.fill = fill;
  return b;
}

FluidBlock ball(int dim, const Vec3d& c, double r, FillMode fill = FillMode::lattice) {
  FluidBlock b;
  b.shape = dim == 2 ? BlockShape::circle : BlockShape::sphere;
  b.center = c;
  b.radius = r;
  b.fill = fill;
  return b;
}

WallBlock wall(WallShape shape, const Vec3d& min, const Vec3d& max, int layers) {
  WallBlock w;
  w.shape = shape;
  w.min = min;
  w.max = max;
  w.layers = layers;
  return w;
}

// The particles' bounding box and count from the real fill of one block.
template <int D>
std::size_t fill_bounds(const CaseSpec& s, Extent& e) {
  const auto init = build_particles<D>(s);
  for (int k = 0; k < D; ++k) e.lo[k] = 1e300, e.hi[k] = -1e300;
  for (const auto& x : init.particles.pos) {
    for (int k = 0; k < D; ++k)
      e.lo[k] = std::min(e.lo[k], x[k]), e.hi[k] = std::max(e.hi[k], x[k]);
  }
  return init.particles.size();
}

template <int D>
void expect_box_like(const CaseSpec& s, double count, const Extent& est) {
  Extent got;
  const std::size_t n = fill_bounds<D>(s, got);
  EXPECT_EQ(count, static_cast<double>(n));
  for (int k = 0; k < D; ++k) {
    EXPECT_NEAR(est.lo[k], got.lo[k], 1e-12) << "axis " << k;
    EXPECT_NEAR(est.hi[k], got.hi[k], 1e-12) << "axis " << k;
  }
}

TEST(BlockExtent, BoxesAndWallsMatchTheFillExactly) {
  // Sides that are and are not whole multiples of dp, lattice and cells, tanks of 3 and 4
  // layers, a box wall; 2D and 3D.
  const double dp = 0.01;
  for (const FluidBlock& b :
       {box({0.01, 0.01, 0}, {0.4, 0.205, 0}), box({0.0, 0.0, 0}, {0.3, 0.2, 0}, FillMode::cells),
        box({0.003, 0.0, 0}, {0.2571, 0.1, 0}, FillMode::cells)}) {
    CaseSpec s = spec_of(2, dp);
    s.fluid_blocks = {b};
    expect_box_like<2>(s, fluid_count(b, dp, 2), fluid_extent(b, dp, 2));
  }
  for (const WallBlock& w : {wall(WallShape::tank, {0, 0, 0}, {1.0, 0.5, 0}, 3),
                             wall(WallShape::tank, {0, 0, 0}, {0.735, 0.5, 0}, 4),
                             wall(WallShape::box, {0.1, 0.1, 0}, {0.2, 0.13, 0}, 3)}) {
    CaseSpec s = spec_of(2, dp);
    s.wall_blocks = {w};
    expect_box_like<2>(s, wall_count(w, dp, 2), wall_extent(w, dp, 2));
  }
  const FluidBlock b3 = box({0.0, 0.0, 0.0}, {0.1, 0.05, 0.08});
  CaseSpec s3 = spec_of(3, dp);
  s3.fluid_blocks = {b3};
  expect_box_like<3>(s3, fluid_count(b3, dp, 3), fluid_extent(b3, dp, 3));
  const WallBlock t3 = wall(WallShape::tank, {0, 0, 0}, {0.12, 0.03, 0.09}, 3);
  s3.fluid_blocks.clear();
  s3.wall_blocks = {t3};
  expect_box_like<3>(s3, wall_count(t3, dp, 3), wall_extent(t3, dp, 3));
  // A tank's layers lie outside its min..max (but not above its open top).
  const Extent te = wall_extent(t3, dp, 3);
  EXPECT_NEAR(te.lo[0], -0.02, 1e-12);
  EXPECT_NEAR(te.lo[2], -0.02, 1e-12);
  EXPECT_NEAR(te.hi[2], 0.09, 1e-12);
}

TEST(BlockExtent, RoundBlocksWithinTheirOuterRow) {
  // Volume / dp^D against the lattice and ring fills: within the outer row (perimeter / dp).
  for (const FluidBlock& b : {ball(2, {0.0, 0.0, 0}, 0.1), ball(2, {0.01, -0.02, 0}, 0.0734),
                              ball(2, {0, 0, 0}, 0.1, FillMode::rings)}) {
    CaseSpec s = spec_of(2, 0.005);
    s.fluid_blocks = {b};
    Extent got;
    const auto n = static_cast<double>(fill_bounds<2>(s, got));
    const double outer_row = 2.0 * 3.14159 * b.radius / s.dp;
    EXPECT_NEAR(fluid_count(b, s.dp, 2), n, outer_row);
    const Extent e = fluid_extent(b, s.dp, 2);
    for (int k = 0; k < 2; ++k) EXPECT_TRUE(e.lo[k] <= got.lo[k] && got.hi[k] <= e.hi[k]);
  }
  const FluidBlock b3 = ball(3, {0, 0, 0}, 0.05);
  CaseSpec s3 = spec_of(3, 0.005);
  s3.fluid_blocks = {b3};
  Extent got;
  const auto n = static_cast<double>(fill_bounds<3>(s3, got));
  EXPECT_NEAR(fluid_count(b3, 0.005, 3), n, 4.0 * 3.14159 * 100.0);  // 4 pi (r / dp)^2
}

TEST(BlockExtent, AbsurdSizesGiveLargeCountsNotOverflow) {
  const FluidBlock b = box({0, 0, 0}, {1e20, 1e20, 0});
  EXPECT_GT(fluid_count(b, 1e-3, 2), 1e45);
  EXPECT_TRUE(std::isinf(fluid_count(b, 1e-300, 2)));
  EXPECT_EQ(nodes_between(0.0, 0.5e-3, 1e-3), 1.0);
  EXPECT_EQ(nodes_between(0.0, -1.0, 1e-3), 0.0);
}

TEST(BlockExtent, DefaultMarginIsAtLeastTheFluidExtent) {
  // A 4 x 3 mm body, h = 1.3e-4: the earlier margin was max(0.1 x 4 mm, 4h) = 0.52 mm; now 4 mm
  // on every side, and the cells stay laid from the earlier edge.
  Vec3d lo{0.0, 0.0, 0}, hi{0.004, 0.003, 0}, origin{};
  grow_default_domain(lo, hi, 2, 0.004, Vec3d{}, 1.3e-4, origin);
  EXPECT_DOUBLE_EQ(lo[0], -0.004);
  EXPECT_DOUBLE_EQ(lo[1], -0.004);
  EXPECT_DOUBLE_EQ(hi[0], 0.008);
  EXPECT_DOUBLE_EQ(hi[1], 0.007);
  EXPECT_DOUBLE_EQ(origin[0], -0.00052);
  EXPECT_DOUBLE_EQ(origin[1], -0.00052);
  // With gravity, a further half of the extent upwards (y = vertical), from the larger margin.
  Vec3d lo2{0.0, 0.0, 0}, hi2{1.0, 2.0, 0};
  grow_default_domain(lo2, hi2, 2, 0.5, Vec3d{0.0, 1.0, 0.0}, 0.013, origin);
  EXPECT_DOUBLE_EQ(lo2[1], -0.5);
  EXPECT_DOUBLE_EQ(hi2[1], 2.0 + 0.5 + 1.0);
  EXPECT_DOUBLE_EQ(origin[1], -0.2);
}

}  // namespace
