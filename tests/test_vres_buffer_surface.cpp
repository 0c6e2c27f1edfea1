// Where buffer particles take lambda and the normal from (numerics.vres_buffer_surface;
// vres/level_coupling.cpp exchange_buffer_field; issue #20 item 4, the coupling as published):
// their own level's sums ("own"), the other level's fluid near the outer edge of their shell
// ("edge", the default) or everywhere in it ("donor"), or lambda as "edge" and the normal as
// "donor" ("donor_normals"), or as "edge" with the normal moved to the other level's where the
// two disagree ("edge_kink"). droplet_vr_2d at dp 2e-4 / 1e-4, t = 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "case_parser_fixtures.hpp"
#include "case_util.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/vres/kink_normal.hpp"

namespace vrsph {
namespace {

using test::load_case;

struct BufferLambda {
  double lowest = 1.0;       // lowest lambda of the interior buffer particles (r < 1.2 mm)
  double largest_dev = 0.0;  // largest |lambda - 1| among them
  std::size_t count = 0;
};

BufferLambda interior_buffer_lambda(const std::string& mode) {
  CaseSpec spec =
      load_case("droplet_vr_2d.toml",
                {"resolution.dp=2e-4", "fluid_block.0.fill=\"lattice\"",
                 "numerics.vres_shepard_fill=0", "numerics.vres_buffer_surface=\"" + mode + "\""});
  Simulation<2> sim(spec);
  sim.update_surface_fields();
  BufferLambda out;
  for (std::size_t l = 0; l < 2; ++l) {
    const Level<2>& L = sim.level(l);
    const SurfaceFields<2>& sf = sim.surface_fields(l);
    for (std::size_t i = 0; i < L.ps.size(); ++i) {
      if (L.ps.kind[i] != Kind::buffer || norm(L.ps.pos[i]) > 1.2e-3) continue;
      out.lowest = std::min(out.lowest, sf.lambda[i]);
      out.largest_dev = std::max(out.largest_dev, std::abs(sf.lambda[i] - 1.0));
      ++out.count;
    }
  }
  std::printf("vres_buffer_surface \"%s\": %zu interior buffer particles, lowest lambda %.3f\n",
              mode.c_str(), out.count, out.lowest);
  return out;
}

// Inside the drop there is no free surface. With "own" the buffer particles at the outer edge of
// their shell sum over a support cut by the shell's edge, so their lambda falls far below 1
// (measured 0.487: a surface that is not there); "edge" and "donor" replace it with the other
// level's value, which is about 1 at every interior point.
TEST(VresBufferSurface, OwnSumsSeeTheShellEdgeAndTheExchangeRemovesIt) {
  const BufferLambda own = interior_buffer_lambda("own");
  const BufferLambda edge = interior_buffer_lambda("edge");
  const BufferLambda donor = interior_buffer_lambda("donor");
  ASSERT_GT(own.count, 20u);
  EXPECT_EQ(own.count, edge.count);
  EXPECT_EQ(own.count, donor.count);
  EXPECT_LT(own.lowest, 0.8);
  EXPECT_GT(edge.lowest, 0.85);   // measured 0.905
  EXPECT_GT(donor.lowest, 0.85);  // measured 0.974
  EXPECT_LE(donor.largest_dev, edge.largest_dev + 1e-12);
}

// Every level's surface fields and particle kinds after update_surface_fields, for the VR drop at
// dp 2e-4 with vres_buffer_surface = mode and the further overrides `sets`.
struct LevelFields {
  std::vector<SurfaceFields<2>> sf;
  std::vector<std::vector<Kind>> kind;
};
LevelFields surface_fields_with(const std::string& mode, std::vector<std::string> sets = {}) {
  sets.push_back("resolution.dp=2e-4");
  sets.push_back("numerics.vres_buffer_surface=\"" + mode + "\"");
  CaseSpec spec = load_case("droplet_vr_2d.toml", sets);
  Simulation<2> sim(spec);
  sim.update_surface_fields();
  LevelFields out;
  for (std::size_t l = 0; l < 2; ++l) {
    out.sf.push_back(sim.surface_fields(l));
    out.kind.push_back(sim.level(l).ps.kind);
  }
  return out;
}

// kink_normal with threshold a = 0.1: the own normal where the other level's differs from it by at
// most a, the other level's from 3a on, a unit vector between the two in between; a zero normal
// on either side leaves the own one.
TEST(VresBufferSurface, KinkNormalTakesTheDonorOnlyAtAKink) {
  const Vec<2> up{0.0, 1.0};
  auto tilted = [](double angle) { return Vec<2>{std::sin(angle), std::cos(angle)}; };
  // |n_d - n_o| = 2 sin(angle / 2)
  const Vec<2> near = tilted(0.08), far = tilted(0.5), mid = tilted(0.2);
  EXPECT_EQ(kink_normal(up, near, 0.1)[0], 0.0);
  EXPECT_EQ(kink_normal(up, far, 0.1)[0], far[0]);
  EXPECT_EQ(kink_normal(up, far, 0.1)[1], far[1]);
  const Vec<2> m = kink_normal(up, mid, 0.1);  // |n_d - n_o| = 0.1997: s = 0.4983
  EXPECT_NEAR(norm(m), 1.0, 1e-15);
  EXPECT_GT(m[0], 0.4 * mid[0]);
  EXPECT_LT(m[0], 0.6 * mid[0]);
  const Vec<2> zero{};
  EXPECT_EQ(norm(kink_normal(zero, far, 0.1)), 0.0);
  EXPECT_EQ(kink_normal(up, zero, 0.1)[1], 1.0);
}

// "donor_normals": lambda exactly as "edge" (so also every fluid particle's normal, which sums
// over lambda), while every buffer particle's normal is the other level's: in the inner part of
// the shell, where "edge" keeps the level's own normal, some change (the surface particles of the
// buffer next to the face, at both crossings of each level).
TEST(VresBufferSurface, DonorNormalsChangeOnlyTheBufferNormals) {
  const LevelFields e = surface_fields_with("edge"), d = surface_fields_with("donor_normals");
  const auto& edge = e.sf;
  const auto& dn = d.sf;
  std::size_t changed = 0, buffers = 0;
  for (std::size_t l = 0; l < 2; ++l) {
    const std::vector<Kind>& kind = e.kind[l];
    ASSERT_EQ(d.kind[l], kind);
    ASSERT_EQ(dn[l].normal.size(), kind.size());
    for (std::size_t i = 0; i < kind.size(); ++i) {
      EXPECT_EQ(dn[l].lambda[i], edge[l].lambda[i]) << "level " << l << ", particle " << i;
      const Vec<2> a = dn[l].normal[i], b = edge[l].normal[i];
      if (kind[i] != Kind::buffer) {
        EXPECT_TRUE(a[0] == b[0] && a[1] == b[1]) << "fluid normal, level " << l << ", " << i;
        continue;
      }
      ++buffers;
      const double m = norm(a);
      EXPECT_TRUE(m == 0.0 || std::abs(m - 1.0) < 1e-12) << "buffer normal of length " << m;
      if (norm(a - b) > 1e-6) ++changed;
    }
  }
  std::printf("donor_normals: %zu of %zu buffer normals differ from edge's\n", changed, buffers);
  EXPECT_GE(changed, 4u);
}

// "edge_kink": lambda and every fluid normal exactly as "edge", and each buffer normal
// kink_normal(edge's, donor_normals', a = dp_coarse / R_k = 2e-4 / 2e-3 = 0.1) (both runs take
// the donor's normal from the same fields).
// The lattice start (a square outline cut off by the circle) meets the face with kinks at t = 0:
// there some buffer normals move (measured 8 of the 38 that donor_normals changes).
TEST(VresBufferSurface, EdgeKinkBlendsOnlyWhereTheLevelsDisagree) {
  const std::vector<std::string> sets = {"fluid_block.0.fill=\"lattice\"",
                                         "numerics.vres_kink_radius=0.002"};
  const LevelFields edge = surface_fields_with("edge", sets);
  const LevelFields donor = surface_fields_with("donor_normals", sets);
  const LevelFields kink = surface_fields_with("edge_kink", sets);
  std::size_t moved = 0, differ = 0;
  for (std::size_t l = 0; l < 2; ++l) {
    const std::vector<Kind>& kind = edge.kind[l];
    ASSERT_EQ(kink.kind[l], kind);
    for (std::size_t i = 0; i < kind.size(); ++i) {
      const Vec<2> e = edge.sf[l].normal[i], d = donor.sf[l].normal[i];
      const Vec<2> k = kink.sf[l].normal[i];
      EXPECT_EQ(kink.sf[l].lambda[i], edge.sf[l].lambda[i]);
      const Vec<2> want = kind[i] == Kind::buffer ? kink_normal(e, d, 0.1) : e;
      EXPECT_TRUE(k[0] == want[0] && k[1] == want[1]) << "level " << l << ", particle " << i;
      if (kind[i] != Kind::buffer) continue;
      if (norm(d - e) > 1e-6) ++differ;
      if (norm(k - e) > 1e-6) ++moved;
    }
  }
  std::printf("edge_kink: %zu buffer normals moved of %zu where donor_normals differs\n", moved,
              differ);
  EXPECT_GT(moved, 0u);
  EXPECT_LT(moved, differ);
}

// Also numerics.vres_shepard_fill (vres/interpolation.hpp), checked here with its neighbour key.
TEST(VresBufferSurface, KeysAreCheckedAndWrittenBack) {
  using namespace case_fixtures;
  expect_contains(error_of(with_numerics("vres_buffer_surface = \"all\"\n")),
                  {"numerics.vres_buffer_surface", "all", "own"});
  const CaseSpec s = parse_text(with_numerics("vres_buffer_surface = \"own\"\n"));
  EXPECT_EQ(s.vres_buffer_surface, BufferSurface::own);
  EXPECT_EQ(written_back(s).vres_buffer_surface, BufferSurface::own);
  const CaseSpec n = parse_text(with_numerics("vres_buffer_surface = \"donor_normals\"\n"));
  EXPECT_EQ(written_back(n).vres_buffer_surface, BufferSurface::donor_normals);
  const CaseSpec k = parse_text(with_numerics("vres_buffer_surface = \"edge_kink\"\n"));
  EXPECT_EQ(written_back(k).vres_buffer_surface, BufferSurface::edge_kink);
  EXPECT_EQ(k.vres_kink_radius, 0.0) << "0: 10 dp of level 0";
  const CaseSpec a =
      parse_text(with_numerics("vres_buffer_surface = \"edge_kink\"\nvres_kink_radius = 0.002\n"));
  EXPECT_EQ(written_back(a).vres_kink_radius, 0.002);
  expect_contains(error_of(with_numerics("vres_kink_radius = -1\n")),
                  {"numerics.vres_kink_radius = -1", "at least 0"});
  expect_contains(error_of(with_numerics("vres_shepard_fill = 3\n")),
                  {"numerics.vres_shepard_fill = 3", "[0, 2]"});
  const CaseSpec dflt = parse_text(kMinimal);
  EXPECT_EQ(dflt.vres_shepard_fill, 0.0);
  EXPECT_EQ(dflt.vres_buffer_surface, BufferSurface::edge);
}

}  // namespace
}  // namespace vrsph
