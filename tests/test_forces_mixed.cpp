// The mixed precision of the force pass (numerics.precision = "mixed", core/precision.hpp)
// against double on the same jittered clouds, 2D and 3D, with walls, every viscosity and
// diffusion model: accelerations and drho/dt agree to float accuracy relative to the largest
// pair term, the pair counts are identical, and a cloud far from the origin gives the same
// result as near it (positions enter the float arithmetic relative to each block's origin).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <vector>

#include "field_compare.hpp"
#include "force_cloud.hpp"
#include "vrsph/solver/forces.hpp"

namespace vrsph {
namespace {

using namespace force_cloud;

struct Result {
  std::vector<double> acc, drho;
  ForceStats stats;
};

template <int D>
Result forces(Cloud<D>& c, Precision precision) {
  c.prm.precision = precision;
  Result r;
  r.stats = compute_forces(c.prm, c.ps, c.grid);
  for (std::size_t i = 0; i < c.ps.size(); ++i) {
    for (int k = 0; k < D; ++k) r.acc.push_back(c.ps.acc[i][k]);
    r.drho.push_back(c.ps.drho[i]);
  }
  return r;
}

using test::max_rel_diff;

template <class T>
class MixedForces : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(MixedForces, Dims);

TYPED_TEST(MixedForces, AgreesWithDoubleToFloatAccuracy) {
  constexpr int D = TypeParam::value;
  const int n = D == 2 ? 20 : 9;
  for (ViscosityModel vm : {ViscosityModel::laminar, ViscosityModel::artificial}) {
    for (DiffusionModel dm :
         {DiffusionModel::none, DiffusionModel::molteni, DiffusionModel::fourtakas}) {
      Cloud<D> c = make_cloud<D>(n, vm, dm, {0.5, 0.01, 0.05, 3}, 41);
      c.prm.up[vertical_axis<D>()] = 1.0;
      c.prm.density_diffusion.set_hydrostatic(c.prm.eos, 9.81);
      const Result d = forces(c, Precision::double_precision);
      const Result m = forces(c, Precision::mixed);
      const double ea = max_rel_diff(d.acc, m.acc), er = max_rel_diff(d.drho, m.drho);
      std::printf("[ mixed %dD ] viscosity %d, diffusion %d: acc %.2e, drho %.2e\n", D,
                  static_cast<int>(vm), static_cast<int>(dm), ea, er);
      EXPECT_LT(ea, 2e-5);
      EXPECT_LT(er, 2e-5);
      EXPECT_GT(ea + er, 0.0) << "the mixed pass did not run in float";
      EXPECT_EQ(d.stats.pairs, m.stats.pairs);
      EXPECT_NEAR(m.stats.max_acc, d.stats.max_acc, 2e-5 * d.stats.max_acc);
    }
  }
}

// The same cloud shifted 1000 m: the float pair terms see the same relative positions.
TYPED_TEST(MixedForces, FarFromTheOriginAsNearIt) {
  constexpr int D = TypeParam::value;
  const int n = D == 2 ? 16 : 8;
  Cloud<D> near = make_cloud<D>(n, ViscosityModel::artificial, DiffusionModel::molteni,
                                {0.5, 0.01, 0.0, 2}, 43);
  Cloud<D> far = near;
  Vec<D> shift;
  for (int k = 0; k < D; ++k) shift[k] = 1000.0;
  for (auto& x : far.ps.pos) x += shift;
  Vec<D> lo = far.grid.domain_min() + shift, hi = far.grid.domain_max() + shift;
  far.grid = CellGrid<D>(lo, hi, far.prm.kernel.support(), 2);
  ASSERT_TRUE(far.grid.sort(far.ps).empty());
  const Result a = forces(near, Precision::mixed);
  const Result b = forces(far, Precision::mixed);
  const Result d = forces(near, Precision::double_precision);
  EXPECT_LT(max_rel_diff(d.acc, b.acc), 2e-5);
  EXPECT_LT(max_rel_diff(a.acc, b.acc), 2e-5);
}

}  // namespace
}  // namespace vrsph
