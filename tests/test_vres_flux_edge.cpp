// Mass points that pass their flux inward below a donor fill (numerics.vres_flux_edge,
// vres/flux_edge.hpp; issue #20, item 6): the neighbours on a face, the moves, the key, and mass
// through an interface with the option on.
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "case_parser_fixtures.hpp"
#include "case_util.hpp"
#include "vres_fixtures.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/vres/flux_edge.hpp"

namespace vrsph {
namespace {

// A face at x = 0 with points every dp along y (normal -x), and one point of a perpendicular
// face beside its end (normal +y).
std::vector<MassPoint<2>> face_points(double dp, int n) {
  std::vector<MassPoint<2>> pts;
  for (int k = 0; k < n; ++k) pts.push_back({{{0.0, k * dp}}, {{-1.0, 0.0}}, dp, 1, 0.0});
  pts.push_back({{{0.5 * dp, (n - 0.5) * dp}}, {{0.0, 1.0}}, dp, 1, 0.0});
  return pts;
}

// Nearest neighbours along the face, both ways; none across to the other face.
TEST(VresFluxEdge, NeighboursOnTheFace) {
  const double dp = 1e-4;
  const auto nb = mass_point_neighbours(face_points(dp, 5), dp);
  ASSERT_EQ(nb.size(), 6u);
  EXPECT_EQ(nb[0], (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(nb[2].size(), 2u);
  EXPECT_EQ(nb[4], (std::vector<std::uint32_t>{3})) << "not the perpendicular face's point";
  EXPECT_TRUE(nb[5].empty());
}

// Fills along the face 0.1, 0.3, 0.7, 1, 1, 0.95, 0.45 (a drop's section with two surfaces) and
// a point that does not accumulate (-1): below 0.5 the increments walk up the fill to the first
// point at or above 0.5; nothing else moves, and their sum is kept.
TEST(VresFluxEdge, IncrementsMoveInsideTheEdge) {
  const double dp = 1e-4;
  const auto nb = mass_point_neighbours(face_points(dp, 8), dp);
  const std::vector<double> fill = {0.1, 0.3, 0.7, 1.0, 1.0, 0.95, 0.45, -1.0, -1.0};
  std::vector<double> dm = {1, 2, 3, 4, 5, 6, 7, 0, 0};
  const double total = std::accumulate(dm.begin(), dm.end(), 0.0);
  move_flux_inward(dm, fill, nb, 0.5);
  EXPECT_EQ(dm, (std::vector<double>{0, 0, 6, 4, 5, 13, 0, 0, 0}));
  EXPECT_EQ(std::accumulate(dm.begin(), dm.end(), 0.0), total);
  // a point below the edge with no neighbour of higher fill keeps its own and takes the rest
  const std::vector<double> low = {0.2, 0.4, 0.3, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0};
  std::vector<double> dl = {1, 2, 3, 0, 0, 0, 0, 0, 0};
  move_flux_inward(dl, low, nb, 0.5);
  EXPECT_EQ(dl, (std::vector<double>{0, 6, 0, 0, 0, 0, 0, 0, 0}));
  // without the neighbours formed it refuses rather than read past them
  EXPECT_THROW(move_flux_inward(dl, low, {}, 0.5), std::logic_error);
}

// The uniform flow of VresFlux.CreatedMassMatchesFlux (test_vres.cpp) fills its face, so the
// option moves nothing there: the created mass still matches the flux and the fluid keeps its
// mass, as without it.
TEST(VresFluxEdge, FlowThroughAnInterfaceKeepsItsMass) {
  CaseSpec spec = parse_case(toml::parse(test::kUniformFlowThroughAFace), "test");
  spec.vres_flux_edge = 0.5;
  const test::FaceFlow f = test::run_face_flow(spec);
  test::expect_face_flow_keeps_mass(f);
}

TEST(VresFluxEdge, KeyIsCheckedAndWrittenBack) {
  using namespace case_fixtures;
  expect_contains(error_of(with_numerics("vres_flux_edge = 1.2\n")),
                  {"numerics.vres_flux_edge = 1.2", "[0, 1)"});
  const CaseSpec s = parse_text(with_numerics("vres_flux_edge = 0.5\n"));
  EXPECT_EQ(s.vres_flux_edge, 0.5);
  EXPECT_EQ(written_back(s).vres_flux_edge, 0.5);
  EXPECT_EQ(parse_text(with_numerics("")).vres_flux_edge, 0.0) << "off by default";
}

}  // namespace
}  // namespace vrsph
