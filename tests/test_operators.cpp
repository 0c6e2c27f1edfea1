// SPH operators on a Cartesian lattice (2D and 3D), interior particles only (at least 2h from the
// lattice edges): the gradient of a linear field, the velocity divergence through the continuity
// term of compute_forces (sign and magnitude: drho = -rho0 div v), and the pressure acceleration of
// a linear pressure field (a = -grad p / rho). Tolerances reflect the lattice gradient-consistency
// matrix M = sum V (r_j - r_i) (x) grad W = m I, m = 0.974 (2D) / 0.979 (3D) at h = 1.3 dp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <type_traits>
#include <vector>

#include "vrsph/core/kernel.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/params.hpp"

namespace vrsph {
namespace {

constexpr double kRho0 = 1000.0;

template <int D>
SolverParams<D> make_params(double dp, double hdp, double c0) {
  SolverParams<D> prm;
  prm.dp = dp;
  prm.h = hdp * dp;
  prm.eta2 = 0.01 * prm.h * prm.h;
  prm.kernel = WendlandC2<D>(prm.h);
  prm.eos = TaitEos(kRho0, 7.0, c0);
  prm.mass = kRho0 * std::pow(dp, D);
  prm.viscosity.model = ViscosityModel::laminar;
  prm.viscosity.nu = 0.0;
  prm.density_diffusion.model = DiffusionModel::none;
  prm.density_diffusion.two_delta_h_c0 = 0.0;
  return prm;
}

template <int D>
struct Lattice {
  SolverParams<D> prm;
  ParticleSet<D> ps;
  CellGrid<D> grid;
  std::vector<bool> interior;  // by sorted index
  std::size_t n_interior = 0;
};

// n^D fluid particles at rest, rho = rho0, spacing dp, offset so no coordinate is zero.
template <int D>
Lattice<D> make_lattice(int n, double hdp, double c0 = 10.0) {
  const double dp = 0.01;
  Lattice<D> l;
  l.prm = make_params<D>(dp, hdp, c0);
  const int nz = D == 3 ? n : 1;
  std::uint64_t id = 0;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        Vec<D> x;
        x[0] = (a + 0.5) * dp + 0.1;
        x[1] = (b + 0.5) * dp - 0.07;
        if constexpr (D == 3) x[2] = (c + 0.5) * dp + 0.03;
        l.ps.push_back(id++, Kind::fluid, x, Vec<D>{}, kRho0, l.prm.mass);
      }
  Vec<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = l.ps.pos[0][k] - 1.5 * dp;
    hi[k] = l.ps.pos.back()[k] + 1.5 * dp;
  }
  l.grid = CellGrid<D>(lo, hi, l.prm.kernel.support(), 2);
  EXPECT_TRUE(l.grid.sort(l.ps).empty());
  // Interior: full kernel support inside the lattice.
  l.interior.assign(l.ps.size(), false);
  for (std::size_t i = 0; i < l.ps.size(); ++i) {
    bool in = true;
    for (int k = 0; k < D; ++k) {
      const double margin =
          std::min(l.ps.pos[i][k] - (lo[k] + 1.5 * dp), (hi[k] - 1.5 * dp) - l.ps.pos[i][k]);
      in = in && margin >= l.prm.kernel.support();
    }
    l.interior[i] = in;
    l.n_interior += in;
  }
  return l;
}

template <class T>
class OperatorsTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(OperatorsTest, Dims);

template <int D>
int lattice_side() {
  return D == 2 ? 24 : 13;
}

// sum_j V_j (f_j - f_i) grad_i W_ij over the grid's neighbour runs, for f = a.x + b.
TYPED_TEST(OperatorsTest, GradientOfLinearField) {
  constexpr int D = TypeParam::value;
  Vec<D> a;
  for (int k = 0; k < D; ++k) a[k] = 3.0 - 2.5 * k;  // (3, 0.5[, -2])
  const double b = 7.0;
  for (double hdp : {1.3, 2.0}) {
    Lattice<D> l = make_lattice<D>(lattice_side<D>(), hdp);
    ASSERT_GE(l.n_interior, 16u);
    const auto& ps = l.ps;
    const auto& kern = l.prm.kernel;
    auto f = [&](const Vec<D>& x) { return dot(a, x) + b; };
    double worst = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (!l.interior[i]) continue;
      Vec<D> grad{};
      l.grid.for_each_run(
          l.grid.particle_cells()[i], Group::fluid, [&](std::uint32_t jb, std::uint32_t je) {
            for (std::uint32_t j = jb; j < je; ++j) {
              const Vec<D> r_ij = ps.pos[i] - ps.pos[j];
              const double r2 = norm2(r_ij);
              if (r2 >= kern.support2 || j == i) continue;
              const double vol_j = ps.mass_of(j) / ps.rho[j];
              grad += vol_j * (f(ps.pos[j]) - f(ps.pos[i])) * kern.f(std::sqrt(r2)) * r_ij;
            }
          });
      worst = std::max(worst, norm(grad - a) / norm(a));
    }
    std::printf("[ operators %dD h/dp=%.1f ] linear-field gradient: max rel error %.4f\n", D, hdp,
                worst);
    EXPECT_LT(worst, hdp < 1.5 ? 0.03 : 0.005) << "h/dp = " << hdp;
  }
}

// Continuity with v = A x + v0 (rho = rho0: p = 0, no diffusion): drho_i = -rho0 m tr(A) in the
// interior (expansion loses density), independent of v0.
TYPED_TEST(OperatorsTest, ContinuityGivesMinusRhoDivergence) {
  constexpr int D = TypeParam::value;
  double am[3][3] = {{0.3, -0.7, 0.2}, {0.45, -0.1, 0.6}, {-0.3, 0.25, 0.5}};
  double trace = 0.0, anorm = 0.0;
  for (int r = 0; r < D; ++r) {
    trace += am[r][r];
    for (int c = 0; c < D; ++c) anorm += am[r][c] * am[r][c];
  }
  anorm = std::sqrt(anorm);
  ASSERT_GT(trace, 0.0);
  for (double hdp : {1.3, 2.0}) {
    Lattice<D> l = make_lattice<D>(lattice_side<D>(), hdp);
    auto& ps = l.ps;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      for (int r = 0; r < D; ++r) {
        ps.vel[i][r] = 1.5 - r;  // uniform offset v0
        for (int c = 0; c < D; ++c) ps.vel[i][r] += am[r][c] * ps.pos[i][c];
      }
    }
    const ForceStats st = compute_forces(l.prm, ps, l.grid);
    EXPECT_GT(st.pairs, 0u);
    double worst = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      EXPECT_EQ(l.prm.eos.pressure(ps.rho[i]), 0.0);
      if (!l.interior[i]) continue;
      const double expected = -kRho0 * trace;
      EXPECT_LT(ps.drho[i], 0.0) << "expansion must lower the density";
      worst = std::max(worst, std::abs(ps.drho[i] - expected) / std::abs(expected));
    }
    std::printf("[ operators %dD h/dp=%.1f ] continuity: max rel error %.4f\n", D, hdp, worst);
    EXPECT_LT(worst, hdp < 1.5 ? 0.03 : 0.005) << "h/dp = " << hdp;

    // A traceless field (rotation + shear) has no divergence: drho ~ 0 to round-off.
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const Vec<D> x = ps.pos[i];
      Vec<D> v{};
      v[0] = 0.8 * x[1] - 0.2;
      v[1] = -0.3 * x[0] + 0.1;
      if constexpr (D == 3) v[2] = 0.5 * x[0] - 0.4 * x[1];
      ps.vel[i] = v;
    }
    compute_forces(l.prm, ps, l.grid);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (l.interior[i]) {
        EXPECT_NEAR(ps.drho[i], 0.0, 1e-10 * kRho0 * anorm);
      }
    }
  }
}

// Pressure p = p0 + G.x, densities from the inverse EOS: a_i = -grad p / rho_i (the symmetric form
// adds 2 p_i sum V_j grad W_ij ~ -2 p_i grad rho / rho0, below 0.1% with these numbers).
TYPED_TEST(OperatorsTest, PressureAccelerationOfLinearPressure) {
  constexpr int D = TypeParam::value;
  Vec<D> g_p;
  for (int k = 0; k < D; ++k) g_p[k] = 1000.0 * (1.0 - 1.5 * k);  // Pa/m: (1000, -500[, -2000])
  const double p0 = 100.0;
  for (double hdp : {1.3, 2.0}) {
    Lattice<D> l = make_lattice<D>(lattice_side<D>(), hdp, 20.0);
    auto& ps = l.ps;
    Vec<D> centre = ps.pos[0];
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (l.interior[i]) centre = ps.pos[i];
    }
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ps.rho[i] = l.prm.eos.density(p0 + dot(g_p, ps.pos[i] - centre));
    }
    compute_forces(l.prm, ps, l.grid);
    double worst = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (!l.interior[i]) continue;
      const Vec<D> expected = g_p * (-1.0 / ps.rho[i]);
      worst = std::max(worst, norm(ps.acc[i] - expected) / norm(expected));
    }
    std::printf("[ operators %dD h/dp=%.1f ] pressure acceleration: max rel error %.4f\n", D, hdp,
                worst);
    EXPECT_LT(worst, hdp < 1.5 ? 0.035 : 0.01) << "h/dp = " << hdp;
  }
}

// A uniform pressure exerts no force in the interior (symmetric form, lattice symmetry), but does
// at the free edge, where it pushes outwards.
TYPED_TEST(OperatorsTest, UniformPressureBalancesInInterior) {
  constexpr int D = TypeParam::value;
  Lattice<D> l = make_lattice<D>(lattice_side<D>(), 1.3);
  auto& ps = l.ps;
  const double rho = l.prm.eos.density(500.0);
  for (auto& r : ps.rho) r = rho;
  compute_forces(l.prm, ps, l.grid);
  const double scale = 500.0 / (rho * l.prm.h);  // p / (rho h): size of an unbalanced term
  Vec<D> mid{};
  for (const auto& x : ps.pos) mid += x * (1.0 / static_cast<double>(ps.size()));
  const auto& lo = l.grid.domain_min();
  const auto& hi = l.grid.domain_max();
  const double dp = l.prm.dp;
  std::size_t outer = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    bool on_edge = false;  // outermost layer of the lattice (1.5 dp inside the grid domain)
    for (int k = 0; k < D; ++k) {
      on_edge = on_edge || ps.pos[i][k] - lo[k] < 2.0 * dp || hi[k] - ps.pos[i][k] < 2.0 * dp;
    }
    if (l.interior[i]) {
      EXPECT_LT(norm(ps.acc[i]), 1e-11 * scale);
    } else if (on_edge) {
      ++outer;
      EXPECT_GT(dot(ps.acc[i], ps.pos[i] - mid), 0.0) << "edge particle pushed inwards";
      EXPECT_GT(norm(ps.acc[i]), 0.1 * scale);
    }
  }
  EXPECT_GT(outer, 0u);
}

}  // namespace
}  // namespace vrsph
