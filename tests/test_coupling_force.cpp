// The net force of a level's buffer on its fluid as vres/momentum.hpp measures it for
// numerics.vres_conserve_momentum: sum_fluid m_i a_pair,i over the fluid's pair accelerations from
// its fluid and buffer neighbours (compute_forces_packed's pair_acc). On a jittered cloud with
// walls, split into halves A and B: with B as buffer the sum over A's fluid is the force of B on
// A; with A as buffer the sum over B's fluid is the force of A on B. The pair terms are
// antisymmetric, so the two are opposite (what the buffer particles' own reaction gave before),
// and with no buffer at all the sum is zero whatever the walls push: walls are left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <vector>

#include "force_cloud.hpp"
#include "vrsph/solver/forces.hpp"

namespace vrsph {
namespace {

using namespace force_cloud;

// sum_fluid m_i a_pair,i with the particles left of x_split (A) or right of it (B) as buffer;
// `largest` gets the largest |m_i a_pair,i|, the scale of the round-off.
template <int D>
Vec<D> fluid_pair_force(Cloud<D> c, int buffer_side, double x_split, double& largest) {
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    if (c.ps.kind[i] == Kind::wall) continue;
    const bool left = c.ps.pos[i][0] < x_split;
    if ((buffer_side == 0 && left) || (buffer_side == 1 && !left)) c.ps.kind[i] = Kind::buffer;
  }
  ForceWorkspace<D> ws;
  std::vector<Vec<D>> pair_acc(c.ps.size(), Vec<D>{});
  compute_forces<D>(c.prm, c.ps, c.grid, ws, nullptr, pair_acc.data());
  Vec<D> f{};
  largest = 0.0;
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    if (c.ps.kind[i] == Kind::buffer) {
      EXPECT_EQ(norm2(c.ps.acc[i]), 0.0);
    }
    if (c.ps.kind[i] != Kind::fluid) continue;
    f += c.ps.mass_of(i) * pair_acc[i];
    largest = std::max(largest, c.ps.mass_of(i) * norm(pair_acc[i]));
  }
  return f;
}

template <class T>
class CouplingForce : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(CouplingForce, Dims);

TYPED_TEST(CouplingForce, OppositeOnTheTwoSidesAndZeroWithoutBuffer) {
  constexpr int D = TypeParam::value;
  const int n = D == 2 ? 16 : 7;
  for (Precision precision : {Precision::double_precision, Precision::mixed}) {
    for (ViscosityModel vm : {ViscosityModel::artificial, ViscosityModel::laminar}) {
      Cloud<D> c = make_cloud<D>(n, vm, DiffusionModel::molteni, {0.5, 0.01, 0.05, 3}, 7);
      c.prm.precision = precision;
      const double x_split = 0.5 * n * c.prm.dp;
      double big_a = 0.0, big_b = 0.0, big_none = 0.0;
      const Vec<D> on_a = fluid_pair_force(c, 1, x_split, big_a);  // B is buffer
      const Vec<D> on_b = fluid_pair_force(c, 0, x_split, big_b);  // A is buffer
      const Vec<D> none = fluid_pair_force(c, -1, x_split, big_none);
      // Round-off of a sum of ~n^D terms of at most `largest` each (measured: 2e-15 and 1e-6 of
      // largest x n^D in double and mixed).
      const double tol = (precision == Precision::mixed ? 1e-7 : 1e-14) * big_a * c.ps.size();
      std::printf("D %d precision %d: |F_A| %.3e |F_A + F_B| %.3e |F none| %.3e largest %.3e\n", D,
                  static_cast<int>(precision), norm(on_a), norm(on_a + on_b), norm(none), big_a);
      EXPECT_GT(norm(on_a), 100.0 * tol);  // a real force, far above the round-off
      EXPECT_LT(norm(on_a + on_b), tol) << "precision " << static_cast<int>(precision);
      EXPECT_LT(norm(none), tol) << "precision " << static_cast<int>(precision);
    }
  }
}

}  // namespace
}  // namespace vrsph
