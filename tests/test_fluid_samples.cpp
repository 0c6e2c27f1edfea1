// The fluid's values at points of a multi-level run (driver/fluid_samples.hpp): on the
// two-level drop (cases/droplet_vr_2d.toml, fine level over x >= 0) started at a uniform
// pressure, the interpolated diameter takes the fine level where it covers the point and the
// coarse one where it does not, never leaves a point inside the drop without values (also at the
// interface, where the levels' sums are added: the point on the box face), reproduces the constant
// pressure exactly there, and leaves the points on the rim and far away outside.
#include <gtest/gtest.h>

#include <cmath>

#include "case_util.hpp"
#include "vrsph/driver/fluid_samples.hpp"

namespace vrsph {
namespace {

TEST(FluidSamples, TwoLevelDiameterUsesTheFinestCoveringLevel) {
  CaseSpec spec = test::load_case("droplet_vr_2d.toml",
                                  {"fluid_block.0.pressure=36.4", "fluid_block.0.fill=\"lattice\"",
                                   "numerics.vres_shepard_fill=0"});
  Simulation<2> sim(spec);
  ASSERT_EQ(sim.level_count(), 2u);
  const double dp0 = sim.level(0).prm.dp, h0 = sim.level(0).prm.h, h1 = sim.level(1).prm.h;
  const auto points = interpolate_line(sim, spec.lines.front());
  ASSERT_EQ(points.size(), 161u) << "every dp/2 of the fine level across 4 mm";
  int fine = 0, coarse = 0;
  for (const auto& q : points) {
    const double x = q.x[0];
    if (std::abs(x) > 0.002 - 0.25 * dp0) {  // on the rim: no fluid beyond the outer rows
      EXPECT_FALSE(q.f.inside()) << x;
      continue;
    }
    if (std::abs(x) > 0.002 - dp0) continue;  // the last half dp: either
    ASSERT_TRUE(q.f.inside()) << "no values at x = " << x << ", S = " << q.f.shepard;
    EXPECT_NEAR(q.f.p, 36.4, 1e-9) << x;
    EXPECT_NEAR(q.f.vel[0], 0.0, 1e-15) << x;
    if (x > 2.0 * h1) {
      EXPECT_EQ(q.f.level, 1) << x;
      ++fine;
    }
    if (x < -2.0 * h0) {
      EXPECT_EQ(q.f.level, 0) << x;
      ++coarse;
    }
  }
  EXPECT_GT(fine, 60);
  EXPECT_GT(coarse, 60);
  // On the box face (x = 0) each level's fluid sum is about 0.497, below 1/2: the point gets the
  // added sums (about 0.99) instead of none.
  const auto& face = points[80];
  ASSERT_EQ(face.x[0], 0.0);
  EXPECT_TRUE(face.f.inside());
  EXPECT_GT(face.f.shepard, 0.9);
  const FluidPoint<2> far = sample_fluid(sim, Vec<2>{{1.0, 1.0}});
  EXPECT_FALSE(far.inside());
  EXPECT_EQ(far.shepard, 0.0);
}

}  // namespace
}  // namespace vrsph
