// numerics.surface_tension.refresh = "capillary" (sim/surface_refresh.hpp): the refresh clock,
// the held capillary acceleration following its particles through sorts and kind changes, and a
// run that stays with the every-step run, does not depend on its outputs or its thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "case_util.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {
namespace {

using test::load_case;

// Position, velocity and density of every particle of every level, by level and id.
std::vector<double> state_of(const Simulation<2>& sim) {
  std::vector<double> v;
  for (std::size_t l = 0; l < sim.level_count(); ++l) {
    const ParticleSet<2>& ps = sim.level(l).ps;
    std::map<std::uint64_t, std::size_t> by_id;
    for (std::size_t i = 0; i < ps.size(); ++i) by_id[ps.id[i]] = i;
    for (const auto& [id, i] : by_id) {
      v.insert(v.end(), {static_cast<double>(id), ps.pos[i][0], ps.pos[i][1], ps.vel[i][0],
                         ps.vel[i][1], ps.rho[i]});
    }
  }
  return v;
}

std::vector<std::string> capillary(double interval) {
  return {"numerics.surface_tension.refresh=\"capillary\"",
          "numerics.surface_tension.refresh_interval=" + std::to_string(interval)};
}

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Mean pressure within R/2 of the origin, over the fluid of every level.
double inner_pressure(Simulation<2>& sim) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t l = 0; l < sim.level_count(); ++l) {
    const ParticleSet<2>& ps = sim.level(l).ps;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.kind[i] == Kind::fluid && norm(ps.pos[i]) < 1e-3)
        sum += sim.params().eos.pressure(ps.rho[i]), ++n;
  }
  return n > 0 ? sum / n : std::nan("");
}

TEST(SurfaceRefresh, ClockRefreshesAtCorrectorStagesOnceTheIntervalHasPassed) {
  const RefreshClock every;
  EXPECT_TRUE(every.every_step());
  EXPECT_TRUE(every.due(0.0, false));
  EXPECT_TRUE(every.due(0.0, true));
  RefreshClock c(1.0);
  EXPECT_TRUE(c.due(0.0, false));  // nothing held yet: the first evaluation refreshes
  EXPECT_TRUE(std::isnan(c.last()));
  c.mark(0.0);
  EXPECT_FALSE(c.due(0.5, true));
  EXPECT_FALSE(c.due(1.5, false));  // the first stage never refreshes a held field
  EXPECT_TRUE(c.due(1.0 - 1e-12, true));
  EXPECT_EQ(c.last(), 0.0);
  RefreshClock r(1.0);
  r.restore(0.25);
  EXPECT_FALSE(r.due(1.0, true));
  EXPECT_TRUE(r.due(1.25, true));
  r.restore(std::nan(""));
  EXPECT_TRUE(r.due(0.0, false));
}

// Between refreshes the acceleration is extrapolated from the last two: a_ref + tau (a_ref -
// a_before) / (t_ref - t_before), where both refreshes gave the particle a non-zero value; held
// as it is elsewhere (a particle created since, or one that got or lost its normal).
TEST(SurfaceRefresh, HeldAccelerationIsExtrapolatedFromTheLastTwoRefreshes) {
  SurfaceFields<2> sf;
  sf.held = true;
  sf.acc_st = {Vec<2>{1.0, 2.0}, Vec<2>{0.0, 0.0}, Vec<2>{3.0, 0.0}};
  sf.extrapolate(0.5);  // nothing refreshed yet: left as it is
  EXPECT_EQ(sf.acc_st[0][1], 2.0);
  sf.take_refresh(std::nan(""));  // the first refresh: no rate
  ASSERT_EQ(sf.acc_rate.size(), 3u);
  EXPECT_EQ(norm2(sf.acc_rate[0]), 0.0);
  sf.extrapolate(0.5);
  EXPECT_EQ(sf.acc_st[0][0], 1.0);
  sf.acc_st = {Vec<2>{2.0, 0.0}, Vec<2>{5.0, 5.0}, Vec<2>{0.0, 0.0}};  // the next refresh
  sf.take_refresh(0.25);
  EXPECT_DOUBLE_EQ(sf.acc_rate[0][0], 4.0);
  EXPECT_DOUBLE_EQ(sf.acc_rate[0][1], -8.0);
  EXPECT_EQ(norm2(sf.acc_rate[1]), 0.0);  // 0 before: held
  EXPECT_EQ(norm2(sf.acc_rate[2]), 0.0);  // 0 now: held at 0
  sf.extrapolate(0.125);
  EXPECT_DOUBLE_EQ(sf.acc_st[0][0], 2.5);
  EXPECT_DOUBLE_EQ(sf.acc_st[0][1], -1.0);
  EXPECT_EQ(sf.acc_st[1][0], 5.0);
  EXPECT_EQ(norm2(sf.acc_st[2]), 0.0);
  sf.compact_held({1, 0, 1});  // the rate follows its particle
  sf.fit_held(3);              // and a created one holds nothing
  ASSERT_EQ(sf.acc_ref.size(), 3u);
  EXPECT_DOUBLE_EQ(sf.acc_rate[0][0], 4.0);
  EXPECT_EQ(norm2(sf.acc_ref[2]) + norm2(sf.acc_rate[2]), 0.0);
}

// The drop at dp 2e-4 to 5 ms: refreshing at every corrector stage (interval 0.1 of the
// capillary limit, shorter than one step here) stays with the every-step run, while running
// passes 2 and 3 half as often.
TEST(SurfaceRefresh, CapillaryRunStaysWithTheEveryStepRun) {
  const std::vector<std::string> base = {"resolution.dp=2e-4", "case.end_time=0.005"};
  CaseSpec se =
      load_case("droplet_2d.toml", with(base, {"numerics.surface_tension.refresh=\"every_step\""}));
  CaseSpec sc = load_case("droplet_2d.toml", with(base, capillary(0.1)));
  Simulation<2> a(se), b(sc);
  while (a.time() < se.end_time - 1e-12) a.step();
  while (b.time() < sc.end_time - 1e-12) b.step();
  ASSERT_EQ(a.step_count(), b.step_count());
  const double pa = inner_pressure(a), pb = inner_pressure(b);
  std::printf(
      "drop at 5 ms: inner pressure %.4f (every step) %.4f Pa (capillary), %zu / %zu "
      "capillary passes\n",
      pa, pb, static_cast<std::size_t>(a.pass_times().capillary_passes),
      static_cast<std::size_t>(b.pass_times().capillary_passes));
  EXPECT_NEAR(pb, pa, 0.01 * std::fabs(pa));
  EXPECT_EQ(a.pass_times().capillary_passes, 2u * a.step_count());
  EXPECT_LE(b.pass_times().capillary_passes, a.step_count() + 1u);
  EXPECT_GT(b.pass_times().capillary_passes, a.step_count() / 2);
}

// Output fields are computed apart: a run whose fields are written at every third step takes
// the same steps to the same bytes.
TEST(SurfaceRefresh, OutputsDoNotChangeTheRun) {
  CaseSpec spec = load_case("droplet_vr_2d.toml", with({"resolution.dp=2e-4"}, capillary(0.5)));
  Simulation<2> a(spec), b(spec);
  for (int s = 0; s < 30; ++s) {
    a.step();
    b.step();
    if (s % 3 == 0) b.update_surface_fields();
  }
  EXPECT_EQ(state_of(a), state_of(b));
  // and the output fields are there, one per particle
  for (std::size_t l = 0; l < b.level_count(); ++l)
    EXPECT_EQ(b.surface_fields(l).lambda.size(), b.level(l).ps.size());
}

// Two levels, the drop moving across the interface at 0.1 m/s: particles are created, deleted
// and change kind while the held acceleration stays one entry per particle; the drop keeps its
// Laplace pressure and the run does not depend on the thread count.
TEST(SurfaceRefresh, VariableResolutionDropHoldsItsFieldsThroughKindChanges) {
  CaseSpec spec = load_case(
      "droplet_vr_2d.toml",
      with({"resolution.dp=2e-4", "case.end_time=0.004", "fluid_block.0.velocity=[0.1, 0]",
            "fluid_block.0.fill=\"lattice\"", "numerics.vres_shepard_fill=0"},
           capillary(0.5)));
  const int saved = omp_get_max_threads();
  std::vector<double> one;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    Simulation<2> sim(spec);
    while (sim.time() < spec.end_time - 1e-12) {
      sim.step();
      for (std::size_t l = 0; l < sim.level_count(); ++l) {
        const SurfaceFields<2>& sf = sim.level(l).sf;
        ASSERT_EQ(sf.acc_st.size(), sim.level(l).ps.size()) << l;
        ASSERT_EQ(sf.acc_rate.size(), sf.acc_ref.size()) << l;
        if (!sf.acc_ref.empty()) {
          ASSERT_EQ(sf.acc_ref.size(), sim.level(l).ps.size()) << l;
        }
      }
    }
    if (threads == 1) {
      one = state_of(sim);
      EXPECT_GT(sim.counters().created + sim.counters().deleted, 0u);
      EXPECT_LT(sim.pass_times().capillary_passes, static_cast<std::uint64_t>(sim.step_count()));
      const double p = inner_pressure(sim);
      std::printf("moving VR drop at 4 ms with the capillary refresh: inner pressure %.2f Pa\n", p);
      EXPECT_GT(p, 0.5 * 36.4);
      EXPECT_LT(p, 1.5 * 36.4);
    } else {
      EXPECT_EQ(state_of(sim), one) << "2 threads";
    }
  }
  omp_set_num_threads(saved);
}

}  // namespace
}  // namespace vrsph
