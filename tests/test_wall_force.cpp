// The force of the fluid on the walls (solver/wall_reaction.hpp, series.csv's wall<N>_f columns):
//  - it is the exact opposite of the walls' force on the fluid in the force pass: on a jittered
//    cloud over wall layers, sum_fluid m a (force pass) + sum_walls F (reaction pass) = 0 to
//    round-off, for both viscosity models, 2D and 3D; and it is not zero;
//  - in a hydrostatic tank (cases/hydrostatic_2d.toml, 0.1 s) the tank carries the fluid's
//    weight: wall0_fy = -M g within 5% at every output after the start and within 1% on average,
//    wall0_fx = 0 to round-off (the tank is symmetric).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <type_traits>
#include <vector>

#include "cli_util.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/wall_reaction.hpp"

namespace vrsph {
namespace {

constexpr double kRho0 = 1000.0, kDp = 0.01;

template <int D>
SolverParams<D> make_params(ViscosityModel vm) {
  SolverParams<D> prm;
  const double c0 = 10.0;
  prm.dp = kDp;
  prm.h = 1.3 * kDp;
  prm.eta2 = 0.01 * prm.h * prm.h;
  prm.kernel = WendlandC2<D>(prm.h);
  prm.eos = TaitEos(kRho0, 7.0, c0);
  prm.mass = kRho0 * std::pow(kDp, D);
  prm.viscosity.model = vm;
  prm.viscosity.nu = vm == ViscosityModel::laminar ? 1e-3 : 0.0;  // large: not negligible
  prm.viscosity.alpha_c0_h = 0.1 * c0 * prm.h;
  return prm;
}

// n^D jittered fluid particles (random velocities, densities and masses) on 3 wall layers.
template <int D>
struct WallCloud {
  SolverParams<D> prm;
  ParticleSet<D> ps;
  CellGrid<D> grid;

  WallCloud(int n, ViscosityModel vm) : prm(make_params<D>(vm)) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int vert = vertical_axis<D>();
    std::uint64_t id = 0;
    for (int c = 0; c < (D == 3 ? n : 1); ++c)
      for (int b = -3; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          int idx[3] = {a, c, b};
          if constexpr (D == 2) idx[1] = b;
          const bool wall = idx[vert] < 0;
          Vec<D> x, v;
          for (int k = 0; k < D; ++k) {
            x[k] = (idx[k] + 0.5) * kDp + (wall ? 0.0 : 0.2 * kDp * u(rng));
            v[k] = wall ? 0.0 : 0.5 * u(rng);
          }
          const double rho = kRho0 * (1.0 + 0.01 * (wall ? 1.0 + u(rng) : u(rng)));
          ps.push_back(id++, wall ? Kind::wall : Kind::fluid, x, v, rho,
                       prm.mass * (1.0 + 0.05 * u(rng)));
        }
    Vec<D> lo, hi;
    for (int k = 0; k < D; ++k) {
      lo[k] = -4 * kDp;
      hi[k] = (n + 1) * kDp;
    }
    grid = CellGrid<D>(lo, hi, prm.kernel.support(), 2);
    EXPECT_TRUE(grid.sort(ps).empty());
  }
};

template <class T>
class WallForceTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(WallForceTest, Dims);

TYPED_TEST(WallForceTest, IsMinusTheWallsForceOnTheFluid) {
  constexpr int D = TypeParam::value;
  for (ViscosityModel vm : {ViscosityModel::laminar, ViscosityModel::artificial}) {
    WallCloud<D> c(D == 2 ? 16 : 7, vm);
    compute_forces(c.prm, c.ps, c.grid);  // acc without gravity
    std::vector<Vec<D>> f;
    wall_reaction_forces(c.prm, c.ps, c.grid, f);
    Vec<D> on_fluid{}, on_walls{};
    double scale = 0.0;
    for (std::size_t i = 0; i < c.ps.size(); ++i) {
      if (c.ps.kind[i] == Kind::fluid) {
        on_fluid += c.ps.mass_of(i) * c.ps.acc[i];
        scale += c.ps.mass_of(i) * norm(c.ps.acc[i]);
      } else {
        on_walls += f[i];
      }
      if (c.ps.kind[i] == Kind::fluid) {
        EXPECT_EQ(norm(f[i]), 0.0);
      }
    }
    // Fluid-fluid pairs cancel in on_fluid: what is left is the walls' push.
    ASSERT_GT(norm(on_walls), 1e-3 * scale) << "the walls feel a force";
    const double residual = norm(on_fluid + on_walls) / scale;
    std::printf("[ wall force %dD ] |sum m a + sum F_wall| / sum m |a| = %.2e\n", D, residual);
    EXPECT_LT(residual, 1e-12);
  }
}

using namespace vrsph_cli;

// side: the largest |wall0_fx| / (M g) allowed for the precision (see below).
void expect_tank_carries_the_weight(const char* precision, double side) {
  TempDir dir;
  const fs::path out = dir / "run";
  const CmdResult r =
      dir.run({"run", (kCases / "hydrostatic_2d.toml").string(), "--out", out.string(), "--quiet",
               "--set", "case.end_time=0.1", "--set", "output.interval=0.01", "--set",
               std::string("numerics.precision=\"") + precision + "\""});
  ASSERT_EQ(r.status, 0) << r;
  const auto rows = read_lines(out / "series.csv");
  ASSERT_EQ(rows.size(), 12u);
  const auto head = split_csv(rows[0]);
  auto col = [&](const std::string& name) {
    const auto it = std::find(head.begin(), head.end(), name);
    EXPECT_NE(it, head.end()) << name << " not in " << rows[0];
    return static_cast<std::size_t>(it - head.begin());
  };
  const std::size_t cm = col("mass_fluid"), cx = col("wall0_fx"), cy = col("wall0_fy");
  double sum = 0.0;
  for (std::size_t k = 2; k < rows.size(); ++k) {  // after t = 0
    const auto c = split_csv(rows[k]);
    const double weight = std::stod(c[cm]) * 9.81;
    const double fy = std::stod(c[cy]);
    EXPECT_NEAR(-fy / weight, 1.0, 0.05) << rows[k];
    EXPECT_LT(std::abs(std::stod(c[cx])), side * weight) << rows[k];
    sum += -fy / weight;
  }
  const double mean = sum / static_cast<double>(rows.size() - 2);
  std::printf("[ wall force ] hydrostatic tank, %s: mean -wall0_fy / (M g) = %.4f\n", precision,
              mean);
  EXPECT_NEAR(mean, 1.0, 0.01);
}

// The tank is symmetric, so the sideways push cancels to round-off: below 1e-9 of the weight in
// double; in mixed precision the pair terms are float and it reaches 7e-9 (measured), hence 1e-7.
TEST(WallForce, HydrostaticTankCarriesTheWeight) {
  expect_tank_carries_the_weight("double", 1e-9);
  expect_tank_carries_the_weight("mixed", 1e-7);
}

}  // namespace
}  // namespace vrsph
