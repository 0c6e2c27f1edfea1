// Surface tension (docs/physics.md section 6) on static particle sets:
//  - lambda (smallest eigenvalue of the correction matrix M_i) in a lattice block (h = 1.3 dp):
//    bulk 0.9739 (2D) / 0.9789 (3D), outer row of a flat face 0.4870 / 0.4894;
//  - the curvature operator with exact radial normals imposed: kappa = 1/R on the outer ring of a
//    circle on concentric rings, 2/R on the outer shell of a sphere on concentric shells (up to a
//    first-order one-sided bias, about 1/(R - dp)).
// The force, its interior zero and the droplet run: test_surface_tension_force.cpp.
#include <gtest/gtest.h>

#include "surface_tension_fixtures.hpp"

namespace vrsph {
namespace {

using namespace st_fixtures;

// ---------------------------------------------------------------------------------------------
// 1. lambda in the bulk and on a flat surface.

template <int D>
void check_lambda_block(int n, double bulk_lo, double bulk_hi, double face_lo, double face_hi) {
  const double dp = 1e-4;
  Static<D> s = make_static<D>(lattice_block<D>(n, dp), dp);
  surface_sums(s.prm, s.ps, s.grid, s.sf);
  double bmin = 1e9, bmax = -1e9, fmin = 1e9, fmax = -1e9, f2min = 1e9, f2max = -1e9;
  std::size_t nb = 0, nf = 0;
  for (std::size_t i = 0; i < s.ps.size(); ++i) {
    const auto d = face_steps<D>(s.ps.pos[i], n, dp);
    const int dmin = *std::min_element(d.begin(), d.end());
    int others_min = 1 << 20;  // the other axes, for face particles away from edges
    int axis = -1;
    for (int k = 0; k < D; ++k)
      if (d[k] == dmin && axis < 0) axis = k;
    for (int k = 0; k < D; ++k)
      if (k != axis) others_min = std::min(others_min, d[k]);
    const double lam = s.sf.lambda[i];
    if (dmin >= 3) {  // full support (2h = 2.6 dp)
      ++nb;
      bmin = std::min(bmin, lam);
      bmax = std::max(bmax, lam);
    } else if (dmin == 0 && others_min >= 3) {  // outer row of a face, away from edges
      ++nf;
      fmin = std::min(fmin, lam);
      fmax = std::max(fmax, lam);
    } else if (dmin == 1 && others_min >= 3) {
      f2min = std::min(f2min, lam);
      f2max = std::max(f2max, lam);
    }
  }
  std::printf(
      "[ surface %dD ] lambda: bulk %.4f..%.4f (%zu), outer face row %.4f..%.4f (%zu), "
      "second row %.4f..%.4f\n",
      D, bmin, bmax, nb, fmin, fmax, nf, f2min, f2max);
  ASSERT_GT(nb, 8u);
  ASSERT_GT(nf, 8u);
  EXPECT_GT(bmin, bulk_lo);
  EXPECT_LT(bmax, bulk_hi);
  EXPECT_LT(bmax - bmin, 1e-12) << "the bulk of a lattice is uniform";
  EXPECT_GT(fmin, face_lo);
  EXPECT_LT(fmax, face_hi);
  EXPECT_LT(fmax - fmin, 1e-12) << "a flat face row is uniform";
  EXPECT_GT(f2min, fmax) << "lambda rises away from the surface";
  EXPECT_LT(f2max, bmin);
}

TEST(SurfaceTensionLambda, BulkAndFlatSurface2D) {
  check_lambda_block<2>(16, 0.972, 0.976, 0.48, 0.495);
}
TEST(SurfaceTensionLambda, BulkAndFlatSurface3D) {
  check_lambda_block<3>(10, 0.975, 0.983, 0.48, 0.51);
}

// An isolated particle has M = 0: lambda = 0 and L = I (not inverted).
TEST(SurfaceTensionLambda, IsolatedParticle) {
  const double dp = 1e-4;
  Static<2> s = make_static<2>({Vec<2>{{0.0, 0.0}}, Vec<2>{{1.0e-3, 0.0}}}, dp);
  surface_sums(s.prm, s.ps, s.grid, s.sf);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(s.sf.lambda[i], 0.0);
    EXPECT_EQ(s.sf.l_corr[i](0, 0), 1.0);
    EXPECT_EQ(s.sf.l_corr[i](0, 1), 0.0);
  }
  surface_tension_force(s.prm, s.ps, s.grid, s.sf);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(norm(s.sf.acc_st[i]), 0.0);
}

// ---------------------------------------------------------------------------------------------
// 3. Curvature operator with exact radial normals imposed on the outer rows.

// Imposes n = x/|x| where |x| > rim, zero inside (after surface_sums, which clears the normals).
template <int D>
void impose_radial_normals(Static<D>& s, double rim) {
  for (std::size_t i = 0; i < s.ps.size(); ++i) {
    const double r = norm(s.ps.pos[i]);
    s.sf.normal[i] = r > rim ? s.ps.pos[i] * (1.0 / r) : Vec<D>{};
  }
}

// The curvature pass on a static set with exact radial normals on its outer three rows
// (|x| > R - 3 dp, so the outer row's whole support inwards carries normals and the filter S_ij
// cuts none of its neighbours).
template <int D>
Static<D> curvature_with_radial_normals(const std::vector<Vec<D>>& pos, double R, double dp) {
  Static<D> s = make_static<D>(pos, dp);
  surface_sums(s.prm, s.ps, s.grid, s.sf);
  impose_radial_normals(s, R - 3.0 * dp);
  surface_curvature_force(s.prm, s.ps, s.grid, s.sf);
  return s;
}

// Mean, min and max curvature over the particles with r_lo < |x| <= r_hi.
struct LayerStats {
  double mean = 0.0, min = 1e300, max = -1e300;
  std::size_t n = 0;
};

template <int D>
LayerStats layer_curvature(const Static<D>& s, double r_lo, double r_hi) {
  LayerStats st;
  for (std::size_t i = 0; i < s.ps.size(); ++i) {
    const double r = norm(s.ps.pos[i]);
    if (r <= r_lo || r > r_hi) continue;
    const double k = s.sf.curvature[i];
    st.mean += k;
    st.min = std::min(st.min, k);
    st.max = std::max(st.max, k);
    ++st.n;
  }
  if (st.n) st.mean /= static_cast<double>(st.n);
  return st;
}

// The outer ring sits at r = R - dp/2. Its neighbourhood is one-sided (inwards, where 1/r is
// larger), so the corrected gradient of n = x/|x| carries a first-order bias: measured kappa ~ 1/(R
// - 1.03 dp), i.e. kappa R = 1.055 (dp = 1e-4) and 1.026 (dp = 5e-5); against the ring's own
// radius 1.028 and 1.014 (docs/physics.md: within 3%). Checked: within 5% of 1/r_ring,
// within 6% / 3% of 1/R, and the error halves with dp.
TEST(SurfaceTensionCurvature, RadialNormalsOnRingsGiveOneOverR) {
  const double R = 0.002;
  double err_ring[2] = {0.0, 0.0};
  int level = 0;
  for (double dp : {1e-4, 5e-5}) {
    // Three rings (R - dp/2, R - 3dp/2, R - 5dp/2) carry normals.
    const Static<2> s = curvature_with_radial_normals<2>(droplet_circle(dp, "rings"), R, dp);
    const LayerStats outer = layer_curvature(s, R - dp, R);
    const LayerStats second = layer_curvature(s, R - 2.0 * dp, R - dp);
    const double r_ring = R - 0.5 * dp;
    std::printf(
        "[ surface 2D rings dp=%g ] imposed radial normals: outer ring kappa R = %.4f "
        "(%.4f..%.4f, %zu particles), kappa r_ring = %.4f; second ring kappa R = %.4f\n",
        dp, outer.mean * R, outer.min * R, outer.max * R, outer.n, outer.mean * r_ring,
        second.mean * R);
    ASSERT_GT(outer.n, 100u);
    EXPECT_NEAR(outer.mean * r_ring, 1.0, 0.05) << "dp = " << dp;
    EXPECT_NEAR(outer.mean * R, 1.0, dp > 7e-5 ? 0.06 : 0.03) << "dp = " << dp;
    EXPECT_LT(outer.max - outer.min, 0.01 * outer.mean) << "uniform along the ring";
    err_ring[level++] = std::abs(outer.mean * r_ring - 1.0);
    // Particles without a normal get no curvature.
    for (std::size_t i = 0; i < s.ps.size(); ++i) {
      if (norm(s.ps.pos[i]) < R - 3.0 * dp) {
        EXPECT_EQ(s.sf.curvature[i], 0.0);
      }
    }
  }
  EXPECT_LT(err_ring[1], 0.6 * err_ring[0]) << "first-order convergence in dp";
}

// Sphere on concentric shells (Fibonacci points, built here): kappa = 2/R on the outer shell.
TEST(SurfaceTensionCurvature, RadialNormalsOnSphereShellsGiveTwoOverR) {
  const double R = 0.002, dp = 1e-4;
  const Static<3> s = curvature_with_radial_normals<3>(sphere_shells(R, dp), R, dp);
  const LayerStats outer = layer_curvature(s, R - dp, R);
  std::printf(
      "[ surface 3D shells dp=%g ] imposed radial normals: outer shell kappa R / 2 = "
      "%.4f (%.3f..%.3f, %zu particles)\n",
      dp, 0.5 * outer.mean * R, 0.5 * outer.min * R, 0.5 * outer.max * R, outer.n);
  std::printf("[ surface 3D shells dp=%g ] against the shell radius: kappa r_shell / 2 = %.4f\n",
              dp, 0.5 * outer.mean * (R - 0.5 * dp));
  ASSERT_GT(outer.n, 1000u);
  // Same one-sided bias as in 2D: 2/(R - 1.03 dp) expected; the shell itself is at R - dp/2.
  EXPECT_NEAR(0.5 * outer.mean * (R - 0.5 * dp), 1.0, 0.05);
  EXPECT_NEAR(0.5 * outer.mean * R, 1.0, 0.06);
  EXPECT_LT(outer.max - outer.min, 0.02 * outer.mean) << "uniform over the shell";

  // The same on a sphere cut from the lattice (outer-shell average, printed and bounded loosely:
  // the jagged surface spreads the per-particle values).
  const Static<3> l = curvature_with_radial_normals<3>(sphere_lattice(R, dp), R, dp);
  const LayerStats lo = layer_curvature(l, R - dp, R);
  std::printf(
      "[ surface 3D lattice sphere dp=%g ] imposed radial normals: outer shell "
      "kappa R / 2 = %.4f (%.3f..%.3f, %zu particles)\n",
      dp, 0.5 * lo.mean * R, 0.5 * lo.min * R, 0.5 * lo.max * R, lo.n);
  EXPECT_NEAR(0.5 * lo.mean * R, 1.0, 0.1);
}

// curvature_correction (not part of Cen et al.): the same imposed radial normals, now with the
// stencil-consistent curvature. The one-sided first-order bias above (kappa r_ring 1.013-1.028)
// and the truncated set of the inner rows (whose deeper neighbours carry no normal) both go: each
// ring measures its own 1/r (2/r on sphere shells).
TEST(SurfaceTensionCurvature, CorrectedCurvatureGivesEachRingItsRadius) {
  const double R = 0.002;
  for (double dp : {1e-4, 5e-5}) {
    Static<2> s = make_static<2>(droplet_circle(dp, "rings"), dp);
    s.prm.surface_tension.curvature_correction = true;
    surface_sums(s.prm, s.ps, s.grid, s.sf);
    impose_radial_normals(s, R - 3.0 * dp);
    surface_curvature_force(s.prm, s.ps, s.grid, s.sf);
    for (int ring = 0; ring < 3; ++ring) {
      const double r_ring = R - (ring + 0.5) * dp;
      const LayerStats st = layer_curvature(s, r_ring - 0.5 * dp, r_ring + 0.5 * dp);
      std::printf(
          "[ surface 2D rings dp=%g ] corrected curvature, ring %d: kappa r = %.5f "
          "(%.5f..%.5f)\n",
          dp, ring, st.mean * r_ring, st.min * r_ring, st.max * r_ring);
      ASSERT_GT(st.n, 100u);
      EXPECT_NEAR(st.mean * r_ring, 1.0, 0.002) << "dp " << dp << " ring " << ring;
    }
  }
  const double dp = 1e-4;
  Static<3> s = make_static<3>(sphere_shells(R, dp), dp);
  s.prm.surface_tension.curvature_correction = true;
  surface_sums(s.prm, s.ps, s.grid, s.sf);
  impose_radial_normals(s, R - 3.0 * dp);
  surface_curvature_force(s.prm, s.ps, s.grid, s.sf);
  const LayerStats outer = layer_curvature(s, R - dp, R);
  std::printf("[ surface 3D shells dp=%g ] corrected curvature, outer shell: kappa r / 2 = %.5f\n",
              dp, 0.5 * outer.mean * (R - 0.5 * dp));
  EXPECT_NEAR(0.5 * outer.mean * (R - 0.5 * dp), 1.0, 0.005);
}

}  // namespace
}  // namespace vrsph
