// Buffer particles kept apart (numerics.vres_buffer_spacing, vres/buffer_spacing.hpp; issue #20,
// item 3): what the move does to a stacked pair, to a buffer particle next to fluid, and to
// everything else; that it does not depend on the threads; and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "case_parser_fixtures.hpp"
#include "case_util.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/vres/buffer_spacing.hpp"

namespace vrsph {
namespace {

using test::load_case;

// The fine level of droplet_vr_2d at half resolution, as set up (sorted).
Simulation<2> fine_drop() {
  CaseSpec spec = load_case("droplet_vr_2d.toml", {"resolution.dp=2e-4"});
  return Simulation<2>(spec);
}

// The nearest other particle of level L to particle i, and its distance.
double nearest(const Level<2>& L, std::size_t i, std::size_t& j_near) {
  double best = 1e300;
  for (std::size_t j = 0; j < L.ps.size(); ++j) {
    if (j == i) continue;
    const double d = norm(L.ps.pos[i] - L.ps.pos[j]);
    if (d < best) best = d, j_near = j;
  }
  return best;
}

// Places buffer particle b at distance 0.3 dp from particle a (towards b's old place), keeping
// it in its cell, and returns b's new position.
Vec<2> stack_onto(Level<2>& L, std::size_t a, std::size_t b) {
  const Vec<2> e = (L.ps.pos[b] - L.ps.pos[a]) * (1.0 / norm(L.ps.pos[b] - L.ps.pos[a]));
  L.ps.pos[b] = L.ps.pos[a] + e * (0.3 * L.prm.dp);
  return L.ps.pos[b];
}

// Two buffer particles 0.3 dp apart end 0.55 dp apart, each moved half the shortfall along the
// line between them; a buffer particle 0.3 dp from a fluid particle moves the whole shortfall and
// the fluid particle stays; nothing else moves.
TEST(VresSpacing, StackedPairsArePartedAndNothingElseMoves) {
  Simulation<2> sim = fine_drop();
  Level<2>& L = sim.level(1);
  const double dp = L.prm.dp, s = 0.55;
  // Two buffer pairs and one buffer-fluid pair, far from each other.
  std::vector<std::size_t> buffers, fluid;
  for (std::size_t i = 0; i < L.ps.size(); ++i) {
    if (L.ps.kind[i] == Kind::buffer) buffers.push_back(i);
    if (L.ps.kind[i] == Kind::fluid && std::abs(L.ps.pos[i][1]) < 2 * dp && L.ps.pos[i][0] < 1e-3)
      fluid.push_back(i);
  }
  ASSERT_GT(buffers.size(), 20u);
  ASSERT_FALSE(fluid.empty());
  // a buffer particle beside the fluid one: the nearest buffer particle to it
  const std::size_t f = fluid.front();
  std::size_t bf = buffers.front();
  for (std::size_t b : buffers)
    if (norm(L.ps.pos[b] - L.ps.pos[f]) < norm(L.ps.pos[bf] - L.ps.pos[f])) bf = b;
  // a buffer pair far from it: two neighbouring buffer particles
  std::size_t b1 = buffers.back(), b2 = b1;
  nearest(L, b1, b2);
  ASSERT_EQ(L.ps.kind[b2], Kind::buffer);
  ASSERT_GT(norm(L.ps.pos[b1] - L.ps.pos[f]), 10 * dp);
  const Vec<2> x_f = L.ps.pos[f], x_b1 = L.ps.pos[b1];
  const Vec<2> x_b2 = stack_onto(L, b1, b2), x_bf = stack_onto(L, f, bf);
  const std::vector<Vec<2>> before = L.ps.pos;
  const std::size_t moved = space_buffers(L, s);
  EXPECT_EQ(moved, 3u);
  EXPECT_NEAR(norm(L.ps.pos[b1] - L.ps.pos[b2]), s * dp, 1e-12 * dp);
  EXPECT_NEAR(norm(L.ps.pos[b1] - x_b1), 0.125 * dp, 1e-12 * dp);  // half of 0.25 dp
  EXPECT_NEAR(norm(L.ps.pos[b2] - x_b2), 0.125 * dp, 1e-12 * dp);
  EXPECT_EQ(L.ps.pos[f][0], x_f[0]);
  EXPECT_EQ(L.ps.pos[f][1], x_f[1]);
  EXPECT_NEAR(norm(L.ps.pos[bf] - x_f), s * dp, 1e-12 * dp);
  EXPECT_NEAR(norm(L.ps.pos[bf] - x_bf), 0.25 * dp, 1e-12 * dp);
  for (std::size_t i = 0; i < L.ps.size(); ++i) {
    if (i == b1 || i == b2 || i == bf) continue;
    EXPECT_EQ(L.ps.pos[i][0], before[i][0]) << "particle " << i;
    EXPECT_EQ(L.ps.pos[i][1], before[i][1]) << "particle " << i;
  }
  // Off: nothing moves.
  EXPECT_EQ(space_buffers(L, 0.0), 0u);
}

// A coupled run with the spacing on, started with one stacked buffer pair (so the first step
// parts it), gives the same particles on 1 and 2 threads, and the pair ends parted.
TEST(VresSpacing, RunDoesNotDependOnThreads) {
  std::vector<Vec<2>> pos[2];
  for (int threads : {1, 2}) {
    exec::set_thread_count(threads);
    CaseSpec spec = load_case("droplet_vr_2d.toml", {"resolution.dp=2e-4", "case.end_time=0.0002",
                                                     "numerics.vres_buffer_spacing=0.55"});
    Simulation<2> sim(spec);
    Level<2>& L = sim.level(1);
    std::size_t b1 = 0, b2 = 0;
    while (L.ps.kind[b1] != Kind::buffer) ++b1;
    nearest(L, b1, b2);
    stack_onto(L, b1, b2);
    const std::uint64_t id1 = L.ps.id[b1], id2 = L.ps.id[b2];
    while (sim.time() < spec.end_time - 1e-12) sim.step();
    pos[threads - 1] = L.ps.pos;
    Vec<2> x1{}, x2{};
    for (std::size_t i = 0; i < L.ps.size(); ++i) {
      if (L.ps.id[i] == id1) x1 = L.ps.pos[i];
      if (L.ps.id[i] == id2) x2 = L.ps.pos[i];
    }
    EXPECT_GT(norm(x1 - x2), 0.5 * L.prm.dp) << threads << " thread(s)";
  }
  exec::set_thread_count(2);
  ASSERT_EQ(pos[0].size(), pos[1].size());
  for (std::size_t i = 0; i < pos[0].size(); ++i) {
    EXPECT_EQ(pos[0][i][0], pos[1][i][0]);
    EXPECT_EQ(pos[0][i][1], pos[1][i][1]);
  }
}

TEST(VresSpacing, KeyIsCheckedAndWrittenBack) {
  using namespace case_fixtures;
  expect_contains(error_of(with_numerics("vres_buffer_spacing = 1.2\n")),
                  {"numerics.vres_buffer_spacing = 1.2", "[0, 1)"});
  const CaseSpec s = parse_text(with_numerics("vres_buffer_spacing = 0.55\n"));
  EXPECT_EQ(s.vres_buffer_spacing, 0.55);
  EXPECT_EQ(written_back(s).vres_buffer_spacing, 0.55);
  EXPECT_EQ(parse_text(kMinimal).vres_buffer_spacing, 0.0);
}

}  // namespace
}  // namespace vrsph
