// Particle shifting (docs/physics.md section 7): the displacement formula (physics/shifting.hpp)
// and the sums it is fed from (surface_sums: grad C, div r), then short droplet runs with both
// models.
//  - an undisturbed lattice interior has grad C = 0, so no displacement (lind and skillen);
//  - each component is clamped to 0.1 dp; zero below the free-surface threshold T on div r, and
//    scaled by (div r - T)/(D - T) above it; skillen scales with |v| dt (zero at rest);
//  - droplet_2d at dp = 1e-4 with skillen and with lind: finite state, max speed < 0.2 m/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "case_util.hpp"
#include "vrsph/core/kernel.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/surface_pass.hpp"

namespace vrsph {
namespace {

constexpr double kRho0 = 1000.0;

template <int D>
ShiftingLevel shifting_params(ShiftingModel model, double dp) {
  ShiftingLevel s;
  s.model = model;
  s.coefficient = model == ShiftingModel::skillen ? 2.0 : 0.05;
  s.surface_threshold = D == 2 ? 1.5 : 2.75;
  s.dp = dp;
  s.h = 1.3 * dp;
  return s;
}

// ---------------------------------------------------------------------------------------------
// Lattice interior: grad C ~ 0 and div r ~ D m (m = 0.974 / 0.979), so no displacement.

// Water at rest with h = 1.3 dp.
template <int D>
SolverParams<D> lattice_params(double dp) {
  SolverParams<D> prm;
  prm.dp = dp;
  prm.h = 1.3 * dp;
  prm.kernel = WendlandC2<D>(prm.h);
  prm.eos = TaitEos(kRho0, 7.0, 10.0);
  prm.mass = kRho0 * std::pow(dp, D);
  return prm;
}

// n x n (x n) fluid particles at the centres of dp cells, the block offset by
// (0.031, -0.017, 0.005) from the origin.
template <int D>
ParticleSet<D> lattice_block(int n, double dp, double mass) {
  ParticleSet<D> ps;
  std::uint64_t id = 0;
  const int nz = D == 3 ? n : 1;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        Vec<D> x;
        x[0] = (a + 0.5) * dp + 0.031;
        x[1] = (b + 0.5) * dp - 0.017;
        if constexpr (D == 3) x[2] = (c + 0.5) * dp + 0.005;
        ps.push_back(id++, Kind::fluid, x, Vec<D>{}, kRho0, mass);
      }
  return ps;
}

// A half-cell grid over the block, 3 dp beyond its first and last particles.
template <int D>
CellGrid<D> grid_around(const ParticleSet<D>& ps, double dp, double support) {
  Vec<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = ps.pos[0][k] - 3.0 * dp;
    hi[k] = ps.pos.back()[k] + 3.0 * dp;
  }
  return CellGrid<D>(lo, hi, support, 2);
}

template <int D>
void check_lattice_interior(int n) {
  const double dp = 1e-4;
  const SolverParams<D> prm = lattice_params<D>(dp);
  ParticleSet<D> ps = lattice_block<D>(n, dp, prm.mass);
  CellGrid<D> grid = grid_around(ps, dp, prm.kernel.support());
  ASSERT_TRUE(grid.sort(ps).empty());
  SurfaceFields<D> sf;
  surface_sums(prm, ps, grid, sf);

  const double dt = 0.2 * prm.h / 10.0, speed = 0.5;
  const ShiftingLevel lind = shifting_params<D>(ShiftingModel::lind, dp);
  const ShiftingLevel skillen = shifting_params<D>(ShiftingModel::skillen, dp);
  double worst_gc = 0.0, worst_dr = 0.0, div_min = 1e9, div_max = -1e9;
  double edge_dr = 0.0;
  std::size_t inner = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    int dmin = n;
    for (int k = 0; k < D; ++k) {
      const double off = k == 0 ? 0.031 : k == 1 ? -0.017 : 0.005;
      const int a = static_cast<int>(std::lround((ps.pos[i][k] - off) / dp - 0.5));
      dmin = std::min({dmin, a, n - 1 - a});
    }
    const Vec<D> dr_l = shifting_displacement<D>(lind, sf.grad_c[i], sf.div_r[i], speed, dt);
    const Vec<D> dr_s = shifting_displacement<D>(skillen, sf.grad_c[i], sf.div_r[i], speed, dt);
    if (dmin >= 3) {  // full support (2h = 2.6 dp)
      ++inner;
      worst_gc = std::max(worst_gc, norm(sf.grad_c[i]) * prm.h);
      worst_dr = std::max({worst_dr, norm(dr_l) / dp, norm(dr_s) / dp});
      div_min = std::min(div_min, sf.div_r[i]);
      div_max = std::max(div_max, sf.div_r[i]);
    } else if (dmin == 1) {  // second row: grad C does not vanish, shifting acts (inwards)
      edge_dr = std::max(edge_dr, norm(dr_l) / dp);
    }
  }
  std::printf(
      "[ shifting %dD ] lattice interior (%zu): max |grad C| h = %.1e, max |dr| / dp = "
      "%.1e, div r %.4f..%.4f; second row max |dr_lind| / dp = %.3f\n",
      D, inner, worst_gc, worst_dr, div_min, div_max, edge_dr);
  ASSERT_GT(inner, 8u);
  EXPECT_LT(worst_gc, 1e-10);
  EXPECT_LT(worst_dr, 1e-10);
  EXPECT_NEAR(div_min, D * (D == 2 ? 0.974 : 0.979), 0.01 * D);
  EXPECT_LT(div_max - div_min, 1e-12);
  EXPECT_GT(edge_dr, 1e-4) << "near the surface grad C is non-zero: the check above can fail";
}

TEST(ShiftingLattice, InteriorDoesNotMove2D) { check_lattice_interior<2>(20); }
TEST(ShiftingLattice, InteriorDoesNotMove3D) { check_lattice_interior<3>(10); }

// ---------------------------------------------------------------------------------------------
// The displacement formula.

TEST(ShiftingDisplacement, ClampsEachComponentAtTenthOfDp) {
  const double dp = 1e-4;
  for (ShiftingModel model : {ShiftingModel::lind, ShiftingModel::skillen}) {
    const ShiftingLevel s = shifting_params<2>(model, dp);
    // Huge gradient: both components at the cap, signs opposite to grad C.
    const Vec<2> big{{3.0e8, -5.0e8}};
    const Vec<2> dr = shifting_displacement<2>(s, big, 2.0, 1.0, 1e-5);
    EXPECT_DOUBLE_EQ(dr[0], -0.1 * dp);
    EXPECT_DOUBLE_EQ(dr[1], 0.1 * dp);
    // One large, one tiny component: only the large one is clamped (per component, not the norm).
    const Vec<2> mixed{{1.0e9, 1.0}};
    const Vec<2> dm = shifting_displacement<2>(s, mixed, 2.0, 1.0, 1e-5);
    EXPECT_DOUBLE_EQ(dm[0], -0.1 * dp);
    const double scale =
        model == ShiftingModel::lind ? s.coefficient * s.h * s.h : s.coefficient * s.h * 1.0 * 1e-5;
    EXPECT_NEAR(dm[1], -scale * 1.0, 1e-12 * scale);
    // 3D as well.
    const ShiftingLevel s3 = shifting_params<3>(model, dp);
    const Vec<3> dr3 = shifting_displacement<3>(s3, Vec<3>{{1e9, -1e9, 1e9}}, 3.0, 1.0, 1e-5);
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(std::abs(dr3[k]), 0.1 * dp);
    EXPECT_LT(dr3[0], 0.0);
    EXPECT_GT(dr3[1], 0.0);
  }
}

TEST(ShiftingDisplacement, LindMagnitudeAndSurfaceScaling) {
  const double dp = 1e-4;
  const ShiftingLevel s = shifting_params<2>(ShiftingModel::lind, dp);
  const double h = s.h, T = s.surface_threshold;
  const Vec<2> gc{{40.0, -25.0}};  // 1/m: small enough to stay below the cap
  // Bulk (div r = D): dr = -A h^2 grad C exactly.
  const Vec<2> bulk = shifting_displacement<2>(s, gc, 2.0, 0.0, 1e-5);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(bulk[k], -0.05 * h * h * gc[k], 1e-15 * dp);
  ASSERT_LT(std::abs(bulk[0]), 0.1 * dp);
  // Lind has no velocity term: the same at any speed or time step.
  const Vec<2> moving = shifting_displacement<2>(s, gc, 2.0, 3.0, 7e-4);
  EXPECT_EQ(moving[0], bulk[0]);
  EXPECT_EQ(moving[1], bulk[1]);
  // Below the threshold: nothing; at the threshold: zero scale; above: linear in div r - T.
  for (double div : {0.0, 0.9, 1.2, T - 1e-9}) {
    const Vec<2> d = shifting_displacement<2>(s, gc, div, 0.0, 1e-5);
    EXPECT_EQ(d[0], 0.0) << "div r = " << div;
    EXPECT_EQ(d[1], 0.0) << "div r = " << div;
  }
  EXPECT_NEAR(norm(shifting_displacement<2>(s, gc, T, 0.0, 1e-5)), 0.0, 1e-30);
  for (double div : {1.6, 1.75, 1.9, 1.948}) {
    const double f = (div - T) / (2.0 - T);
    const Vec<2> d = shifting_displacement<2>(s, gc, div, 0.0, 1e-5);
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(d[k], f * bulk[k], 1e-12 * std::abs(bulk[k])) << div;
  }
  // 3D: T = 2.75, D = 3.
  const ShiftingLevel s3 = shifting_params<3>(ShiftingModel::lind, dp);
  const Vec<3> g3{{10.0, 20.0, -30.0}};
  const Vec<3> b3 = shifting_displacement<3>(s3, g3, 3.0, 0.0, 1e-5);
  const Vec<3> m3 = shifting_displacement<3>(s3, g3, 2.875, 0.0, 1e-5);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b3[k], -0.05 * h * h * g3[k], 1e-15 * dp);
    EXPECT_NEAR(m3[k], 0.5 * b3[k], 1e-12 * std::abs(b3[k]));
  }
  EXPECT_EQ(norm(shifting_displacement<3>(s3, g3, 2.7, 0.0, 1e-5)), 0.0);
}

TEST(ShiftingDisplacement, SkillenScalesWithSpeedTimesDt) {
  const double dp = 1e-4;
  const ShiftingLevel s = shifting_params<2>(ShiftingModel::skillen, dp);
  const Vec<2> gc{{400.0, 250.0}};
  const double dt = 2.6e-6;
  // At rest: no displacement, whatever grad C.
  const Vec<2> rest = shifting_displacement<2>(s, gc, 2.0, 0.0, dt);
  EXPECT_EQ(rest[0], 0.0);
  EXPECT_EQ(rest[1], 0.0);
  EXPECT_EQ(norm(shifting_displacement<2>(s, Vec<2>{{1e12, 1e12}}, 2.0, 0.0, dt)), 0.0);
  // dr = -A h |v| dt grad C, linear in |v| and in dt.
  const Vec<2> d1 = shifting_displacement<2>(s, gc, 2.0, 0.1, dt);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(d1[k], -2.0 * s.h * 0.1 * dt * gc[k], 1e-15 * dp);
  const Vec<2> d2 = shifting_displacement<2>(s, gc, 2.0, 0.2, dt);
  const Vec<2> d3 = shifting_displacement<2>(s, gc, 2.0, 0.1, 2.0 * dt);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(d2[k], 2.0 * d1[k], 1e-12 * std::abs(d1[k]));
    EXPECT_NEAR(d3[k], 2.0 * d1[k], 1e-12 * std::abs(d1[k]));
  }
  // The free-surface rule applies to skillen too.
  EXPECT_EQ(norm(shifting_displacement<2>(s, gc, 1.4, 0.1, dt)), 0.0);
  const Vec<2> half = shifting_displacement<2>(s, gc, 1.75, 0.1, dt);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(half[k], 0.5 * d1[k], 1e-12 * std::abs(d1[k]));
  // model = none: never.
  ShiftingLevel off = s;
  off.model = ShiftingModel::none;
  EXPECT_EQ(norm(shifting_displacement<2>(off, gc, 2.0, 0.1, dt)), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Short droplet runs with each model.

// To t = 2 ms: the lattice start's speed peaks (about 0.19 m/s) come at 0.5 and 2 ms.
void run_droplet(const std::vector<std::string>& extra, const char* label, ShiftingModel model,
                 double coefficient) {
  std::vector<std::string> sets =
      test::droplet_lattice_cen_alone({"resolution.dp=1e-4", "case.end_time=0.002"});
  sets.insert(sets.end(), extra.begin(), extra.end());
  CaseSpec spec = test::load_case("droplet_2d.toml", sets);
  Simulation<2> sim(spec);
  ASSERT_EQ(sim.params().shifting.model, model) << label;
  ASSERT_EQ(sim.params().shifting.coefficient, coefficient) << label;
  double vmax = 0.0, shift_max = 0.0;
  while (sim.time() < 0.002 * (1.0 - 1e-12)) {
    ASSERT_NO_THROW(sim.step()) << label << " at t = " << sim.time();
    const auto& ps = sim.particles();
    for (std::size_t i = 0; i < ps.size(); ++i) {
      vmax = std::max(vmax, norm(ps.vel[i]));
      shift_max = std::max(shift_max, norm(ps.shift[i]));
    }
  }
  const auto& ps = sim.particles();
  bool finite = true;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    finite = finite && std::isfinite(norm2(ps.pos[i])) && std::isfinite(norm2(ps.vel[i])) &&
             std::isfinite(ps.rho[i]);
  }
  std::printf(
      "[ shifting %s ] droplet dp=1e-4 to t = %.3g s (%lld steps): max speed %.4f m/s, "
      "max shift %.3g dp, %zu of %zu fluid particles\n",
      label, sim.time(), static_cast<long long>(sim.step_count()), vmax, shift_max / 1e-4,
      ps.count(Kind::fluid), sim.initial_fluid());
  EXPECT_TRUE(finite) << label;
  EXPECT_NEAR(sim.time(), 0.002, 1e-12) << label;
  EXPECT_LT(vmax, 0.2) << label;
  EXPECT_GT(shift_max, 0.0) << label << ": shifting never moved a particle";
  EXPECT_LE(shift_max, 0.1 * 1e-4 * std::sqrt(2.0) * (1.0 + 1e-12)) << label;
  EXPECT_EQ(ps.count(Kind::fluid), sim.initial_fluid()) << label;
}

TEST(ShiftingRun, DropletSkillen) {
  run_droplet({"numerics.shifting.model=skillen", "numerics.shifting.coefficient=2.0"}, "skillen",
              ShiftingModel::skillen, 2.0);
}
TEST(ShiftingRun, DropletLind) {
  run_droplet({"numerics.shifting.model=lind"}, "lind", ShiftingModel::lind, 0.05);
}

}  // namespace
}  // namespace vrsph
