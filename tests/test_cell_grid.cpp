// CellGrid (particles/cell_grid.hpp), 2D and 3D, full and half cells: on random clouds with fluid,
// buffer and wall particles and a few particles outside the domain, the sort permutes every array
// consistently, deletes exactly the outside particles, puts the fluid group before the wall group,
// keeps equal-cell particles in their previous order, is idempotent, and the neighbour runs
// (for_each_run over both groups) find exactly the brute-force neighbours within 2h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <type_traits>
#include <vector>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"

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
    m[ps.id[i]] = {ps.kind[i],  ps.pos[i], ps.vel[i],     ps.pos0[i], ps.vel0[i],
                   ps.shift[i], ps.rho[i], ps.mass_of(i), ps.rho0[i], i};
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

// Every array permuted together: id -> all fields preserved, each id once, all inside.
template <int D>
void expect_fields_preserved(const ParticleSet<D>& ps,
                             const std::map<std::uint64_t, Record<D>>& before,
                             const CellGrid<D>& grid) {
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
    EXPECT_EQ(ps.mass_of(i), r.mass);
    EXPECT_EQ(ps.rho0[i], r.rho0);
    EXPECT_TRUE(grid.inside(ps.pos[i]));
  }
}

// Groups: fluid (and buffer) first, then walls; cells non-decreasing within a group, and
// particles of one cell in their input order (stable sort).
template <int D>
void expect_grouped_by_cell(const ParticleSet<D>& ps,
                            const std::map<std::uint64_t, Record<D>>& before,
                            const CellGrid<D>& grid) {
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
    EXPECT_EQ(ps.drho.size(), ps.size());
    EXPECT_EQ(ps.acc.size(), ps.size());

    ASSERT_NO_FATAL_FAILURE(expect_fields_preserved(ps, before, grid));
    ASSERT_NO_FATAL_FAILURE(expect_grouped_by_cell(ps, before, grid));
  }
}

// An array kept beside the particles (the held surface fields) follows them through carry();
// one of another length is left alone.
TYPED_TEST(CellGridTest, CarriedArrayFollowsItsParticles) {
  constexpr int D = TypeParam::value / 10, cps = TypeParam::value % 10;
  Cloud<D> cl = cloud_for_test<D>(4);
  std::vector<double> ids(cl.ps.size()), other(3, 7.0);
  std::vector<Vec<D>> xs = cl.ps.pos;
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<double>(cl.ps.id[i]);
  CellGrid<D> grid(cl.lo, cl.hi, cl.support, cps);
  grid.sort(cl.ps);
  grid.carry(ids);
  grid.carry(xs);
  grid.carry(other);
  ASSERT_EQ(ids.size(), cl.ps.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(ids[i], static_cast<double>(cl.ps.id[i]));
    EXPECT_EQ(norm2(xs[i] - cl.ps.pos[i]), 0.0);
  }
  EXPECT_EQ(other, std::vector<double>(3, 7.0));
}

// for_each_run_within (the cross-level surface passes' search): for query points inside and
// beyond the cloud and radii from half to three supports, the runs visit each particle at most
// once and hold every particle within the radius.
TYPED_TEST(CellGridTest, RunsWithinARadiusHoldEveryParticleInIt) {
  constexpr int D = TypeParam::value / 10, cps = TypeParam::value % 10;
  Cloud<D> cl = cloud_for_test<D>(6);
  CellGrid<D> grid(cl.lo, cl.hi, cl.support, cps);
  grid.sort(cl.ps);
  const ParticleSet<D>& ps = cl.ps;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.6, 1.1);
  std::vector<int> visits(ps.size());
  std::size_t total = 0;
  for (int q = 0; q < 60; ++q) {
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = u(rng);
    const double radius = cl.support * (0.5 + 2.5 * (q % 6) / 5.0);
    std::fill(visits.begin(), visits.end(), 0);
    std::vector<std::uint64_t> found, brute;
    for (Group g : {Group::fluid, Group::wall}) {
      grid.for_each_run_within(x, radius, g, [&](std::uint32_t b, std::uint32_t e) {
        ASSERT_LE(e, ps.size());
        for (std::uint32_t j = b; j < e; ++j) {
          ++visits[j];
          if (norm2(ps.pos[j] - x) < radius * radius) found.push_back(ps.id[j]);
        }
      });
    }
    for (std::size_t j = 0; j < ps.size(); ++j) {
      ASSERT_LE(visits[j], 1) << "visited twice";
      if (norm2(ps.pos[j] - x) < radius * radius) brute.push_back(ps.id[j]);
    }
    std::sort(found.begin(), found.end());
    std::sort(brute.begin(), brute.end());
    ASSERT_EQ(found, brute) << "query " << q;
    total += brute.size();
  }
  EXPECT_GT(total, 600u);  // the queries found particles
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
  EXPECT_EQ(cl.ps.masses(), first.masses());
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

// A sort where no particle left its cell is skipped (the stable sort would be the identity) and
// carry() then leaves arrays as they are; one particle moved into another cell makes the next sort
// a real one again, whose order and cells are a fresh grid's.
TYPED_TEST(CellGridTest, SortSkipsOnlyWhenNoParticleChangedCell) {
  constexpr int D = TypeParam::value / 10, cps = TypeParam::value % 10;
  Cloud<D> cl = cloud_for_test<D>(8);
  CellGrid<D> grid(cl.lo, cl.hi, cl.support, cps);
  grid.sort(cl.ps);
  const auto cells = grid.particle_cells();
  const std::vector<std::uint64_t> ids = cl.ps.id;
  std::vector<double> side(cl.ps.size());
  for (std::size_t i = 0; i < side.size(); ++i) side[i] = static_cast<double>(i);
  const std::vector<double> side_before = side;
  EXPECT_TRUE(grid.sort(cl.ps).empty());
  EXPECT_TRUE(grid.last_sort_skipped());
  grid.carry(side);
  EXPECT_EQ(cl.ps.id, ids);
  EXPECT_EQ(grid.particle_cells(), cells);
  EXPECT_EQ(side, side_before);
  // The first fluid particle whose move by one cell along x keeps it inside the domain.
  std::size_t moved = cl.ps.size();
  for (std::size_t i = 0; i < cl.ps.size() && moved == cl.ps.size(); ++i) {
    Vec<D> x = cl.ps.pos[i];
    x[0] += grid.cell_size();
    if (cl.ps.kind[i] == Kind::fluid && grid.inside(x)) moved = i;
  }
  ASSERT_LT(moved, cl.ps.size());
  cl.ps.pos[moved][0] += grid.cell_size();
  const std::uint64_t moved_id = cl.ps.id[moved];
  grid.sort(cl.ps);
  EXPECT_FALSE(grid.last_sort_skipped());
  grid.carry(side);
  ParticleSet<D> copy = cl.ps;
  CellGrid<D> fresh(cl.lo, cl.hi, cl.support, cps);
  fresh.sort(copy);
  EXPECT_EQ(copy.id, cl.ps.id);
  EXPECT_EQ(fresh.particle_cells(), grid.particle_cells());
  EXPECT_NE(grid.particle_cells(), cells);        // the moved particle has its new cell
  for (std::size_t i = 0; i < cl.ps.size(); ++i)  // the side array followed its particles
    EXPECT_EQ(ids[static_cast<std::size_t>(side[i])], cl.ps.id[i]) << "moved id " << moved_id;
}

}  // namespace
}  // namespace vrsph
