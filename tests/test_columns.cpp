// The packed columns of a force evaluation (solver/columns.hpp): the volume a wall's continuity
// sum sees is a column of its own only where the level holds buffer particles (0 there, the
// particle's volume elsewhere); without buffers no such column is kept, in either precision.
#include <gtest/gtest.h>

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

TEST(LevelColumns, WallVolumeColumnOnlyWithBufferParticles) {
  const TaitEos eos(1000.0, 7.0, 10.0);
  for (Precision precision : {Precision::double_precision, Precision::mixed}) {
    const bool floats = precision == Precision::mixed;
    ParticleSet<2> plain = three_particles(Kind::fluid);
    LevelColumns<2> a;
    a.pack(plain, eos, precision);
    EXPECT_TRUE(a.wall_vol.empty());
    EXPECT_TRUE(a.f.wall_vol.empty());
    ParticleSet<2> with_buffer = three_particles(Kind::buffer);
    LevelColumns<2> b;
    b.pack(with_buffer, eos, precision);
    ASSERT_EQ(floats ? b.f.wall_vol.size() : b.wall_vol.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      const double want = i == 1 ? 0.0 : with_buffer.mass[i] / with_buffer.rho[i];
      const double got = floats ? b.f.wall_vol[i] : b.wall_vol[i];
      EXPECT_NEAR(got, want, floats ? 1e-7 * want : 0.0) << i;
    }
  }
}

}  // namespace
}  // namespace vrsph
