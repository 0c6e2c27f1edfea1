// Surface pass 1 summed by the force pass (solver/forces.hpp, Pass1Out): on the evaluations where
// pass 1 would run for shifting alone, the force pass sums each fluid particle's grad C and div r
// over the same neighbours instead, and at a capillary refresh all of pass 1; pass 1 itself then
// runs over the other particles only (surface_sums_for_shifting, surface_sums_in_forces).
//  - on a jittered block over wall layers, in 2D and 3D, double and mixed precision, the force
//    pass's grad C and div r equal pass 1's (to the round-off of a different order of the sums
//    across fluid and wall neighbours), and its accelerations and drho/dt are those of the force
//    pass without them, bit for bit; in 2D the same for all of pass 1 (lambda, L, the Shepard sum,
//    G);
//  - surface_sums_for_shifting leaves the fluid particles' lambda as it was, gives a buffer
//    particle pass 1's values, and hands the fluid rows to the next level_forces (the flag);
//  - a refresh with pass 1 in the force pass and passes 2 and 3 after it (add_capillary) gives the
//    accelerations of passes 1-3 before the force pass, bit for bit without walls; 3D runs pass 1
//    apart.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "force_cloud.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/level.hpp"
#include "vrsph/solver/stepper.hpp"
#include "vrsph/solver/surface_pass.hpp"

namespace vrsph {
namespace {

using force_cloud::CloudOptions;
using force_cloud::make_cloud;

// A jittered block over two wall layers, its columns packed, and its surface pass 1.
template <int D>
struct WalledBlock {
  force_cloud::Cloud<D> c;
  ForceWorkspace<D> ws;
  SurfaceFields<D> sf;
};
template <int D>
WalledBlock<D> walled_block(Precision precision, double sigma, std::uint64_t seed) {
  CloudOptions o;
  o.wall_layers = 2;
  WalledBlock<D> b{
      make_cloud<D>(D == 2 ? 14 : 7, ViscosityModel::laminar, DiffusionModel::molteni, o, seed),
      {},
      {}};
  b.c.prm.precision = precision;
  b.c.prm.sigma = sigma;
  b.ws.pack(b.c.ps, b.c.grid, b.c.prm.eos, b.c.prm.precision);
  surface_sums(b.c.prm, b.c.ps, b.c.grid, b.ws, b.sf);
  return b;
}

// A free jittered block of n^D particles as one level, with surface tension sigma.
template <int D>
Level<D> free_level(int n, double sigma, std::uint64_t seed) {
  auto c = make_cloud<D>(n, ViscosityModel::laminar, DiffusionModel::molteni, CloudOptions{}, seed);
  Level<D> L;
  L.prm = c.prm;
  L.prm.sigma = sigma;
  L.ps = c.ps;
  L.grid = c.grid;
  return L;
}

template <int D>
void check_sums_match(Precision precision) {
  WalledBlock<D> b = walled_block<D>(precision, 0.0, 7);
  auto& c = b.c;
  const ForceWorkspace<D>& ws = b.ws;
  const SurfaceFields<D>& sf = b.sf;

  ParticleSet<D> plain = c.ps;
  compute_forces_packed(c.prm, plain, c.grid, ws);
  std::vector<Vec<D>> grad_c(c.ps.size());
  std::vector<double> div_r(c.ps.size(), -7.0);
  const Pass1Out<D> shift{grad_c.data(), div_r.data()};
  compute_forces_packed<D>(c.prm, c.ps, c.grid, ws, nullptr, nullptr, &shift);

  // Round-off: float pair terms (mixed) or double ones, summed in another order near the walls.
  const bool mixed = precision == Precision::mixed;
  const double gc_scale = 1.0 / c.prm.h, tol = mixed ? 2e-6 : 1e-13;
  double worst_gc = 0.0, worst_div = 0.0;
  std::size_t fluid = 0, near_wall = 0;
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    if (c.ps.kind[i] != Kind::fluid) continue;
    ++fluid;
    worst_gc = std::max(worst_gc, norm(grad_c[i] - sf.grad_c[i]) / gc_scale);
    worst_div = std::max(worst_div, std::abs(div_r[i] - sf.div_r[i]));
    if (norm(sf.grad_c[i]) * c.prm.h > 0.05) ++near_wall;  // the block's faces and the walls
    for (int k = 0; k < D; ++k) ASSERT_EQ(c.ps.acc[i][k], plain.acc[i][k]) << "particle " << i;
    ASSERT_EQ(c.ps.drho[i], plain.drho[i]) << "particle " << i;
  }
  ASSERT_GT(fluid, 50u);
  ASSERT_GT(near_wall, 10u) << "grad C must be far from zero somewhere for the check to bite";
  EXPECT_LT(worst_gc, tol) << D << "D";
  EXPECT_LT(worst_div, tol * D) << D << "D";
}

TEST(Pass1InForces, ForcePassSumsWhatPassOneSums2D) {
  check_sums_match<2>(Precision::double_precision);
  check_sums_match<2>(Precision::mixed);
}
TEST(Pass1InForces, ForcePassSumsWhatPassOneSums3D) {
  check_sums_match<3>(Precision::double_precision);
  check_sums_match<3>(Precision::mixed);
}

TEST(Pass1InForces, PassOneForShiftingLeavesFluidRowsToTheForcePass) {
  CloudOptions o;
  o.wall_layers = 1;
  auto c = make_cloud<2>(12, ViscosityModel::laminar, DiffusionModel::molteni, o, 11);
  // One fluid particle of the middle becomes a buffer particle.
  std::size_t b = 0;
  for (std::size_t i = 0; i < c.ps.size(); ++i)
    if (c.ps.kind[i] == Kind::fluid && std::abs(c.ps.pos[i][0] - 0.06) < 0.006 &&
        std::abs(c.ps.pos[i][1] - 0.06) < 0.006)
      b = i;
  ASSERT_NE(b, 0u);
  c.ps.kind[b] = Kind::buffer;

  Level<2> L;
  L.prm = c.prm;
  L.ps = c.ps;
  L.grid = c.grid;
  pack_level(L);
  SurfaceFields<2> full;
  surface_sums(L.prm, L.ps, L.grid, L.cols, full);

  surface_pass_sums(L);  // a full pass 1, then marks on the fluid rows
  for (std::size_t i = 0; i < L.ps.size(); ++i)
    if (L.ps.kind[i] == Kind::fluid) L.sf.lambda[i] = -1.0, L.sf.div_r[i] = -1.0;
  L.sf.grad_c[b] = Vec<2>{};
  surface_pass_shifting_sums(L);
  ASSERT_EQ(L.sf.in_forces, Pass1InForces::shifting);
  for (std::size_t i = 0; i < L.ps.size(); ++i) {
    if (L.ps.kind[i] == Kind::fluid) {
      ASSERT_EQ(L.sf.lambda[i], -1.0) << "pass 1 for shifting rewrote fluid particle " << i;
      ASSERT_EQ(L.sf.div_r[i], -1.0) << "pass 1 for shifting rewrote fluid particle " << i;
    }
  }
  EXPECT_EQ(L.sf.grad_c[b][0], full.grad_c[b][0]);
  EXPECT_EQ(L.sf.grad_c[b][1], full.grad_c[b][1]);
  EXPECT_EQ(L.sf.div_r[b], full.div_r[b]);

  level_forces(L, false, false);  // sums the fluid rows and clears the flag
  EXPECT_EQ(L.sf.in_forces, Pass1InForces::none);
  double worst = 0.0;
  for (std::size_t i = 0; i < L.ps.size(); ++i)
    if (L.ps.kind[i] == Kind::fluid)
      worst = std::max(worst, std::abs(L.sf.div_r[i] - full.div_r[i]));
  EXPECT_LT(worst, 1e-13);
}

// All of pass 1 in the force pass (2D: its 4 sums and pass 1's 8 fill the sweep's 12).
template <int D>
void check_whole_pass_matches(Precision precision) {
  WalledBlock<D> b = walled_block<D>(precision, 0.0728, 5);  // sigma: pass 1 sums G too
  auto& c = b.c;
  const ForceWorkspace<D>& ws = b.ws;
  const SurfaceFields<D>& sf = b.sf;
  ASSERT_EQ(sf.grad_w.size(), c.ps.size());

  ParticleSet<D> plain = c.ps;
  compute_forces_packed(c.prm, plain, c.grid, ws);
  SurfaceFields<D> in;
  in.resize(c.ps.size());
  in.grad_w.assign(c.ps.size(), -7.0);
  in.sums_grad_w = true;
  const Pass1Out<D> whole = in.pass1_out(true);
  ASSERT_EQ(whole.terms, (kPass1Terms<D, true>));
  compute_forces_packed<D>(c.prm, c.ps, c.grid, ws, nullptr, nullptr, &whole);

  const bool mixed = precision == Precision::mixed;
  const double tol = mixed ? 2e-6 : 1e-13, h = c.prm.h;
  double worst = 0.0;
  std::size_t fluid = 0, thin = 0;
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    if (c.ps.kind[i] != Kind::fluid) continue;
    ++fluid;
    if (sf.lambda[i] < 0.7) ++thin;  // the block's free faces: M far from the identity
    worst = std::max(worst, std::abs(in.lambda[i] - sf.lambda[i]));
    worst = std::max(worst, std::abs(in.shepard[i] - sf.shepard[i]));
    worst = std::max(worst, std::abs(in.grad_w[i] - sf.grad_w[i]) * h);
    worst = std::max(worst, norm(in.grad_c[i] - sf.grad_c[i]) * h);
    worst = std::max(worst, std::abs(in.div_r[i] - sf.div_r[i]) / D);
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b)
        worst = std::max(worst, std::abs(in.l_corr[i](a, b) - sf.l_corr[i](a, b)) / 10);
    for (int k = 0; k < D; ++k) ASSERT_EQ(c.ps.acc[i][k], plain.acc[i][k]) << "particle " << i;
    ASSERT_EQ(c.ps.drho[i], plain.drho[i]) << "particle " << i;
  }
  ASSERT_GT(fluid, 100u);
  ASSERT_GT(thin, 20u) << "lambda must fall at the free faces for the check to bite";
  EXPECT_LT(worst, tol) << D << "D, " << (mixed ? "mixed" : "double");
}

TEST(Pass1InForces, ForcePassSumsAllOfPassOne2D) {
  check_whole_pass_matches<2>(Precision::double_precision);
  check_whole_pass_matches<2>(Precision::mixed);
}

// A refresh in both orders on a free block (no walls): passes 1-3, then the forces with a_st; or
// pass 1 in the force pass, passes 2 and 3 after it, a_st added.
void check_refresh_orders(Precision precision) {
  Level<2> before = free_level<2>(16, 0.0728, 3);
  before.prm.precision = precision;
  Level<2> after = before;

  pack_level(before);
  surface_pass_sums(before);
  surface_pass_normals(before);
  surface_pass_curvature(before);
  const ForceStats s0 = level_forces(before, true, false);

  pack_level(after);
  ASSERT_TRUE(surface_pass_sums_in_forces(after));
  ASSERT_EQ(after.sf.in_forces, Pass1InForces::full);
  ForceStats s1 = level_forces(after, false, false);
  EXPECT_EQ(after.sf.in_forces, Pass1InForces::none);
  surface_pass_normals(after);
  surface_pass_curvature(after);
  add_capillary(after, s1);

  std::size_t pulled = 0;
  for (std::size_t i = 0; i < before.ps.size(); ++i) {
    if (norm(before.sf.acc_st[i]) > 0.0) ++pulled;
    ASSERT_EQ(after.sf.lambda[i], before.sf.lambda[i]) << "particle " << i;
    for (int k = 0; k < 2; ++k) {
      ASSERT_EQ(after.sf.acc_st[i][k], before.sf.acc_st[i][k]) << "particle " << i;
      ASSERT_EQ(after.ps.acc[i][k], before.ps.acc[i][k]) << "particle " << i;
    }
  }
  EXPECT_GT(pulled, 30u) << "the capillary force must act for the check to bite";
  EXPECT_EQ(s1.max_acc, s0.max_acc);
  EXPECT_EQ(s1.pairs, s0.pairs);
}

TEST(Pass1InForces, RefreshAfterTheForcePassGivesTheSameAccelerations) {
  check_refresh_orders(Precision::double_precision);
  check_refresh_orders(Precision::mixed);
}

// 3D keeps pass 1 apart (surface_sums_in_forces: 5 + 12 sums exceed the sweep's 12): the whole
// pass runs, the flag stays clear; a 2D level hands it to the force pass in either precision.
TEST(Pass1InForces, ThreeDRunsPassOneApart) {
  Level<2> L = free_level<2>(10, 0.0728, 2);
  for (Precision p : {Precision::mixed, Precision::double_precision}) {
    L.prm.precision = p;
    pack_level(L);
    EXPECT_TRUE(surface_pass_sums_in_forces(L));
    EXPECT_EQ(L.sf.in_forces, Pass1InForces::full);
    L.sf.in_forces = Pass1InForces::none;
  }

  Level<3> L3 = free_level<3>(6, 0.0728, 2);
  pack_level(L3);
  EXPECT_FALSE(surface_pass_sums_in_forces(L3));
  EXPECT_EQ(L3.sf.in_forces, Pass1InForces::none);
  EXPECT_GT(L3.sf.lambda[0], 0.0) << "the whole pass 1 ran";
}

}  // namespace
}  // namespace vrsph
