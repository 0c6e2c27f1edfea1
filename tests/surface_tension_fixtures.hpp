// Static particle sets and parameters shared by the surface-tension tests
// (test_surface_tension*.cpp).
#pragma once

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

namespace vrsph::st_fixtures {

inline constexpr double kRho0 = 1000.0;
inline constexpr double kSigma = 0.0728;
inline constexpr double kPi = std::numbers::pi;

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

// cells: the grid's layout (the fixture's default: half cells, blocks of two cells).
template <int D>
Static<D> make_static(const std::vector<Vec<D>>& pos, double dp, double hdp = 1.3,
                      CellLayout cells = {2, 2}) {
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
  s.grid = CellGrid<D>(lo, hi, s.prm.kernel.support(), cells.cells_per_support);
  s.grid.set_block_width(cells.cells_per_block);
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
inline std::vector<Vec<2>> droplet_circle(double dp, const std::string& fill) {
  CaseSpec spec = test::load_case(
      "droplet_2d.toml", {"resolution.dp=" + std::to_string(dp), "fluid_block.0.fill=" + fill});
  const ParticleSet<2> ps = build_particles<2>(spec).particles;
  return ps.pos;
}

// Sphere of radius R on concentric shells at radii (k + 1/2) dp, round(4 pi r^2 / dp^2) points per
// shell on a Fibonacci spiral (each shell turned by a different angle).
inline std::vector<Vec<3>> sphere_shells(double radius, double dp) {
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
inline std::vector<Vec<3>> sphere_lattice(double radius, double dp) {
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

}  // namespace vrsph::st_fixtures
