// Surface tension (docs/physics.md section 6): the full model on a static circle (the integrated
// inward force equals the Laplace jump times the perimeter, sum_i V_i F_st,i . (-e_r) = 2 pi sigma:
// rings within 5%, a Cartesian-lattice circle overshoots about 1.6x - 1.9x, printed), no surface
// force in the interior of a lattice, droplet_2d at dp = 1e-4 heading towards sigma / R = 36.4 Pa,
// and the surface_offset option.
#include <gtest/gtest.h>

#include "surface_tension_fixtures.hpp"

namespace vrsph {
namespace {

using namespace st_fixtures;

// ---------------------------------------------------------------------------------------------
// 4. Full model on a static circle: integrated inward force against the Laplace jump.

// sum_i V_i F_st,i . (-e_r) / (2 pi sigma), F_st = rho a_st (force per unit volume).
double integrated_force_ratio(const Static<2>& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.ps.size(); ++i) {
    const double r = norm(s.ps.pos[i]);
    if (r == 0.0) continue;
    const double vol = s.ps.mass_of(i) / s.ps.rho[i];
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
      net += s.sf.acc_st[i] * s.ps.mass_of(i);
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
        "(docs/physics.md: about %s)\n",
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
  const auto& ps = sim.particles();
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] != Kind::fluid || norm(ps.pos[i]) >= 0.5 * R) continue;
    sum += sim.params().eos.pressure(ps.rho[i]);
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
  CaseSpec spec = test::load_case(
      "droplet_2d.toml",
      test::droplet_lattice_cen_alone({"resolution.dp=1e-4", "case.end_time=0.01"}));
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
