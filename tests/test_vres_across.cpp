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
  CaseSpec spec = load_case(
      "droplet_vr_2d.toml",
      {"resolution.dp=2e-4", "fluid_block.0.fill=\"lattice\"", "numerics.vres_shepard_fill=0",
       std::string("numerics.vres_surface_across_levels=") + (across ? "true" : "false")});
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

// Issue #20 item 6: lambda along the face of the static drop (droplet_vr_2d on the lattice with
// first-order buffer values, the case as shipped before it took rings and Shepard values; half
// resolution, the face x = 0 through the drop's centre) is continuous: the largest difference
// between neighbouring fluid particles of the two levels is no larger than between neighbours
// within either level (pairs closer than 1.5 dp_coarse, inside R - 3 h_coarse of the centre of
// mass, where lambda is not a free-surface value). Measured at 0.02 s: face 0.0331 (84 pairs),
// within a level 0.0426. Later in the run the face's jumps reach 1.2x the levels' (0.036 against
// 0.029 at 0.2 s; docs/validation.md, "The rings + Shepard VR drop against the tests of item
// 6"), which this test, kept short, does not cover. The shipped case (rings, Shepard values)
// gives 0.0484 across the face against 0.0345 within a level at 0.02 s: 1.4x, not continuous in
// this sense (docs/validation.md, "The shipped VR drop becomes the quiet combination").
TEST(VresAcross, LambdaIsContinuousAcrossTheFace) {
  CaseSpec spec = load_case("droplet_vr_2d.toml",
                            {"resolution.dp=2e-4", "case.end_time=0.02",
                             "fluid_block.0.fill=\"lattice\"", "numerics.vres_shepard_fill=0"});
  Simulation<2> sim(spec);
  while (sim.time() < spec.end_time - 1e-12) sim.step();
  sim.update_surface_fields();
  const double dp = 2e-4, h = 1.3 * dp;
  Vec<2> centre{};
  double mass = 0.0;
  for (std::size_t l = 0; l < 2; ++l) {
    const ParticleSet<2>& ps = sim.level(l).ps;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.kind[i] != Kind::fluid) continue;
      centre += ps.pos[i] * ps.mass_of(i);
      mass += ps.mass_of(i);
    }
  }
  centre = centre * (1.0 / mass);
  struct P {
    Vec<2> x;
    double lambda;
    std::size_t level;
  };
  std::vector<P> inner;
  for (std::size_t l = 0; l < 2; ++l) {
    const ParticleSet<2>& ps = sim.level(l).ps;
    const SurfaceFields<2>& sf = sim.surface_fields(l);
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.kind[i] == Kind::fluid && norm(ps.pos[i] - centre) < 0.002 - 3 * h)
        inner.push_back({ps.pos[i], sf.lambda[i], l});
  }
  double face = 0.0, within = 0.0;
  std::size_t face_pairs = 0;
  for (std::size_t a = 0; a < inner.size(); ++a)
    for (std::size_t b = a + 1; b < inner.size(); ++b) {
      if (norm(inner[a].x - inner[b].x) >= 1.5 * dp) continue;
      const double jump = std::abs(inner[a].lambda - inner[b].lambda);
      if (inner[a].level != inner[b].level) {
        face = std::max(face, jump);
        ++face_pairs;
      } else {
        within = std::max(within, jump);
      }
    }
  std::printf("lambda jumps at 0.02 s: across the face %.4f (%zu pairs), within a level %.4f\n",
              face, face_pairs, within);
  EXPECT_GT(face_pairs, 50u);
  EXPECT_GT(within, 0.0);
  EXPECT_LE(face, within);
}

}  // namespace
}  // namespace vrsph
