// Surface tension (PHYSICS.md section 3) on static particle sets, then through a short droplet run:
//  - lambda (smallest eigenvalue of the correction matrix M_i) in a lattice block (h = 1.3 dp):
//    bulk 0.9739 (2D) / 0.9789 (3D), outer row of a flat face 0.4870 / 0.4894;
//  - the curvature operator with exact radial normals imposed: kappa = 1/R on the outer ring of a
//    circle on concentric rings, 2/R on the outer shell of a sphere on concentric shells (up to a
//    first-order one-sided bias, about 1/(R - dp));
//  - the full model on a static circle: the integrated inward force equals the Laplace jump times
//    the perimeter, sum_i V_i F_st,i . (-e_r) = 2 pi R (sigma / R) = 2 pi sigma (rings: within 5%;
//    a Cartesian-lattice circle overshoots, about 1.6x - 1.9x, printed);
//  - no surface force in the interior of a lattice;
//  - droplet_2d at dp = 1e-4: the interior pressure heads towards sigma / R = 36.4 Pa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "case_util.hpp"
#include "vrsph/core/kernel.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/surface_tension.hpp"
#include "vrsph/setup/geometry.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/surface_pass.hpp"

namespace vrsph {
namespace {

constexpr double kRho0 = 1000.0;
constexpr double kSigma = 0.0728;
constexpr double kPi = std::numbers::pi;

template <int D>
SolverParams<D> make_params(double dp, double hdp) {
  SolverParams<D> prm;
  prm.dp = dp;
  prm.h = hdp * dp;
  prm.eta2 = 0.01 * prm.h * prm.h;
  prm.kernel = WendlandC2<D>(prm.h);
  prm.eos = TaitEos(kRho0, 7.0, 10.0);
  prm.mass = kRho0 * std::pow(dp, D);
  prm.sigma = kSigma;
  prm.surface_tension.lambda_threshold = 0.7;
  prm.surface_tension.normal_epsilon = 0.1;
  return prm;
}

// A static particle set (fluid at rest, rho = rho0) with its sorted grid.
template <int D>
struct Static {
  SolverParams<D> prm;
  ParticleSet<D> ps;
  CellGrid<D> grid;
  SurfaceFields<D> sf;
};

template <int D>
Static<D> make_static(const std::vector<Vec<D>>& pos, double dp, double hdp = 1.3) {
  Static<D> s;
  s.prm = make_params<D>(dp, hdp);
  std::uint64_t id = 0;
  Vec<D> lo = pos.front(), hi = pos.front();
  for (const auto& x : pos) {
    s.ps.push_back(id++, Kind::fluid, x, Vec<D>{}, kRho0, s.prm.mass);
    for (int k = 0; k < D; ++k) {
      lo[k] = std::min(lo[k], x[k]);
      hi[k] = std::max(hi[k], x[k]);
    }
  }
  for (int k = 0; k < D; ++k) {
    lo[k] -= 3.0 * dp;
    hi[k] += 3.0 * dp;
  }
  s.grid = CellGrid<D>(lo, hi, s.prm.kernel.support(), 2);
  EXPECT_TRUE(s.grid.sort(s.ps).empty());
  return s;
}

// n^D lattice nodes (a + 1/2) dp + offset: a block with flat faces.
template <int D>
std::vector<Vec<D>> lattice_block(int n, double dp) {
  std::vector<Vec<D>> pos;
  const int nz = D == 3 ? n : 1;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        Vec<D> x;
        x[0] = (a + 0.5) * dp + 0.013;
        x[1] = (b + 0.5) * dp - 0.021;
        if constexpr (D == 3) x[2] = (c + 0.5) * dp + 0.007;
        pos.push_back(x);
      }
  return pos;
}

// Distance of x (a node of lattice_block(n, dp)) to the nearest face, in lattice steps, per axis.
template <int D>
std::array<int, D> face_steps(const Vec<D>& x, int n, double dp) {
  const double off[3] = {0.013, -0.021, 0.007};
  std::array<int, D> d{};
  for (int k = 0; k < D; ++k) {
    const int a = static_cast<int>(std::lround((x[k] - off[k]) / dp - 0.5));
    d[k] = std::min(a, n - 1 - a);
  }
  return d;
}

// The droplet circle (R = 2 mm, centre 0) from the shipped case, lattice or rings fill.
std::vector<Vec<2>> droplet_circle(double dp, const std::string& fill) {
  CaseSpec spec = test::load_case(
      "droplet_2d.toml", {"resolution.dp=" + std::to_string(dp), "fluid_block.0.fill=" + fill});
  const ParticleSet<2> ps = build_particles<2>(spec).particles;
  return ps.pos;
}

// Sphere of radius R on concentric shells at radii (k + 1/2) dp, round(4 pi r^2 / dp^2) points per
// shell on a Fibonacci spiral (each shell turned by a different angle).
std::vector<Vec<3>> sphere_shells(double radius, double dp) {
  std::vector<Vec<3>> pos;
  const long shells = std::lround(radius / dp);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (long k = 0; k < shells; ++k) {
    const double r = (k + 0.5) * dp;
    const long count = std::max(1L, std::lround(4.0 * kPi * r * r / (dp * dp)));
    for (long q = 0; q < count; ++q) {
      const double z = 1.0 - (2.0 * q + 1.0) / static_cast<double>(count);
      const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double th = golden * static_cast<double>(q) + 0.7 * static_cast<double>(k);
      pos.push_back(Vec<3>{{r * rho * std::cos(th), r * rho * std::sin(th), r * z}});
    }
  }
  return pos;
}

// Sphere cut from the lattice (cell centres inside R), as fill = "lattice" builds it.
std::vector<Vec<3>> sphere_lattice(double radius, double dp) {
  std::vector<Vec<3>> pos;
  const long m = static_cast<long>(std::ceil(radius / dp)) + 1;
  for (long c = -m; c < m; ++c)
    for (long b = -m; b < m; ++b)
      for (long a = -m; a < m; ++a) {
        const Vec<3> x{{(a + 0.5) * dp, (b + 0.5) * dp, (c + 0.5) * dp}};
        if (norm2(x) < radius * radius) pos.push_back(x);
      }
  return pos;
}

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
// radius 1.028 and 1.014 (PHYSICS.md: "outer ring within 3%"). Checked: within 5% of 1/r_ring,
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

// ---------------------------------------------------------------------------------------------
// 4. Full model on a static circle: integrated inward force against the Laplace jump.

// sum_i V_i F_st,i . (-e_r) / (2 pi sigma), F_st = rho a_st (force per unit volume).
double integrated_force_ratio(const Static<2>& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.ps.size(); ++i) {
    const double r = norm(s.ps.pos[i]);
    if (r == 0.0) continue;
    const double vol = s.ps.mass[i] / s.ps.rho[i];
    sum += vol * s.ps.rho[i] * dot(s.sf.acc_st[i], s.ps.pos[i] * (-1.0 / r));
  }
  return sum / (2.0 * kPi * kSigma);
}

TEST(SurfaceTensionForce, IntegratedForceMatchesLaplaceOnRings) {
  const double R = 0.002;
  for (double dp : {1e-4, 5e-5}) {
    Static<2> s = make_static<2>(droplet_circle(dp, "rings"), dp);
    surface_sums(s.prm, s.ps, s.grid, s.sf);
    surface_tension_force(s.prm, s.ps, s.grid, s.sf);
    const double ratio = integrated_force_ratio(s);
    // Normals on the outer ring: within a degree of radial, outwards.
    double worst_angle = 0.0;
    Vec<2> net{};
    for (std::size_t i = 0; i < s.ps.size(); ++i) {
      const double r = norm(s.ps.pos[i]);
      net += s.sf.acc_st[i] * s.ps.mass[i];
      if (r > R - dp) {
        ASSERT_GT(norm(s.sf.normal[i]), 0.5) << "outer-ring particle without a normal";
        const double c = dot(s.sf.normal[i], s.ps.pos[i] * (1.0 / r));
        worst_angle = std::max(worst_angle, std::acos(std::min(1.0, c)) * 180.0 / kPi);
        EXPECT_GT(s.sf.curvature[i] * R, 0.5);
        EXPECT_LT(s.sf.curvature[i] * R, 1.5);
      }
    }
    std::printf(
        "[ surface 2D rings dp=%g ] integrated inward force / (2 pi sigma) = %.4f, "
        "outer-ring normals within %.3f deg of radial, |net force| / (2 pi sigma) = %.1e\n",
        dp, ratio, worst_angle, norm(net) / (2.0 * kPi * kSigma));
    EXPECT_NEAR(ratio, 1.0, 0.05) << "dp = " << dp;
    EXPECT_LT(worst_angle, 1.0);
    EXPECT_LT(norm(net) / (2.0 * kPi * kSigma), 0.02) << "a round drop feels no net force";
  }
}

TEST(SurfaceTensionForce, IntegratedForceOnLatticeCircleOvershoots) {
  for (double dp : {1e-4, 5e-5}) {
    Static<2> s = make_static<2>(droplet_circle(dp, "lattice"), dp);
    surface_sums(s.prm, s.ps, s.grid, s.sf);
    surface_tension_force(s.prm, s.ps, s.grid, s.sf);
    const double ratio = integrated_force_ratio(s);
    std::printf(
        "[ surface 2D lattice dp=%g ] integrated inward force / (2 pi sigma) = %.4f "
        "(PHYSICS.md: about %s)\n",
        dp, ratio, dp > 7e-5 ? "1.6" : "1.9");
    EXPECT_GT(ratio, 1.3) << "dp = " << dp;
    EXPECT_LT(ratio, 2.5) << "dp = " << dp;
  }
}

// ---------------------------------------------------------------------------------------------
// 5. No surface force inside a lattice.

template <int D>
void check_interior_zero(int n) {
  const double dp = 1e-4;
  Static<D> s = make_static<D>(lattice_block<D>(n, dp), dp);
  surface_sums(s.prm, s.ps, s.grid, s.sf);
  surface_tension_force(s.prm, s.ps, s.grid, s.sf);
  const double h = s.prm.h;
  std::size_t inner = 0, outer_face = 0;
  for (std::size_t i = 0; i < s.ps.size(); ++i) {
    const auto d = face_steps<D>(s.ps.pos[i], n, dp);
    const int dmin = *std::min_element(d.begin(), d.end());
    if (dmin * dp > 3.0 * h) {
      ++inner;
      EXPECT_EQ(norm(s.sf.normal[i]), 0.0);
      EXPECT_EQ(s.sf.curvature[i], 0.0);
      EXPECT_EQ(norm(s.sf.acc_st[i]), 0.0);
    } else if (dmin == 0) {
      // The outer row does have an outward normal (so the test above can tell).
      int axis = 0;
      for (int k = 0; k < D; ++k)
        if (d[k] == 0) axis = k;
      bool single_face = true;
      for (int k = 0; k < D; ++k)
        if (k != axis && d[k] < 3) single_face = false;
      if (!single_face) continue;
      ++outer_face;
      const Vec<D> n_i = s.sf.normal[i];
      EXPECT_NEAR(norm(n_i), 1.0, 1e-12);
      EXPECT_GT(std::abs(n_i[axis]), 0.999) << "face normal along the face axis";
    }
  }
  std::printf(
      "[ surface %dD ] lattice %d^%d: %zu interior particles (> 3h from faces) with zero "
      "normal, curvature and force; %zu face particles with unit normals\n",
      D, n, D, inner, outer_face);
  EXPECT_GT(inner, 16u);
  EXPECT_GT(outer_face, 8u);
}

TEST(SurfaceTensionForce, ZeroInLatticeInterior2D) { check_interior_zero<2>(30); }
TEST(SurfaceTensionForce, ZeroInLatticeInterior3D) { check_interior_zero<3>(14); }

// ---------------------------------------------------------------------------------------------
// 7. A short droplet run through the library: interior pressure towards sigma / R.

double interior_pressure(Simulation<2>& sim, double R) {
  sim.update_pressure();
  const auto& ps = sim.particles();
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] != Kind::fluid || norm(ps.pos[i]) >= 0.5 * R) continue;
    sum += ps.p[i];
    ++n;
  }
  EXPECT_GT(n, 50u);
  return n ? sum / static_cast<double>(n) : 0.0;
}

// The lattice start rings: the interior pressure swings by +-50 Pa around the Laplace value with a
// period of about 0.5 ms (acoustic), decaying slowly. Checked: the mean over the last 2 ms is
// within 15% of sigma / R, closer than the value at 1 ms, and the swing (RMS about sigma / R) over
// the last 2 ms is smaller than over 0.5 - 2.5 ms.
TEST(SurfaceTensionDroplet, InteriorPressureHeadsToLaplace) {
  const double R = 0.002, laplace = kSigma / R;  // 36.4 Pa
  const double end = 0.01;
  CaseSpec spec = test::load_case("droplet_2d.toml", {"resolution.dp=1e-4", "case.end_time=0.01"});
  Simulation<2> sim(spec);
  double p_1ms = 0.0;
  bool at_1ms = false;
  struct Window {
    double sum = 0.0, sq = 0.0;
    std::size_t n = 0;
    void add(double p, double ref) {
      sum += p;
      sq += (p - ref) * (p - ref);
      ++n;
    }
    double mean() const { return sum / static_cast<double>(n); }
    double rms() const { return std::sqrt(sq / static_cast<double>(n)); }
  } early, late;
  while (sim.time() < end * (1.0 - 1e-12)) {
    sim.step();
    const double t = sim.time();
    const bool in_early = t >= 0.0005 && t <= 0.0025, in_late = t >= end - 0.002;
    if (!(in_early || in_late || (!at_1ms && t >= 0.001))) continue;
    const double p = interior_pressure(sim, R);
    if (!at_1ms && t >= 0.001) {
      p_1ms = p;
      at_1ms = true;
    }
    if (in_early) early.add(p, laplace);
    if (in_late) late.add(p, laplace);
  }
  ASSERT_GT(late.n, 100u);
  ASSERT_GT(early.n, 100u);
  const double p_end = interior_pressure(sim, R);
  std::printf(
      "[ droplet 2D dp=1e-4 ] %lld steps to t = %.3g s: interior pressure %.2f Pa at 1 ms; "
      "0.5-2.5 ms mean %.2f Pa (RMS about sigma/R %.1f Pa); last 2 ms mean %.2f Pa "
      "(RMS %.1f Pa); %.2f Pa at the end; Laplace %.1f Pa\n",
      static_cast<long long>(sim.step_count()), sim.time(), p_1ms, early.mean(), early.rms(),
      late.mean(), late.rms(), p_end, laplace);
  EXPECT_NEAR(sim.time(), end, 1e-12);
  EXPECT_NEAR(late.mean(), laplace, 0.15 * laplace);
  EXPECT_LT(std::abs(late.mean() - laplace), std::abs(p_1ms - laplace));
  EXPECT_LT(late.rms(), early.rms()) << "the pressure swing decays";
}

}  // namespace
}  // namespace vrsph

namespace vrsph {
namespace {

// surface_offset: the curvature of a circle (sphere) of particle radius r referred to the free
// surface dp/2 further out; kept finite for strongly concave values.
TEST(SurfaceTensionOffset, CurvatureReferredToTheSurface) {
  const double r = 1.95e-3, dp = 1e-4;
  EXPECT_NEAR(curvature_at_surface<2>(1.0 / r, dp), 1.0 / (r + 0.5 * dp), 1e-9);
  EXPECT_NEAR(curvature_at_surface<3>(2.0 / r, dp), 2.0 / (r + 0.5 * dp), 1e-9);
  EXPECT_NEAR(curvature_at_surface<2>(-1.0 / r, dp), -1.0 / (r - 0.5 * dp), 1e-9);
  EXPECT_DOUBLE_EQ(curvature_at_surface<2>(0.0, dp), 0.0);
  EXPECT_NEAR(curvature_at_surface<2>(-1.0 / (0.4 * dp), dp), -2.0 / (0.4 * dp), 1e-6);
}

}  // namespace
}  // namespace vrsph
