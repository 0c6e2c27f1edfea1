// A jittered lattice of fluid particles on optional wall layers, with the solver parameters of a
// force test: shared by the force-pass tests (test_forces.cpp, test_forces_mixed.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>

#include "vrsph/core/vec.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/solver/params.hpp"

namespace vrsph::force_cloud {

constexpr double kRho0 = 1000.0;

template <int D>
SolverParams<D> make_params(double dp, ViscosityModel vm, DiffusionModel dm) {
  SolverParams<D> prm;
  const double c0 = 10.0;
  prm.dp = dp;
  prm.h = 1.3 * dp;
  prm.eta2 = 0.01 * prm.h * prm.h;
  prm.kernel = WendlandC2<D>(prm.h);
  prm.eos = TaitEos(kRho0, 7.0, c0);
  prm.mass = kRho0 * std::pow(dp, D);
  prm.viscosity.model = vm;
  prm.viscosity.nu =
      vm == ViscosityModel::laminar ? 1e-3 : 0.0;  // large, so the term is not negligible
  prm.viscosity.alpha_c0_h = 0.1 * c0 * prm.h;
  prm.density_diffusion.model = dm;
  prm.density_diffusion.two_delta_h_c0 = 2.0 * 0.1 * prm.h * c0;
  return prm;
}

struct CloudOptions {
  double vel = 0.5;          // velocity components uniform in [-vel, vel]
  double rho_jitter = 0.01;  // relative density perturbation
  double mass_jitter = 0.0;  // relative mass perturbation
  int wall_layers = 0;       // wall layers below the fluid (vertical axis)
};

// An n^D lattice of fluid particles jittered by up to 0.2 dp, optionally on wall layers.
template <int D>
struct Cloud {
  SolverParams<D> prm;
  ParticleSet<D> ps;
  CellGrid<D> grid;
};

template <int D>
Cloud<D> make_cloud(int n, ViscosityModel vm, DiffusionModel dm, const CloudOptions& o,
                    std::uint64_t seed) {
  const double dp = 0.01;
  Cloud<D> c;
  c.prm = make_params<D>(dp, vm, dm);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int nz = D == 3 ? n : 1;
  const int vert = vertical_axis<D>();
  std::uint64_t id = 0;
  for (int cz = 0; cz < nz; ++cz)
    for (int b = -o.wall_layers; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        int idx[3] = {a, b, cz};
        if constexpr (D == 3) std::swap(idx[1], idx[2]);  // b runs along z in 3D
        const bool wall = idx[vert] < 0;
        Vec<D> x, v;
        for (int k = 0; k < D; ++k) {
          x[k] = (idx[k] + 0.5) * dp + (wall ? 0.0 : 0.2 * dp * u(rng));
          v[k] = wall ? 0.0 : o.vel * u(rng);
        }
        const double rho = kRho0 * (1.0 + (wall ? 0.0 : o.rho_jitter * u(rng)));
        const double m = c.prm.mass * (1.0 + o.mass_jitter * u(rng));
        c.ps.push_back(id++, wall ? Kind::wall : Kind::fluid, x, v, rho, m);
      }
  Vec<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = -(o.wall_layers + 1) * dp;
    hi[k] = (n + 1) * dp;
  }
  c.grid = CellGrid<D>(lo, hi, c.prm.kernel.support(), 2);
  EXPECT_TRUE(c.grid.sort(c.ps).empty());
  return c;
}

}  // namespace vrsph::force_cloud
