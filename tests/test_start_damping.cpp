// The damped start (numerics.start_damping_time, start_damping_tau; physics/start_damping.hpp):
// the factor, and a drop that starts out of equilibrium (droplet_2d at p = 0, R/dp = 10): while
// the damping lasts its fluid moves slower than without it; the same steps after it are undamped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "case_util.hpp"
#include "vrsph/physics/start_damping.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {
namespace {

using test::load_case;

TEST(StartDamping, FactorOnlyBeforeTheEndTime) {
  EXPECT_DOUBLE_EQ(start_damping_factor(0.0, 1e-6, 0.01, 1e-3), std::exp(-1e-3));
  EXPECT_DOUBLE_EQ(start_damping_factor(0.0099, 2e-4, 0.01, 1e-3), std::exp(-0.2));
  EXPECT_EQ(start_damping_factor(0.01, 1e-6, 0.01, 1e-3), 1.0);  // from T_d on: none
  EXPECT_EQ(start_damping_factor(0.0, 1e-6, 0.0, 1e-3), 1.0);    // off
}

double max_fluid_speed(const Simulation<2>& sim) {
  double v = 0.0;
  const auto& ps = sim.level(0).ps;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.kind[i] == Kind::fluid) v = std::max(v, norm(ps.vel[i]));
  return v;
}

// Largest fluid speed at t_stop, with the damped start to t_damp (0: none).
double speed_at(double t_stop, double t_damp) {
  CaseSpec spec =
      load_case("droplet_2d.toml", {"resolution.dp=2e-4", "fluid_block.0.pressure=0",
                                    "numerics.start_damping_time=" + std::to_string(t_damp),
                                    "numerics.start_damping_tau=5e-4"});
  Simulation<2> sim(spec);
  while (sim.time() < t_stop - 1e-12) sim.step();
  return max_fluid_speed(sim);
}

// Measured (2026-12-05): at 4 ms 0.0014 m/s damped against 0.0059 undamped.
TEST(StartDamping, DropStartedAtRestMovesSlowerWhileDamped) {
  const double free = speed_at(0.004, 0.0), damped = speed_at(0.004, 0.004);
  std::printf("max fluid speed at 4 ms: undamped %.4g m/s, damped %.4g m/s\n", free, damped);
  EXPECT_GT(free, 0.0);
  EXPECT_LT(damped, 0.5 * free);
}

}  // namespace
}  // namespace vrsph
