// The packed columns of a force evaluation (solver/columns.hpp) in the grid's run layout
// (particles/run_columns.hpp): particle i at index i, kBlockPad inert dummies after the last,
// positions split into hi + lo in float; the volume a wall's
// continuity sum sees is a column of its own only where the level holds buffer particles (0
// there, the particle's volume elsewhere), in either precision.
#include <gtest/gtest.h>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/solver/columns.hpp"

namespace vrsph {
namespace {

ParticleSet<2> three_particles(Kind middle) {
  ParticleSet<2> ps;
  ps.push_back(1, Kind::fluid, {0.0, 0.0}, {0.1, 0.0}, 1000.0, 0.01);
  ps.push_back(2, middle, {0.01, 0.0}, {0.0, 0.2}, 1010.0, 0.02);
  ps.push_back(3, Kind::wall, {0.02, 0.0}, {0.0, 0.0}, 1005.0, 0.01);
  return ps;
}

CellGrid<2> sorted_grid(ParticleSet<2>& ps) {
  CellGrid<2> grid({-0.1, -0.1}, {0.1, 0.1}, 0.026, 1);
  grid.sort(ps);
  return grid;
}

template <class T>
void check_layout(const LevelColumns<2>& c, const ParticleSet<2>& ps, const TaitEos& eos) {
  using C = StateCol<2>;
  const StateRuns<2, T>& st = c.state_of<T>();
  const double tol = std::is_same_v<T, float> ? 1e-6 : 0.0;
  ASSERT_EQ(st.count, 3u);
  for (std::uint32_t i = 0; i < 3; ++i) {
    const std::size_t q = i;
    T hi[3], lo[3];
    st.self(i, hi, lo);
    for (int k = 0; k < 2; ++k) {
      // hi + lo carries the position to double accuracy, also in float
      EXPECT_NEAR(static_cast<double>(hi[k]) + static_cast<double>(lo[k]) + st.origin[k],
                  ps.pos[i][k], 1e-15)
          << i;
      EXPECT_EQ(st.base[k][q], hi[k]);
    }
    EXPECT_NEAR(st.base[C::v + 1][q], ps.vel[i][1], tol);
    EXPECT_NEAR(st.base[C::rho][q], ps.rho[i] - 1000.0, tol * 10);
    EXPECT_NEAR(st.base[C::p][q], eos.pressure(ps.rho[i]), tol * 1e3);
    EXPECT_NEAR(st.base[C::vol][q], ps.mass_of(i) / ps.rho[i], tol * 1e-5);
  }
  // the dummies after the particles: far away, no volume
  ASSERT_EQ(st.col[0].size(), 3 + kBlockPad);
  for (std::size_t q = 3; q < 3 + kBlockPad; ++q) {
    EXPECT_GT(st.base[0][q], T(1e14)) << q;
    EXPECT_EQ(st.base[C::vol][q], T(0)) << q;
  }
}

TEST(LevelColumns, StateInTheRunLayoutWithDummiesAfterTheLast) {
  const TaitEos eos(1000.0, 7.0, 10.0);
  for (Precision precision : {Precision::double_precision, Precision::mixed}) {
    ParticleSet<2> ps = three_particles(Kind::fluid);
    const CellGrid<2> grid = sorted_grid(ps);
    LevelColumns<2> c;
    c.pack(ps, grid, eos, precision);
    if (precision == Precision::mixed)
      check_layout<float>(c, ps, eos);
    else
      check_layout<double>(c, ps, eos);
  }
}

TEST(LevelColumns, PackRefusesParticlesChangedSinceTheSort) {
  const TaitEos eos(1000.0, 7.0, 10.0);
  ParticleSet<2> ps = three_particles(Kind::fluid);
  const CellGrid<2> grid = sorted_grid(ps);
  ps.push_back(4, Kind::fluid, {0.03, 0.0}, {0.0, 0.0}, 1000.0, 0.01);
  LevelColumns<2> c;
  EXPECT_THROW(c.pack(ps, grid, eos), std::logic_error);
}

TEST(LevelColumns, WallVolumeColumnOnlyWithBufferParticles) {
  using C = StateCol<2>;
  const TaitEos eos(1000.0, 7.0, 10.0);
  for (Precision precision : {Precision::double_precision, Precision::mixed}) {
    const bool floats = precision == Precision::mixed;
    ParticleSet<2> plain = three_particles(Kind::fluid);
    const CellGrid<2> plain_grid = sorted_grid(plain);
    LevelColumns<2> a;
    a.pack(plain, plain_grid, eos, precision);
    EXPECT_FALSE(a.has_wall_vol);
    EXPECT_TRUE(a.state.col[C::wall_vol].empty());
    EXPECT_TRUE(a.f.state.col[C::wall_vol].empty());
    // the absent column reads the volumes
    if (floats)
      EXPECT_EQ(a.f.state.base[C::wall_vol], a.f.state.base[C::vol]);
    else
      EXPECT_EQ(a.state.base[C::wall_vol], a.state.base[C::vol]);
    ParticleSet<2> with_buffer = three_particles(Kind::buffer);
    const CellGrid<2> grid = sorted_grid(with_buffer);
    LevelColumns<2> b;
    b.pack(with_buffer, grid, eos, precision);
    EXPECT_TRUE(b.has_wall_vol);
    for (std::uint32_t i = 0; i < 3; ++i) {
      const double want =
          with_buffer.kind[i] == Kind::buffer ? 0.0 : with_buffer.mass_of(i) / with_buffer.rho[i];
      const double got = floats ? b.f.state.base[C::wall_vol][i] : b.state.base[C::wall_vol][i];
      EXPECT_NEAR(got, want, floats ? 1e-7 * want : 0.0) << i;
    }
  }
}

}  // namespace
}  // namespace vrsph
