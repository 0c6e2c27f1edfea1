// The mixed precision of the three surface passes (numerics.precision = "mixed",
// core/precision.hpp: float candidate blocks and pair terms, per-particle results in double)
// against double on the same static drops, 2D and 3D, jittered and far from the origin: lambda,
// grad C, div r, the Shepard sum, the normal, the curvature and the capillary acceleration
// agree to float accuracy relative to each field's largest value, and the same particles get a
// normal. Also: pass 2's skip of sure-zero normals changes no field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "field_compare.hpp"
#include "surface_tension_fixtures.hpp"

namespace vrsph {
namespace {

using namespace st_fixtures;

// Every surface field of a static set, flattened.
struct Fields {
  std::vector<double> lambda, grad_c, div_r, shepard, normal, curvature, acc;
  std::size_t with_normal = 0;
};

template <int D>
Fields surface_fields(const std::vector<Vec<D>>& pos, double dp, Precision precision) {
  Static<D> s = make_static<D>(pos, dp);
  s.prm.precision = precision;
  surface_sums(s.prm, s.ps, s.grid, s.sf);
  surface_tension_force(s.prm, s.ps, s.grid, s.sf);
  Fields f;
  for (std::size_t i = 0; i < s.ps.size(); ++i) {
    f.lambda.push_back(s.sf.lambda[i]);
    f.div_r.push_back(s.sf.div_r[i]);
    f.shepard.push_back(s.sf.shepard[i]);
    f.curvature.push_back(s.sf.curvature[i]);
    for (int k = 0; k < D; ++k) {
      f.grad_c.push_back(s.sf.grad_c[i][k]);
      f.normal.push_back(s.sf.normal[i][k]);
      f.acc.push_back(s.sf.acc_st[i][k]);
    }
    f.with_normal += norm2(s.sf.normal[i]) > 0.0;
  }
  return f;
}

using test::max_rel_diff;

// Moves every particle by up to 0.05 dp at random (seeded: no lattice symmetry left to make
// sums cancel exactly) and the whole set far from the origin.
template <int D>
std::vector<Vec<D>> jitter_and_shift(std::vector<Vec<D>> pos, double dp, double shift) {
  std::mt19937 gen(12345);
  std::uniform_real_distribution<double> u(-0.05 * dp, 0.05 * dp);
  for (Vec<D>& x : pos)
    for (int k = 0; k < D; ++k) x[k] += u(gen) + shift;
  return pos;
}

template <int D>
void check_mixed_against_double(const std::vector<Vec<D>>& pos, double dp) {
  const Fields d = surface_fields<D>(pos, dp, Precision::double_precision);
  const Fields m = surface_fields<D>(pos, dp, Precision::mixed);
  const double e_lambda = max_rel_diff(d.lambda, m.lambda);
  const double e_grad_c = max_rel_diff(d.grad_c, m.grad_c);
  const double e_div_r = max_rel_diff(d.div_r, m.div_r);
  const double e_shepard = max_rel_diff(d.shepard, m.shepard);
  const double e_normal = max_rel_diff(d.normal, m.normal);
  const double e_kappa = max_rel_diff(d.curvature, m.curvature);
  const double e_acc = max_rel_diff(d.acc, m.acc);
  std::printf(
      "[ surface mixed %dD ] %zu particles, %zu / %zu with a normal; largest relative "
      "differences: lambda %.1e, grad C %.1e, div r %.1e, Shepard %.1e, normal %.1e, "
      "curvature %.1e, a_st %.1e\n",
      D, pos.size(), d.with_normal, m.with_normal, e_lambda, e_grad_c, e_div_r, e_shepard, e_normal,
      e_kappa, e_acc);
  EXPECT_EQ(d.with_normal, m.with_normal) << "the same particles get a normal";
  // Float carries 6e-8 per operation; the sums run over 20-60 pairs in 8 lanes.
  EXPECT_LT(e_lambda, 2e-6);
  EXPECT_LT(e_grad_c, 2e-6);
  EXPECT_LT(e_div_r, 2e-6);
  EXPECT_LT(e_shepard, 2e-6);
  EXPECT_LT(e_normal, 1e-5);
  EXPECT_LT(e_kappa, 1e-5);
  EXPECT_LT(e_acc, 1e-5);
}

TEST(MixedSurfacePasses, CircleAgreesWithDoubleToFloatAccuracy) {
  const double dp = 1e-4;
  check_mixed_against_double<2>(jitter_and_shift(droplet_circle(dp, "lattice"), dp, 0.0), dp);
}

TEST(MixedSurfacePasses, CircleFarFromTheOriginAgreesWithDouble) {
  const double dp = 1e-4;  // 10 m away: r_ij is 1e-5 of |x|, below float's resolution of x
  check_mixed_against_double<2>(jitter_and_shift(droplet_circle(dp, "lattice"), dp, 10.0), dp);
}

TEST(MixedSurfacePasses, SphereAgreesWithDoubleToFloatAccuracy) {
  const double dp = 2e-4;
  check_mixed_against_double<3>(jitter_and_shift(sphere_lattice(2e-3, dp), dp, 3.0), dp);
}

// Pass 2 skips the sweep of a particle whose normal is sure to vanish (a bound from G_i and the
// block's lambda range, solver/normal_bound.hpp): the normals, curvature and capillary
// acceleration are bit for bit those of sweeping every particle, in both precisions and with
// each cell layout (the ranges are built per cell and per row of a block); and, where the drop
// is wide enough for blocks that reach no surface (expect_skips), the bound does skip.
template <int D>
void check_skip_changes_nothing(const std::vector<Vec<D>>& pos, double dp, Precision precision,
                                CellLayout cells, bool expect_skips) {
  SCOPED_TRACE(testing::Message() << "cells per support " << cells.cells_per_support
                                  << ", per block " << cells.cells_per_block);
  Static<D> a = make_static<D>(pos, dp, 1.3, cells), b = make_static<D>(pos, dp, 1.3, cells);
  a.prm.precision = b.prm.precision = precision;
  surface_sums(a.prm, a.ps, a.grid, a.sf);
  surface_sums(b.prm, b.ps, b.grid, b.sf);
  ASSERT_EQ(a.sf.grad_w.size(), a.ps.size()) << "surface tension on: pass 1 sums G";
  b.sf.grad_w.clear();  // no bound: every particle swept
  surface_tension_force(a.prm, a.ps, a.grid, a.sf);
  surface_tension_force(b.prm, b.ps, b.grid, b.sf);
  std::size_t with_normal = 0, interior = 0, skipped = 0;
  for (std::size_t i = 0; i < a.ps.size(); ++i) {
    for (int k = 0; k < D; ++k) {
      EXPECT_EQ(a.sf.normal[i][k], b.sf.normal[i][k]) << i;
      EXPECT_EQ(a.sf.acc_st[i][k], b.sf.acc_st[i][k]) << i;
    }
    EXPECT_EQ(a.sf.curvature[i], b.sf.curvature[i]) << i;
    with_normal += norm2(a.sf.normal[i]) > 0.0;
    interior += a.sf.lambda[i] > 0.95;
    const double limit = a.prm.surface_tension.normal_epsilon * a.sf.lambda[i] / a.prm.h;
    NormalsScratch<int> sc;
    const std::int64_t cell = a.grid.particle_cells()[i];
    lambda_range<D>(a.grid, cell, a.sf.lambda_ranges, sc);
    double lo = 1e300, hi = -1e300;  // the range over the block's candidates, one by one
    a.grid.for_each_block_run(
        a.grid.block_first(cell), Group::fluid, [&](std::uint32_t b0, std::uint32_t e0) {
          for (std::uint32_t j = b0; j < e0; ++j) {
            const double l =
                precision == Precision::mixed ? double(float(a.sf.lambda[j])) : a.sf.lambda[j];
            lo = std::min(lo, l), hi = std::max(hi, l);
          }
        });
    EXPECT_EQ(sc.lo, lo) << i;
    EXPECT_EQ(sc.hi, hi) << i;
    if (a.sf.lambda[i] >= a.prm.surface_tension.lambda_threshold) {
      skipped += normal_surely_zero<D>(sc.lo, sc.hi, a.sf.lambda[i], a.sf.l_corr[i], a.sf.grad_w[i],
                                       limit);
    }
  }
  EXPECT_GT(with_normal, 0u);
  EXPECT_GT(interior, a.ps.size() / 4) << "a drop with an interior, where the skip acts";
  if (expect_skips) {
    EXPECT_GT(skipped, interior / 4) << "the bound skips part of the interior";
  }
}

template <int D>
void check_skip_all(const std::vector<Vec<D>>& pos, double dp, bool expect_skips) {
  for (const CellLayout cells : {CellLayout{2, 2}, CellLayout{1, 1}, CellLayout{2, 1}}) {
    check_skip_changes_nothing<D>(pos, dp, Precision::mixed, cells, expect_skips);
    check_skip_changes_nothing<D>(pos, dp, Precision::double_precision, cells, expect_skips);
  }
}

TEST(MixedSurfacePasses, NormalSkipChangesNothing2D) {
  const double dp = 5e-5;
  check_skip_all<2>(jitter_and_shift(droplet_circle(dp, "lattice"), dp, 0.0), dp, true);
}

TEST(MixedSurfacePasses, NormalSkipChangesNothing3D) {
  const double dp = 2e-4;
  // 10 dp in radius: every block reaches the surface, so nothing is skipped; the fields must
  // still agree.
  check_skip_all<3>(jitter_and_shift(sphere_lattice(2e-3, dp), dp, 0.0), dp, false);
}

}  // namespace
}  // namespace vrsph
