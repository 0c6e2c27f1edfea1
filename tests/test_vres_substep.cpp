// Buffer values of a level that sub-cycles inside its parent's step (local time stepping;
// interpolate_buffers_level with substep_from, vres/coupling.hpp). Taken from a uniform flow
// through a face after a few steps: the parent's velocity at the end of its step is its start
// velocity plus an increment linear in x, positions unchanged. Then:
//  - half-way through the parent's step the fine buffer particles hold what the parent's state
//    interpolated half-way in time gives (interpolation is linear in the donor values);
//  - at the parent's step end they hold the parent's end values, read again from where they were
//    formed half-way (the same bits as interpolating anew there), except for a particle that has
//    moved more than kParentEndDrift h of the parent since: its values are formed anew where it
//    is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "vres_fixtures.hpp"
#include "vrsph/setup/case_parser.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/vres/interpolation.hpp"

namespace vrsph {
namespace {

// The largest difference in rho (relative to rho0) and in velocity (relative to 1 m/s) between
// level 1's buffer particles and `expected` (one state per particle, index order).
double largest_difference(const ParticleSet<2>& ps,
                          const std::vector<InterpolatedState<2>>& expected) {
  double worst = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] != Kind::buffer) continue;
    worst = std::max(worst, std::abs(ps.rho[i] - expected[i].rho) / 1000.0);
    worst = std::max(worst, norm(ps.vel[i] - expected[i].vel));
  }
  return worst;
}

// What interpolate_from_level gives level 1's buffer particles from level 0 at the fraction a
// of its step (default rule: first-order values, no fill test).
std::vector<InterpolatedState<2>> from_parent(const std::vector<Level<2>>& levels, double a) {
  const Level<2>& P = levels[0];
  const ParticleSet<2>& ps = levels[1].ps;
  std::vector<InterpolatedState<2>> s(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.kind[i] == Kind::buffer)
      s[i] = interpolate_from_level(ps.pos[i], P.ps, P.grid, P.prm.kernel, kVresCondLimit, a);
  return s;
}

TEST(VresSubstep, BufferValuesFollowTheParentInTime) {
  CaseSpec spec = parse_case(toml::parse(test::kUniformFlowThroughAFace), "flux");
  spec.numerics.local_time_stepping = true;
  Simulation<2> sim(spec);
  for (int k = 0; k < 3; ++k) sim.step();
  std::vector<Level<2>> levels = {sim.level(0), sim.level(1)};
  LevelLink<2> link = sim.link(1);
  // The parent's step: start = the state now, end = velocity + (5 x, 0) 1/s, rho + 1%.
  ParticleSet<2>& P = levels[0].ps;
  P.keep_pos0(true);
  for (std::size_t j = 0; j < P.size(); ++j) {
    P.pos0[j] = P.pos[j], P.vel0[j] = P.vel[j], P.rho0[j] = P.rho[j];
    P.vel[j][0] += 5.0 * P.pos[j][0];
    P.rho[j] *= 1.01;
  }
  const DonorRule rule;
  CouplingTally tally;
  // The fine level's values at the parent's step start, then its two sub-steps.
  ASSERT_EQ(interpolate_buffers_level(levels, link, 1, tally, rule, {0.0, 1.0}, {-1.0, -1.0}), 0u);
  const std::vector<InterpolatedState<2>> mid = from_parent(levels, 0.5);
  ASSERT_EQ(interpolate_buffers_level(levels, link, 1, tally, rule, {0.5, 1.0}, {0.0, -1.0}), 0u);
  std::size_t buffers = 0;
  for (Kind k : levels[1].ps.kind) buffers += k == Kind::buffer ? 1 : 0;
  ASSERT_GT(buffers, 20u);
  EXPECT_LT(largest_difference(levels[1].ps, mid), 1e-12);

  // One buffer particle moves by 0.1 h of the parent (beyond the drift): formed anew.
  ParticleSet<2>& F = levels[1].ps;
  const std::size_t moved = static_cast<std::size_t>(
      std::find(F.kind.begin(), F.kind.end(), Kind::buffer) - F.kind.begin());
  const Vec<2> x_mid = F.pos[moved];
  F.pos[moved][0] += 0.1 * levels[0].prm.h;
  const std::vector<InterpolatedState<2>> end = from_parent(levels, 1.0);
  ASSERT_EQ(interpolate_buffers_level(levels, link, 1, tally, rule, {1.0, 1.0}, {0.5, -1.0}), 0u);
  EXPECT_LT(largest_difference(F, end), 1e-12);
  // The values where it stood half-way differ: the cached ones were not taken.
  const InterpolatedState<2> there =
      interpolate_from_level(x_mid, P, levels[0].grid, levels[0].prm.kernel, kVresCondLimit, 1.0);
  EXPECT_GT(norm(there.vel - end[moved].vel), 1e-4);
}

}  // namespace
}  // namespace vrsph
