// Shepard-corrected kernel interpolation at a point (analysis/shepard.hpp), the probes' and the
// interpolated lines' values:
//  - a constant field is exact to round-off wherever the point counts as inside, in the bulk and
//    next to the free surface, on a jittered lattice with uneven volumes;
//  - a linear field is not exact: the error is grad f times the first moment of the weights,
//    zero at the nodes of a regular lattice, below 0.01 |grad f| dp between them (h = 1.3 dp),
//    below 0.15 |grad f| dp on a lattice jittered by 0.1 dp, and visibly off
//    (> 0.05 |grad f| dp) within h of the free surface, where the support is one-sided;
//  - buffer and wall particles are ignored; the Shepard sum is about 1 in the bulk and the point
//    is outside (no values) beyond the surface.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "vrsph/analysis/shepard.hpp"

namespace vrsph {
namespace {

constexpr double kDp = 0.01, kHdp = 1.3, kRho0 = 1000.0;
const TaitEos kEos(kRho0, 7.0, 10.0);  // p_j comes from rho_j through it (B = 14,285.7 Pa)
constexpr int kN = 20;                 // particles per side: the block [0, 20 dp]^2

struct Cloud {
  ParticleSet<2> ps;
  CellGrid<2> grid;
  WendlandC2<2> kernel{kHdp * kDp};
  FluidPoint<2> at(const Vec<2>& x) const {
    return shepard_point<2>(shepard_sums<2>(x, ps, grid, kernel, kEos), 0);
  }
};

// kN^2 lattice nodes (a + 1/2) dp moved by up to `jitter` dp, p = f(x) (rho = the EOS density of
// f(x)), volume V = m / rho = dp^2 rho0 / rho_v(x), v = (p, -p).
template <class F, class R>
Cloud make_cloud(double jitter, F f, R rho_v) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  Cloud c;
  std::uint64_t id = 0;
  for (int b = 0; b < kN; ++b)
    for (int a = 0; a < kN; ++a) {
      const Vec<2> x{{(a + 0.5 + u(gen)) * kDp, (b + 0.5 + u(gen)) * kDp}};
      const double rho = kEos.density(f(x));
      c.ps.push_back(id++, Kind::fluid, x, Vec<2>{{f(x), -f(x)}}, rho,
                     rho * kRho0 * kDp * kDp / rho_v(x));
    }
  c.ps.resize(c.ps.size());
  const double margin = 10 * kDp;
  c.grid = CellGrid<2>(Vec<2>{{-margin, -margin}}, Vec<2>{{kN * kDp + margin, kN * kDp + margin}},
                       c.kernel.support(), 2);
  c.grid.sort(c.ps);
  return c;
}

double linear(const Vec<2>& x) { return 3.0 + 2000.0 * x[0] - 700.0 * x[1]; }
const double kGradNorm = std::hypot(2000.0, 700.0);

TEST(Shepard, ConstantFieldIsExactWhereverInside) {
  // Uneven volumes (rho varies by 20%) and a jitter of 0.2 dp: the division by S still
  // reproduces a constant exactly.
  const Cloud c = make_cloud(
      0.2, [](const Vec<2>&) { return 7.25; },
      [](const Vec<2>& x) { return kRho0 * (1.0 + 10.0 * x[0]); });
  int inside = 0;
  for (double y = 0.3; y < kN; y += 0.37)
    for (double x = -0.5; x < kN + 0.5; x += 0.41) {
      const FluidPoint<2> f = c.at(Vec<2>{{x * kDp, y * kDp}});
      if (!f.inside()) continue;
      ++inside;
      EXPECT_NEAR(f.p, 7.25, 1e-10) << x << " " << y;  // p(rho(7.25)): round-off of B
      EXPECT_NEAR(f.vel[0], 7.25, 1e-12);
      EXPECT_NEAR(f.vel[1], -7.25, 1e-12);
    }
  EXPECT_GT(inside, 1000);
}

// The largest |p - linear| / (|grad| dp) over the points (k step + 1/2) dp of the bulk (>= 3h
// from every face): with step 1, the lattice nodes.
double bulk_linear_error(const Cloud& c, double step) {
  const double lo = 3.0 * kHdp, hi = kN - 3.0 * kHdp;
  const double first = 0.5 + std::ceil((lo - 0.5) / step) * step;
  double worst = 0.0;
  for (double y = first; y <= hi; y += step)
    for (double x = first; x <= hi; x += step) {
      const Vec<2> q{{x * kDp, y * kDp}};
      const FluidPoint<2> f = c.at(q);
      EXPECT_TRUE(f.inside());
      worst = std::max(worst, std::abs(f.p - linear(q)) / (kGradNorm * kDp));
    }
  return worst;
}

TEST(Shepard, LinearFieldToTheStatedToleranceInTheBulk) {
  const auto rho0 = [](const Vec<2>&) { return kRho0; };
  const Cloud lattice = make_cloud(0.0, linear, rho0);
  // At the nodes of a regular lattice the neighbours sit symmetrically: no first moment.
  EXPECT_LT(bulk_linear_error(lattice, 1.0), 1e-10);
  const double regular = bulk_linear_error(lattice, 0.125);
  const double jittered = bulk_linear_error(make_cloud(0.1, linear, rho0), 0.125);
  std::printf(
      "[ shepard ] linear field, bulk: max error / (|grad f| dp) = %.2e (lattice), "
      "%.2e (jitter 0.1 dp)\n",
      regular, jittered);
  EXPECT_GT(regular, 1e-4) << "between the nodes the lattice's first moment is not zero";
  EXPECT_LT(regular, 0.01);
  EXPECT_LT(jittered, 0.15);
  EXPECT_GT(jittered, regular) << "disorder adds a first moment";
  // Next to the surface the support is one-sided and the Shepard form is off by O(h) |grad|.
  const Cloud c = make_cloud(0.0, linear, rho0);
  const Vec<2> edge{{0.5 * kDp, 10.0 * kDp}};
  const FluidPoint<2> f = c.at(edge);
  ASSERT_TRUE(f.inside());
  EXPECT_GT(std::abs(f.p - linear(edge)) / (kGradNorm * kDp), 0.05);
}

TEST(Shepard, SumIsOneInsideAndPointsBeyondTheSurfaceAreOutside) {
  const Cloud c = make_cloud(0.0, linear, [](const Vec<2>&) { return kRho0; });
  const FluidPoint<2> mid = c.at(Vec<2>{{10.0 * kDp, 10.0 * kDp}});
  EXPECT_NEAR(mid.shepard, 1.0, 0.02);
  EXPECT_EQ(mid.level, 0);
  // One dp beyond the outer row (dp/2 beyond the block's face): below 1/2, outside.
  const FluidPoint<2> out = c.at(Vec<2>{{-0.5 * kDp, 10.0 * kDp}});
  EXPECT_LT(out.shepard, kShepardInside);
  EXPECT_GT(out.shepard, 0.0);
  EXPECT_FALSE(out.inside());
  EXPECT_EQ(out.level, -1);
  EXPECT_EQ(out.p, 0.0);
  // Far away: no particle in reach, a zero sum.
  EXPECT_EQ(c.at(Vec<2>{{-8.0 * kDp, 10.0 * kDp}}).shepard, 0.0);
  EXPECT_EQ(c.at(Vec<2>{{1e3, 1e3}}).shepard, 0.0);
}

TEST(Shepard, BufferAndWallParticlesAreIgnored) {
  Cloud c = make_cloud(
      0.0, [](const Vec<2>&) { return 5.0; }, [](const Vec<2>&) { return kRho0; });
  const Vec<2> q{{10.0 * kDp, 10.0 * kDp}};
  const FluidPoint<2> before = c.at(q);
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    if (std::abs(c.ps.pos[i][0] - q[0] - 0.5 * kDp) > 0.1 * kDp) continue;  // the column at +dp/2
    c.ps.kind[i] = (c.ps.id[i] % 2 == 0) ? Kind::buffer : Kind::wall;
  }
  c.grid.sort(c.ps);
  for (std::size_t i = 0; i < c.ps.size(); ++i)
    if (c.ps.kind[i] != Kind::fluid) c.ps.rho[i] = kEos.density(1e9);
  const FluidPoint<2> after = c.at(q);
  ASSERT_TRUE(after.inside());
  EXPECT_NEAR(after.p, 5.0, 1e-10);
  EXPECT_LT(after.shepard, before.shepard - 0.1) << "the column no longer counts";
}

}  // namespace
}  // namespace vrsph
