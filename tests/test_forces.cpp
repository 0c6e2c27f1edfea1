// The force pass (solver/forces.cpp) on jittered clouds, 2D and 3D: momentum conservation of the
// antisymmetric pair terms (pressure, laminar and artificial viscosity), antisymmetry of Molteni
// diffusion, the sign of diffusion, Fourtakas removing the hydrostatic part, walls skipped by
// diffusion, ForceStats (pairs, max |a|, viscous dt measure) against brute force, and a Simulation
// whose results are bit-identical for 1 and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <type_traits>
#include <vector>

#include "force_cloud.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/params.hpp"

namespace vrsph {
namespace {

using namespace force_cloud;

template <class T>
class ForcesTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(ForcesTest, Dims);

template <int D>
int side() {
  return D == 2 ? 20 : 9;
}

template <int D>
void expect_momentum_conserved(Cloud<D>& c, const char* what) {
  compute_forces(c.prm, c.ps, c.grid);
  Vec<D> total{};
  double scale = 0.0;
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    total += c.ps.mass_of(i) * c.ps.acc[i];
    scale += c.ps.mass_of(i) * norm(c.ps.acc[i]);
  }
  ASSERT_GT(scale, 0.0) << what;
  std::printf("[ forces %dD ] %s: |sum m a| / sum m |a| = %.2e\n", D, what, norm(total) / scale);
  EXPECT_LT(norm(total), 1e-13 * scale)
      << what << ": |sum m a| / sum m |a| = " << norm(total) / scale;
}

TYPED_TEST(ForcesTest, PairTermsConserveMomentum) {
  constexpr int D = TypeParam::value;
  for (ViscosityModel vm : {ViscosityModel::laminar, ViscosityModel::artificial}) {
    const char* name = vm == ViscosityModel::laminar ? "laminar" : "artificial";
    // Pressure and viscosity together, unequal masses.
    Cloud<D> c = make_cloud<D>(side<D>(), vm, DiffusionModel::none, {0.5, 0.01, 0.05, 0}, 11);
    expect_momentum_conserved(c, name);
    // Viscosity alone: rho = rho0 everywhere, so p = 0.
    Cloud<D> v = make_cloud<D>(side<D>(), vm, DiffusionModel::none, {0.5, 0.0, 0.05, 0}, 12);
    expect_momentum_conserved(v,
                              vm == ViscosityModel::laminar ? "laminar only" : "artificial only");
  }
}

// D_i = sum_j 2 delta h c0 V_j (rho_i - rho_j) F r^2/(r^2 + eta^2): sum_i V_i D_i = 0.
TYPED_TEST(ForcesTest, MolteniDiffusionIsAntisymmetric) {
  constexpr int D = TypeParam::value;
  for (double vel : {0.0, 0.5}) {
    Cloud<D> c = make_cloud<D>(side<D>(), ViscosityModel::laminar, DiffusionModel::none,
                               {vel, 0.01, 0.0, 0}, 21);
    compute_forces(c.prm, c.ps, c.grid);
    const std::vector<double> none = c.ps.drho;
    c.prm.density_diffusion.model = DiffusionModel::molteni;
    compute_forces(c.prm, c.ps, c.grid);
    double total = 0.0, scale = 0.0, rounding = 0.0;
    for (std::size_t i = 0; i < c.ps.size(); ++i) {
      const double vol = c.ps.mass_of(i) / c.ps.rho[i];
      const double d = c.ps.drho[i] - none[i];
      total += vol * d;
      scale += vol * std::abs(d);
      rounding += vol * (std::abs(c.ps.drho[i]) + std::abs(none[i]));
    }
    ASSERT_GT(scale, 0.0);
    std::printf("[ forces %dD ] molteni (v = %.1f): |sum V D| / sum V |D| = %.2e\n", D, vel,
                std::abs(total) / scale);
    EXPECT_LT(std::abs(total), 1e-13 * scale + 1e-14 * rounding) << "vel = " << vel;
  }
}

// A particle denser than its neighbours loses density, and they gain it.
TYPED_TEST(ForcesTest, MolteniDiffusionSmoothsDensity) {
  constexpr int D = TypeParam::value;
  Cloud<D> c = make_cloud<D>(side<D>(), ViscosityModel::laminar, DiffusionModel::molteni,
                             {0.0, 0.0, 0.0, 0}, 31);
  const std::size_t k = c.ps.size() / 2;
  c.ps.rho[k] = 1.01 * kRho0;
  compute_forces(c.prm, c.ps, c.grid);
  EXPECT_LT(c.ps.drho[k], 0.0);
  int gained = 0;
  for (std::size_t j = 0; j < c.ps.size(); ++j) {
    const double r2 = norm2(c.ps.pos[j] - c.ps.pos[k]);
    if (j == k) continue;
    if (r2 < c.prm.kernel.support2) {
      EXPECT_GT(c.ps.drho[j], 0.0);
      ++gained;
    } else {
      EXPECT_EQ(c.ps.drho[j], 0.0);
    }
  }
  EXPECT_GT(gained, 5);
}

// Hydrostatic column (v = 0, rho from the EOS at depth): Fourtakas' term cancels the hydrostatic
// density difference to first order in k z = rho0 g z / B, so what is left is a fraction ~ k H of
// Molteni's term (large at the free surface and the bottom, where the support is one-sided), and
// that fraction falls as 1/c0^2.
template <int D>
double fourtakas_over_molteni(double c0_factor) {
  const int vert = vertical_axis<D>();
  Cloud<D> c = make_cloud<D>(side<D>(), ViscosityModel::laminar, DiffusionModel::none,
                             {0.0, 0.0, 0.0, 0}, 41);
  double top = -1e300, bottom = 1e300;
  for (const auto& x : c.ps.pos) {
    top = std::max(top, x[vert]);
    bottom = std::min(bottom, x[vert]);
  }
  const double g = 9.81, c0 = c0_factor * std::sqrt(g * (top - bottom));
  c.prm.eos = TaitEos(kRho0, 7.0, c0);
  c.prm.density_diffusion.two_delta_h_c0 = 2.0 * 0.1 * c.prm.h * c0;
  c.prm.gravity[vert] = -g;
  c.prm.up[vert] = 1.0;
  c.prm.density_diffusion.set_hydrostatic(c.prm.eos, g);
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    c.ps.rho[i] = c.prm.eos.density(kRho0 * g * (top - c.ps.pos[i][vert]));
  }
  std::map<DiffusionModel, std::vector<double>> d;
  for (DiffusionModel dm :
       {DiffusionModel::none, DiffusionModel::molteni, DiffusionModel::fourtakas}) {
    c.prm.density_diffusion.model = dm;
    compute_forces(c.prm, c.ps, c.grid);
    d[dm] = c.ps.drho;
  }
  double max_m = 0.0, max_f = 0.0;
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    max_m = std::max(max_m, std::abs(d[DiffusionModel::molteni][i] - d[DiffusionModel::none][i]));
    max_f = std::max(max_f, std::abs(d[DiffusionModel::fourtakas][i] - d[DiffusionModel::none][i]));
  }
  EXPECT_GT(max_m, 0.0);
  return max_f / max_m;
}

TYPED_TEST(ForcesTest, FourtakasRemovesHydrostaticPart) {
  constexpr int D = TypeParam::value;
  // c0 = 20 sqrt(g H) (docs/physics.md section 2): k H = gamma / 400 ~ 1.75e-2.
  const double r20 = fourtakas_over_molteni<D>(20.0);
  const double r40 = fourtakas_over_molteni<D>(40.0);
  std::printf(
      "[ forces %dD ] hydrostatic: |D_fourtakas| / |D_molteni| = %.2e (c0 = 20 sqrt(gH)), "
      "%.2e (40 sqrt(gH))\n",
      D, r20, r40);
  EXPECT_LT(r20, 0.05);
  EXPECT_GT(r20, 0.0);
  EXPECT_NEAR(r40 / r20, 0.25, 0.05);  // second-order residual
}

// rho^H(z) = rho0 [(1 + rho0 g z / B)^(1/gamma) - 1] by the folded series (physics/
// density_diffusion.hpp) against expm1 and log1p: in double to 1e-10 of the result up to the
// set-up's bound on |x| = rho0 g |z| / B, in float (third order) to a few float ulp there and at
// practical |x|.
TEST(FourtakasSeries, MatchesThePowerLaw) {
  const TaitEos eos(1000.0, 7.0, 20.0);
  const DiffusionLevel d = diffusion_level(DiffusionParams{}, eos, 9.81, 0.01);
  const HydrostaticSeries<double> in_double(d.hydrostatic);
  const HydrostaticSeries<float> in_float(d.hydrostatic);
  for (const double x : {-1e-2, -3e-3, -1e-4, -1e-6, 1e-6, 1e-4, 3e-3, 1e-2}) {
    const double z = x / d.rho0_g_over_b;
    const double exact = eos.rho0 * std::expm1(std::log1p(x) / eos.gamma);
    EXPECT_NEAR(in_double(z) / exact, 1.0, 1e-10) << "x = " << x;
    const double in_f = in_float(static_cast<float>(z));
    EXPECT_NEAR(in_f / exact, 1.0, std::abs(x) > 1e-3 ? 1e-6 : 4e-7) << "x = " << x;
  }
  EXPECT_EQ(in_double(0.0), 0.0);
  EXPECT_EQ(in_float(0.0f), 0.0f);
}

// Diffusion skips wall neighbours: with v = 0, the fluid density rates do not depend on the wall
// densities (the pressure of the walls does change the accelerations).
TYPED_TEST(ForcesTest, DiffusionIgnoresWallDensity) {
  constexpr int D = TypeParam::value;
  for (DiffusionModel dm : {DiffusionModel::molteni, DiffusionModel::fourtakas}) {
    Cloud<D> c = make_cloud<D>(side<D>(), ViscosityModel::artificial, dm, {0.0, 0.01, 0.0, 3}, 51);
    c.prm.density_diffusion.set_hydrostatic(c.prm.eos, 9.81);
    c.prm.up[vertical_axis<D>()] = 1.0;
    compute_forces(c.prm, c.ps, c.grid);
    const auto drho = c.ps.drho;
    const auto acc = c.ps.acc;
    for (std::size_t i = 0; i < c.ps.size(); ++i) {
      if (c.ps.kind[i] == Kind::wall) c.ps.rho[i] = 1.02 * kRho0;
    }
    compute_forces(c.prm, c.ps, c.grid);
    bool acc_changed = false;
    for (std::size_t i = 0; i < c.ps.size(); ++i) {
      if (c.ps.kind[i] == Kind::wall) continue;
      EXPECT_EQ(c.ps.drho[i], drho[i]) << "fluid particle " << c.ps.id[i];
      acc_changed = acc_changed || !(c.ps.acc[i] == acc[i]);
    }
    EXPECT_TRUE(acc_changed);
  }
}

// ForceStats against brute force: ordered pairs (i != j) within 2h except wall-wall, max |a| over
// fluid, max v_ij . r_ij / (r^2 + eta^2) over the evaluated pairs. Walls get acc = 0.
TYPED_TEST(ForcesTest, StatsMatchBruteForce) {
  constexpr int D = TypeParam::value;
  Cloud<D> c = make_cloud<D>(side<D>(), ViscosityModel::artificial, DiffusionModel::molteni,
                             {0.5, 0.01, 0.0, 3}, 61);
  const ForceStats st = compute_forces(c.prm, c.ps, c.grid);
  const auto& ps = c.ps;
  std::uint64_t pairs = 0;
  double max_visc = -1e300, max_acc = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] == Kind::wall) {
      EXPECT_EQ(norm2(ps.acc[i]), 0.0);
    } else {
      max_acc = std::max(max_acc, norm(ps.acc[i]));
    }
    for (std::size_t j = 0; j < ps.size(); ++j) {
      if (j == i || (ps.kind[i] == Kind::wall && ps.kind[j] == Kind::wall)) continue;
      const Vec<D> r_ij = ps.pos[i] - ps.pos[j];
      const double r2 = norm2(r_ij);
      if (r2 >= c.prm.kernel.support2) continue;
      ++pairs;
      max_visc = std::max(max_visc, dot(ps.vel[i] - ps.vel[j], r_ij) / (r2 + c.prm.eta2));
    }
  }
  EXPECT_GT(ps.count(Kind::wall), 0u);
  EXPECT_EQ(st.pairs, pairs);
  EXPECT_NEAR(st.max_acc, max_acc, 1e-12 * max_acc);
  EXPECT_NEAR(st.max_visc_dt, max_visc, 1e-12 * std::abs(max_visc));
}

// A small dam break stepped with 1 and 2 threads from the same start: bit-identical states.
template <int D>
CaseSpec dam_break_spec() {
  CaseSpec s;
  s.name = "thread_check";
  s.dimension = D;
  s.fluid.gravity = {0.0, 0.0, 0.0};
  s.fluid.gravity[static_cast<std::size_t>(vertical_axis<D>())] = -9.81;
  s.numerics.viscosity.model = ViscosityModel::artificial;
  s.numerics.viscosity.alpha = 0.1;
  s.numerics.density_diffusion.model = DiffusionModel::fourtakas;
  FluidBlock f;
  f.shape = BlockShape::box;
  WallBlock w;
  w.shape = WallShape::tank;
  w.layers = 3;
  if constexpr (D == 2) {
    s.dp = 0.01;
    f.min = {0.01, 0.01, 0.0};
    f.max = {0.4, 0.4, 0.0};
    w.min = {0.0, 0.0, 0.0};
    w.max = {1.0, 0.6, 0.0};
  } else {
    s.dp = 0.02;
    f.min = {0.02, 0.02, 0.02};
    f.max = {0.16, 0.1, 0.16};
    w.min = {0.0, 0.0, 0.0};
    w.max = {0.24, 0.12, 0.2};
  }
  f.velocity = {1.0, 0.0, 0.0};  // sliding over the bottom: fluid-wall pairs with v_ij != 0
  s.fluid_blocks = {f};
  s.wall_blocks = {w};
  return s;
}

struct State {
  std::vector<double> values;  // x, v, rho per particle, ordered by id
};

template <int D>
State run_with_threads(int threads, int steps, std::size_t& n_particles, double& moved,
                       Precision precision = Precision::double_precision) {
  omp_set_num_threads(threads);
  CaseSpec spec = dam_break_spec<D>();
  spec.numerics.precision = precision;
  Simulation<D> sim(spec);
  std::map<std::uint64_t, Vec<D>> start;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    start[sim.particles().id[i]] = sim.particles().pos[i];
  }
  for (int s = 0; s < steps; ++s) sim.step();
  const auto& ps = sim.particles();
  n_particles = ps.size();
  std::map<std::uint64_t, std::size_t> by_id;
  for (std::size_t i = 0; i < ps.size(); ++i) by_id[ps.id[i]] = i;
  State st;
  moved = 0.0;
  for (const auto& [id, i] : by_id) {
    for (int k = 0; k < D; ++k) st.values.push_back(ps.pos[i][k]);
    for (int k = 0; k < D; ++k) st.values.push_back(ps.vel[i][k]);
    st.values.push_back(ps.rho[i]);
    moved = std::max(moved, norm(ps.pos[i] - start.at(id)));
  }
  return st;
}

template <int D>
void expect_independent_of_threads(Precision precision);

// In both precisions (the mixed one sums its float lanes in the same fixed order).
TYPED_TEST(ForcesTest, SimulationIndependentOfThreadCount) {
  constexpr int D = TypeParam::value;
  for (Precision p : {Precision::double_precision, Precision::mixed}) {
    expect_independent_of_threads<D>(p);
  }
}

template <int D>
void expect_independent_of_threads(Precision precision) {
  const int steps = D == 2 ? 20 : 5;
  const int saved = omp_get_max_threads();
  std::size_t n1 = 0, n = 0;
  double moved = 0.0, moved_n = 0.0;
  const State one = run_with_threads<D>(1, steps, n1, moved, precision);
  std::printf("[ forces %dD ] thread check: %zu particles, %d steps, max displacement %.3g m\n", D,
              n1, steps, moved);
  EXPECT_GT(n1, 1500u);
  EXPECT_LT(n1, 4000u);
  EXPECT_GT(moved, 0.0);
  for (int threads : {2}) {
    const State many = run_with_threads<D>(threads, steps, n, moved_n, precision);
    ASSERT_EQ(n, n1);
    ASSERT_EQ(many.values.size(), one.values.size());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < one.values.size(); ++k)
      differ += !(many.values[k] == one.values[k]);
    EXPECT_EQ(differ, 0u) << threads << " threads: " << differ << " values differ";
  }
  omp_set_num_threads(saved);
}

}  // namespace
}  // namespace vrsph
