// CellGrid (particles/cell_grid.hpp), 2D and 3D, full and half cells: on random clouds with fluid,
// buffer and wall particles and a few particles outside the domain, the sort permutes every array
// consistently, deletes exactly the outside particles, puts the fluid group before the wall group,
// keeps equal-cell particles in their previous order, is idempotent, and the neighbour runs
// (for_each_run over both groups) find exactly the brute-force neighbours within 2h.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <type_traits>
#include <vector>

#include "vrsph/core/to_vec.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/setup/case_spec.hpp"
#include "vrsph/setup/geometry.hpp"

namespace vrsph {
namespace {

// Everything a particle carries, keyed by id, to check that the sort permuted arrays together.
template <int D>
struct Record {
  Kind kind;
  Vec<D> pos, vel, pos0, vel0, shift;
  double rho, mass, rho0;
  std::size_t input_index;
};

template <int D>
struct Cloud {
  ParticleSet<D> ps;
  Vec<D> lo, hi;
  double support = 0.0;
  std::set<std::uint64_t> outside;  // ids placed outside the domain
};

// n particles; ids are scattered (not 0..n-1); ~3% lie outside the domain (one is NaN), a few sit
// exactly on the domain faces (inside: the domain is closed).
template <int D>
Cloud<D> random_cloud(int n, double support, std::uint64_t seed) {
  Cloud<D> cl;
  cl.support = support;
  for (int k = 0; k < D; ++k) {
    cl.lo[k] = -0.3 + 0.11 * k;
    cl.hi[k] = 0.71 + 0.07 * k;  // extents are not multiples of the cell size
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<std::uint64_t> ids(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    ids[static_cast<std::size_t>(k)] = 1000 + 7 * static_cast<std::uint64_t>(k);
  std::shuffle(ids.begin(), ids.end(), rng);
  for (int k = 0; k < n; ++k) {
    const std::uint64_t id = ids[static_cast<std::size_t>(k)];
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = cl.lo[a] + u01(rng) * (cl.hi[a] - cl.lo[a]);
    const double roll = u01(rng);
    bool out = false;
    if (roll < 0.03) {  // outside along one random axis, on either side
      const int a = static_cast<int>(u01(rng) * D);
      const double d = (0.01 + 0.5 * u01(rng)) * (cl.hi[a] - cl.lo[a]);
      x[a] = u01(rng) < 0.5 ? cl.lo[a] - d : cl.hi[a] + d;
      out = true;
    } else if (roll < 0.04) {  // exactly on a face (still inside)
      const int a = static_cast<int>(u01(rng) * D);
      x[a] = u01(rng) < 0.5 ? cl.lo[a] : cl.hi[a];
    }
    if (k == 17) {
      x[0] = std::numeric_limits<double>::quiet_NaN();
      out = true;
    }
    if (out) cl.outside.insert(id);
    const double kr = u01(rng);
    const Kind kind = kr < 0.6 ? Kind::fluid : (kr < 0.7 ? Kind::buffer : Kind::wall);
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = u01(rng) - 0.5;
    cl.ps.push_back(id, kind, x, v, 990.0 + 20.0 * u01(rng), 0.5 + u01(rng));
    const std::size_t i = cl.ps.size() - 1;
    cl.ps.pos0[i] = x + v * 0.1;
    cl.ps.vel0[i] = v * 2.0;
    cl.ps.rho0[i] = 1000.0 + u01(rng);
    cl.ps.shift[i] = v * 1e-3;
  }
  return cl;
}

template <int D>
std::map<std::uint64_t, Record<D>> records(const ParticleSet<D>& ps) {
  std::map<std::uint64_t, Record<D>> m;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    m[ps.id[i]] = {ps.kind[i],  ps.pos[i], ps.vel[i],  ps.pos0[i], ps.vel0[i],
                   ps.shift[i], ps.rho[i], ps.mass[i], ps.rho0[i], i};
  }
  return m;
}

template <class T>
class CellGridTest : public ::testing::Test {};
using Configs = ::testing::Types<std::integral_constant<int, 21>, std::integral_constant<int, 22>,
                                 std::integral_constant<int, 31>, std::integral_constant<int, 32>>;
TYPED_TEST_SUITE(CellGridTest, Configs);  // value = 10 * dimension + cells_per_support

template <int D>
Cloud<D> cloud_for_test(std::uint64_t seed) {
  // About 30 neighbours within 2h per particle.
  return D == 2 ? random_cloud<D>(1500, 0.08, seed) : random_cloud<D>(2000, 0.15, seed);
}

TYPED_TEST(CellGridTest, SortPermutesConsistentlyAndDropsOutside) {
  constexpr int D = TypeParam::value / 10, cps = TypeParam::value % 10;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    Cloud<D> cl = cloud_for_test<D>(seed);
    ASSERT_GE(cl.outside.size(), 10u);
    const auto before = records(cl.ps);
    CellGrid<D> grid(cl.lo, cl.hi, cl.support, cps);
    EXPECT_EQ(grid.reach(), cps);
    EXPECT_DOUBLE_EQ(grid.cell_size(), cl.support / cps);
    const auto lost = grid.sort(cl.ps);
    ParticleSet<D>& ps = cl.ps;

    // Lost ids: exactly the outside ones, each once.
    EXPECT_EQ(std::set<std::uint64_t>(lost.begin(), lost.end()), cl.outside);
    EXPECT_EQ(lost.size(), cl.outside.size());
    ASSERT_EQ(ps.size(), before.size() - cl.outside.size());
    for (auto* arr : {&ps.p, &ps.drho}) EXPECT_EQ(arr->size(), ps.size());
    EXPECT_EQ(ps.acc.size(), ps.size());

    // Every array permuted together: id -> all fields preserved.
    std::set<std::uint64_t> seen;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ASSERT_TRUE(seen.insert(ps.id[i]).second) << "duplicate id " << ps.id[i];
      const auto it = before.find(ps.id[i]);
      ASSERT_NE(it, before.end());
      const Record<D>& r = it->second;
      EXPECT_EQ(ps.kind[i], r.kind);
      EXPECT_EQ(ps.pos[i], r.pos);
      EXPECT_EQ(ps.vel[i], r.vel);
      EXPECT_EQ(ps.pos0[i], r.pos0);
      EXPECT_EQ(ps.vel0[i], r.vel0);
      EXPECT_EQ(ps.shift[i], r.shift);
      EXPECT_EQ(ps.rho[i], r.rho);
      EXPECT_EQ(ps.mass[i], r.mass);
      EXPECT_EQ(ps.rho0[i], r.rho0);
      EXPECT_TRUE(grid.inside(ps.pos[i]));
    }

    // Groups: fluid (and buffer) first, then walls; cells non-decreasing within a group, and
    // particles of one cell in their input order (stable sort).
    const auto fb = grid.group_begin(Group::fluid), fe = grid.group_end(Group::fluid);
    const auto wb = grid.group_begin(Group::wall), we = grid.group_end(Group::wall);
    EXPECT_EQ(fb, 0u);
    EXPECT_EQ(fe, wb);
    EXPECT_EQ(we, ps.size());
    EXPECT_GT(fe, 0u);
    EXPECT_GT(we, wb);
    const auto& cells = grid.particle_cells();
    ASSERT_EQ(cells.size(), ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const bool wall_range = i >= wb;
      EXPECT_EQ(ps.kind[i] == Kind::wall, wall_range) << "index " << i;
      EXPECT_EQ(cells[i], grid.cell_of(ps.pos[i]));
      EXPECT_GE(cells[i], 0);
      EXPECT_LT(cells[i], grid.cell_count());
      if (i > 0 && i != wb) {
        EXPECT_LE(cells[i - 1], cells[i]) << "index " << i;
        if (cells[i - 1] == cells[i]) {
          EXPECT_LT(before.at(ps.id[i - 1]).input_index, before.at(ps.id[i]).input_index);
        }
      }
    }
  }
}

TYPED_TEST(CellGridTest, NeighbourRunsMatchBruteForce) {
  constexpr int D = TypeParam::value / 10, cps = TypeParam::value % 10;
  for (std::uint64_t seed : {4u, 5u}) {
    Cloud<D> cl = cloud_for_test<D>(seed);
    CellGrid<D> grid(cl.lo, cl.hi, cl.support, cps);
    grid.sort(cl.ps);
    const ParticleSet<D>& ps = cl.ps;
    const std::size_t n = ps.size();
    const double s2 = cl.support * cl.support;
    const auto wb = grid.group_begin(Group::wall);
    std::size_t total = 0;
    std::vector<int> visits(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::uint64_t> found, brute;
      std::fill(visits.begin(), visits.end(), 0);
      for (Group g : {Group::fluid, Group::wall}) {
        grid.for_each_run(grid.particle_cells()[i], g, [&](std::uint32_t b, std::uint32_t e) {
          ASSERT_LE(b, e);
          ASSERT_LE(e, n);
          for (std::uint32_t j = b; j < e; ++j) {
            EXPECT_EQ(j >= wb, g == Group::wall) << "run of the wrong group";
            ++visits[j];
            if (j != i && norm2(ps.pos[i] - ps.pos[j]) < s2) found.push_back(ps.id[j]);
          }
        });
      }
      for (std::size_t j = 0; j < n; ++j) {
        ASSERT_LE(visits[j], 1) << "candidate visited twice";
        if (j != i && norm2(ps.pos[i] - ps.pos[j]) < s2) brute.push_back(ps.id[j]);
      }
      std::sort(found.begin(), found.end());
      std::sort(brute.begin(), brute.end());
      ASSERT_EQ(found, brute) << "particle id " << ps.id[i];
      total += brute.size();
    }
    // The cloud is dense enough for the check to mean something.
    EXPECT_GT(static_cast<double>(total) / static_cast<double>(n), 15.0);
  }
}

TYPED_TEST(CellGridTest, SecondSortChangesNothing) {
  constexpr int D = TypeParam::value / 10, cps = TypeParam::value % 10;
  Cloud<D> cl = cloud_for_test<D>(6);
  CellGrid<D> grid(cl.lo, cl.hi, cl.support, cps);
  grid.sort(cl.ps);
  const ParticleSet<D> first = cl.ps;
  const auto cells = grid.particle_cells();
  const auto fe = grid.group_end(Group::fluid);
  const auto lost = grid.sort(cl.ps);
  EXPECT_TRUE(lost.empty());
  EXPECT_EQ(cl.ps.id, first.id);
  EXPECT_EQ(cl.ps.kind, first.kind);
  EXPECT_EQ(cl.ps.pos, first.pos);
  EXPECT_EQ(cl.ps.vel, first.vel);
  EXPECT_EQ(cl.ps.pos0, first.pos0);
  EXPECT_EQ(cl.ps.vel0, first.vel0);
  EXPECT_EQ(cl.ps.rho, first.rho);
  EXPECT_EQ(cl.ps.mass, first.mass);
  EXPECT_EQ(cl.ps.rho0, first.rho0);
  EXPECT_EQ(grid.particle_cells(), cells);
  EXPECT_EQ(grid.group_end(Group::fluid), fe);
}

// Moving particles and re-sorting with the same grid object (as a run does every step) gives the
// same neighbours as a fresh grid.
TYPED_TEST(CellGridTest, ResortAfterMotionMatchesFreshGrid) {
  constexpr int D = TypeParam::value / 10, cps = TypeParam::value % 10;
  Cloud<D> cl = cloud_for_test<D>(7);
  CellGrid<D> grid(cl.lo, cl.hi, cl.support, cps);
  grid.sort(cl.ps);
  const std::size_t n_before = cl.ps.size();
  for (std::size_t i = 0; i < cl.ps.size(); ++i) cl.ps.pos[i] += cl.ps.vel[i] * 0.05;
  std::size_t leaving = 0;
  for (const auto& x : cl.ps.pos) leaving += grid.inside(x) ? 0 : 1;
  const auto lost = grid.sort(cl.ps);
  EXPECT_EQ(lost.size(), leaving);
  EXPECT_EQ(cl.ps.size(), n_before - leaving);
  ParticleSet<D> copy = cl.ps;
  CellGrid<D> fresh(cl.lo, cl.hi, cl.support, cps);
  fresh.sort(copy);
  EXPECT_EQ(copy.id, cl.ps.id);
  EXPECT_EQ(fresh.particle_cells(), grid.particle_cells());
  EXPECT_EQ(fresh.group_end(Group::fluid), grid.group_end(Group::fluid));
}

// ---- Geometry fill (setup/geometry.hpp), checked with the grid: counts, spacing, masses. ----

// Smallest distance between two particles (searched within dp with a full-cell grid).
template <int D>
double min_distance(ParticleSet<D> ps, double dp) {
  Vec<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = 1e300;
    hi[k] = -1e300;
    for (const auto& x : ps.pos) {
      lo[k] = std::min(lo[k], x[k] - dp);
      hi[k] = std::max(hi[k], x[k] + dp);
    }
  }
  CellGrid<D> grid(lo, hi, dp, 1);
  EXPECT_TRUE(grid.sort(ps).empty());
  double best2 = dp * dp;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    for (Group g : {Group::fluid, Group::wall}) {
      grid.for_each_run(grid.particle_cells()[i], g, [&](std::uint32_t b, std::uint32_t e) {
        for (std::uint32_t j = b; j < e; ++j) {
          if (j != i) best2 = std::min(best2, norm2(ps.pos[i] - ps.pos[j]));
        }
      });
    }
  }
  return std::sqrt(best2);
}

CaseSpec geometry_spec(int dim, double dp) {
  CaseSpec s;
  s.dimension = dim;
  s.dp = dp;
  return s;
}

TEST(CellGridGeometry, DamBreakBenchmarkGeometry) {
  CaseSpec s = geometry_spec(2, 0.005);
  FluidBlock f;
  f.shape = BlockShape::box;
  f.min = {0.005, 0.005, 0.0};
  f.max = {1.0, 2.0, 0.0};
  WallBlock w;
  w.shape = WallShape::tank;
  w.min = {0.0, 0.0, 0.0};
  w.max = {4.0, 2.5, 0.0};
  w.layers = 3;
  s.fluid_blocks = {f};
  s.wall_blocks = {w};
  const InitialSet<2> init = build_particles<2>(s);
  const ParticleSet<2>& ps = init.particles;
  EXPECT_EQ(ps.count(Kind::fluid), 80000u);
  EXPECT_EQ(ps.count(Kind::wall), 5415u);
  EXPECT_EQ(ps.size(), 85415u);
  EXPECT_NEAR(init.fluid_height, 1.995, 1e-12);
  const double m = 1000.0 * 0.005 * 0.005;
  std::set<std::uint64_t> ids(ps.id.begin(), ps.id.end());
  EXPECT_EQ(ids.size(), ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    ASSERT_DOUBLE_EQ(ps.mass[i], m);
    ASSERT_EQ(ps.rho[i], 1000.0);
    if (ps.kind[i] == Kind::wall) continue;
    // Fluid inside the tank, clear of the walls by at least dp.
    ASSERT_GE(ps.pos[i][0], 0.005 - 1e-12);
    ASSERT_LE(ps.pos[i][0], 1.0 + 1e-12);
    ASSERT_GE(ps.pos[i][1], 0.005 - 1e-12);
  }
  EXPECT_GE(min_distance(ps, 0.005), 0.99 * 0.005);
}

// fill = "cells": the centres of the dp cells of the box, so the box is the fluid's volume at
// any spacing (a refinement level fills the same box at its own dp). A 4 mm square at 1e-4 and
// 5e-5 m: 40 x 40 and 80 x 80 particles, outer rows dp/2 inside each face, centred on the box.
TEST(CellGridGeometry, CellsFillTheBoxAtEverySpacing) {
  for (const double dp : {1e-4, 5e-5}) {
    CaseSpec s = geometry_spec(2, dp);
    FluidBlock f;
    f.shape = BlockShape::box;
    f.fill = FillMode::cells;
    f.min = {-0.002, -0.002, 0.0};
    f.max = {0.002, 0.002, 0.0};
    s.fluid_blocks = {f};
    const InitialSet<2> init = build_particles<2>(s);
    const ParticleSet<2>& ps = init.particles;
    const auto n = static_cast<std::size_t>(std::lround(0.004 / dp));
    ASSERT_EQ(ps.size(), n * n) << "dp " << dp;
    Vec<2> lo{{1.0, 1.0}}, hi{{-1.0, -1.0}}, sum{};
    for (std::size_t i = 0; i < ps.size(); ++i)
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], ps.pos[i][k]);
        hi[k] = std::max(hi[k], ps.pos[i][k]);
        sum[k] += ps.pos[i][k];
      }
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(lo[k], -0.002 + 0.5 * dp, 1e-12) << "dp " << dp;
      EXPECT_NEAR(hi[k], 0.002 - 0.5 * dp, 1e-12) << "dp " << dp;
      EXPECT_NEAR(sum[k] / static_cast<double>(ps.size()), 0.0, 1e-12) << "dp " << dp;
    }
    EXPECT_NEAR(init.fluid_height, 0.004, 1e-15);
    EXPECT_GE(min_distance(ps, dp), 0.99 * dp);
  }
}

TEST(CellGridGeometry, CircleFillsHaveTheCircleArea) {
  const double dp = 1e-4, r = 0.002;
  const Vec3d centre{0.01, -0.003, 0.0};
  const double expected = std::numbers::pi * r * r / (dp * dp);
  for (FillMode fill : {FillMode::lattice, FillMode::rings}) {
    CaseSpec s = geometry_spec(2, dp);
    FluidBlock f;
    f.shape = BlockShape::circle;
    f.center = centre;
    f.radius = r;
    f.fill = fill;
    s.fluid_blocks = {f};
    const ParticleSet<2> ps = build_particles<2>(s).particles;
    const double n = static_cast<double>(ps.count(Kind::fluid));
    std::printf("[ geometry ] circle R/dp = 20, %s fill: %.0f particles (pi R^2/dp^2 = %.1f)\n",
                fill == FillMode::lattice ? "lattice" : "rings", n, expected);
    EXPECT_NEAR(n / expected, 1.0, 0.02) << "fill " << static_cast<int>(fill) << ": " << n;
    Vec<2> mean{};
    const Vec<2> c = to_vec<2>(centre);
    for (const auto& x : ps.pos) {
      EXPECT_LT(norm(x - c), r);
      mean += x * (1.0 / n);
    }
    EXPECT_LT(norm(mean - c), 1e-3 * dp);  // both fills are symmetric about the centre
    // Lattice: nearest neighbours dp apart; rings: the 3-particle centre ring is the tightest.
    EXPECT_GE(min_distance(ps, dp), (fill == FillMode::lattice ? 0.99 : 0.8) * dp);
  }
}

// Longest run of neighbouring rings k, k+1, ... that each have a particle on one common ray
// (each within 0.1 dp of arc of the previous ring's particle), for a ring fill centred at the
// origin.
std::size_t longest_radial_chain(const std::vector<Vec<2>>& pos, double dp) {
  std::vector<std::vector<double>> ring;  // sorted angles per ring index
  for (const auto& x : pos) {
    const auto k = static_cast<std::size_t>(std::lround(norm(x) / dp - 0.5));
    if (ring.size() <= k) ring.resize(k + 1);
    ring[k].push_back(std::atan2(x[1], x[0]));
  }
  for (auto& a : ring) std::sort(a.begin(), a.end());
  // The angle of ring `a` (sorted, in [-pi, pi]) nearest to `th`.
  const auto nearest = [](const std::vector<double>& a, double th) {
    const auto it = std::lower_bound(a.begin(), a.end(), th);
    const double up = it == a.end() ? a.front() + 2.0 * std::numbers::pi : *it;
    const double down = it == a.begin() ? a.back() - 2.0 * std::numbers::pi : *(it - 1);
    return up - th < th - down ? up : down;
  };
  std::size_t longest = 0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    for (double th : ring[k]) {
      std::size_t len = 1;
      while (k + len < ring.size()) {
        const double next = nearest(ring[k + len], th);
        if (std::abs(next - th) * ((k + len + 0.5) * dp) >= 0.1 * dp) break;
        th = std::remainder(next, 2.0 * std::numbers::pi);  // back into [-pi, pi] after a wrap
        ++len;
      }
      longest = std::max(longest, len);
    }
  }
  return longest;
}

// Were all rings started at theta = 0, every ring would have a particle on the +x ray (a chain
// of R/dp rings), a seam that seeds the drop's shape modes (geometry.cpp). The quadratic turn
// frac(k^2 g) of each ring leaves only short accidental alignments.
TEST(CellGridGeometry, RingFillHasNoRadialSeam) {
  const double dp = 2e-5, r = 0.002;  // the poster's finer droplet: 100 rings
  CaseSpec s = geometry_spec(2, dp);
  FluidBlock f;
  f.shape = BlockShape::circle;
  f.center = {0.0, 0.0, 0.0};
  f.radius = r;
  f.fill = FillMode::rings;
  s.fluid_blocks = {f};
  const ParticleSet<2> ps = build_particles<2>(s).particles;
  const std::size_t chain = longest_radial_chain(ps.pos, dp);
  std::printf("[ geometry ] rings at R/dp = 100: longest radially aligned chain %zu rings\n",
              chain);
  EXPECT_LE(chain, 6u);
  // The check itself sees a seam: a fill with every ring started at theta = 0.
  std::vector<Vec<2>> seam;
  for (long k = 0; k < 100; ++k) {
    const double rk = (k + 0.5) * dp;
    const long n = std::max(1L, std::lround(2.0 * std::numbers::pi * rk / dp));
    for (long q = 0; q < n; ++q) {
      const double th = 2.0 * std::numbers::pi * q / n;
      seam.push_back(Vec<2>{{rk * std::cos(th), rk * std::sin(th)}});
    }
  }
  EXPECT_EQ(longest_radial_chain(seam, dp), 100u);
}

TEST(CellGridGeometry, SphereAndTank3DHaveNoDuplicates) {
  const double dp = 0.01;
  CaseSpec s = geometry_spec(3, dp);
  FluidBlock ball;
  ball.shape = BlockShape::sphere;
  ball.center = {0.5, 0.5, 0.5};
  ball.radius = 0.1;
  const ParticleSet<3> sphere = [&] {
    CaseSpec t = s;
    t.fluid_blocks = {ball};
    return build_particles<3>(t).particles;
  }();
  const double expected = 4.0 / 3.0 * std::numbers::pi * std::pow(0.1 / dp, 3);
  EXPECT_NEAR(static_cast<double>(sphere.size()) / expected, 1.0, 0.02) << sphere.size();
  EXPECT_GE(min_distance(sphere, dp), 0.99 * dp);

  FluidBlock f;
  f.shape = BlockShape::box;
  f.min = {dp, dp, dp};
  f.max = {0.05, 0.04, 0.04};
  WallBlock w;
  w.shape = WallShape::tank;
  w.min = {0.0, 0.0, 0.0};
  w.max = {0.1, 0.08, 0.06};
  w.layers = 3;
  s.fluid_blocks = {f};
  s.wall_blocks = {w};
  const ParticleSet<3> ps = build_particles<3>(s).particles;
  // nodes per axis of the inner box 11 x 9 x 7; layers L = 3 grow the bottom by 2 on each side.
  const std::size_t nx = 11, ny = 9, nz = 7, grown = 2 * (3 - 1);
  const std::size_t bottom = (nx + grown) * (ny + grown) * 3;
  const std::size_t x_walls = 2 * 3 * (nz - 1) * (ny + grown);
  const std::size_t y_walls = 2 * 3 * (nz - 1) * (nx - 2);
  EXPECT_EQ(ps.count(Kind::wall), bottom + x_walls + y_walls);
  EXPECT_EQ(ps.count(Kind::fluid), 5u * 4u * 4u);
  EXPECT_GE(min_distance(ps, dp), 0.99 * dp);
  // Closed sides: every node of the 3-layer shell below the top face is a wall particle.
  std::set<std::array<long, 3>> nodes;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] != Kind::wall) continue;
    std::array<long, 3> key{};
    for (int k = 0; k < 3; ++k) key[static_cast<std::size_t>(k)] = std::lround(ps.pos[i][k] / dp);
    nodes.insert(key);
  }
  for (long z = -2; z <= 6; ++z)
    for (long y = -2; y <= 10; ++y)
      for (long x = -2; x <= 12; ++x) {
        const bool inner = x >= 1 && x <= 9 && y >= 1 && y <= 7 && z >= 1;
        EXPECT_EQ(nodes.count({x, y, z}), inner ? 0u : 1u) << x << " " << y << " " << z;
      }
}

}  // namespace
}  // namespace vrsph
