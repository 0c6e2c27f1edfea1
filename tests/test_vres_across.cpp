// Surface fields summed over the fluid of both levels (numerics.vres_surface_across_levels,
// solver/cross_level.hpp; issue #20, item 1, first version): what the passes see and the lambda
// it gives across the face of droplet_vr_2d at t = 0 (lattice, dp 2e-4 / 1e-4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "case_util.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {
namespace {

using test::load_case;

struct FaceLambda {
  double worst = 0.0;  // largest |lambda - 1| of interior fluid within 3 h_coarse of the face
  double far = 0.0;    // the same further from the face (the levels' own lattice error)
  std::size_t hits[2] = {0, 0};
};

FaceLambda face_lambda(bool across) {
  CaseSpec spec =
      load_case("droplet_vr_2d.toml",
                {"resolution.dp=2e-4", std::string("numerics.vres_surface_across_levels=") +
                                           (across ? "true" : "false")});
  Simulation<2> sim(spec);
  sim.update_surface_fields();
  FaceLambda out;
  const double reach = 3 * 1.3 * 2e-4;
  for (std::size_t l = 0; l < 2; ++l) {
    const Level<2>& L = sim.level(l);
    const SurfaceFields<2>& sf = sim.surface_fields(l);
    for (std::size_t i = 0; i < L.ps.size(); ++i) {
      if (!sf.cross_hit.empty() && sf.cross_hit[i]) ++out.hits[l];
      if (L.ps.kind[i] != Kind::fluid || norm(L.ps.pos[i]) > 1.2e-3) continue;  // interior
      const double dev = std::abs(sf.lambda[i] - 1.0);
      double& slot = std::abs(L.ps.pos[i][0]) < reach ? out.worst : out.far;
      slot = std::max(slot, dev);
    }
  }
  return out;
}

// With the option the particles near the face find the other level's fluid and the interior
// lambda stays far above the free-surface threshold (0.7). Measured: the largest deviation from
// 1 within 3 h_coarse of the face 0.048 with the blended gather kernel of
// LevelCoupling::cross_sources (0.091 with the pair kernel of h_ij = (h_i + h_j) / 2, which is
// no consistent partition across a jump of h), against 0.026 elsewhere and 0.026 without the
// option (each level then sees its own buffer's lattice). With the rings fill the two levels'
// rings do not meet regularly at the face: 0.418 on (h_ij) against 0.105 off.
TEST(VresAcross, LambdaAcrossTheFaceAtTheStart) {
  const FaceLambda off = face_lambda(false), on = face_lambda(true);
  std::printf(
      "interior |lambda - 1|: near the face %.3f (option off %.3f), elsewhere %.3f; "
      "particles with cross-level neighbours %zu coarse, %zu fine\n",
      on.worst, off.worst, on.far, on.hits[0], on.hits[1]);
  EXPECT_EQ(off.hits[0] + off.hits[1], 0u);
  EXPECT_GT(on.hits[0], 50u);
  EXPECT_GT(on.hits[1], 100u);
  EXPECT_LT(off.worst, 0.05);
  EXPECT_LT(on.far, 0.05);
  EXPECT_LT(on.worst, 0.07);
}

}  // namespace
}  // namespace vrsph
