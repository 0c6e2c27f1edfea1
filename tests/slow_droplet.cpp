// Droplet validation at the poster's resolution (issue #3), labelled `slow`: run by hand
// (ctest -L slow, or the binary with --gtest_filter='SlowDroplet*'); results are recorded in
// docs/validation.md. The poster's figures are asserted for the ring start with the two curvature
// options (below, and tests/slow_droplet_fine.sh at dp = 2e-5); the lattice start with the Cen
// model alone is recorded as measured (it does not reach the poster's 0.4960 Pa).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "case_util.hpp"
#include "run_util.hpp"
#include "vrsph/analysis/laplace.hpp"
#include "vrsph/driver/level_samples.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {
namespace {

using test::droplet_lattice_cen_alone;
using test::load_case;
using test::run_to;

// cases/droplet_2d.toml at dp = 5e-5 to t = 0.2 s: RMSE of the diameter pressure against 36.4 Pa.
// Poster (DualSPHysics implementation): 0.4960 Pa; our goal 0.35 Pa. VRSPH_SLOW_SHIFTING=skillen
// runs the Skillen variant.
LaplaceError run_droplet(std::vector<std::string> sets) {
  CaseSpec spec = load_case("droplet_2d.toml", sets);
  Simulation<2> sim(spec);
  run_to(sim, spec.end_time);
  const OutputLine& line = spec.lines.front();
  const LaplaceError e = levels_laplace_error<2>(sim, line, 36.4);
  std::printf("droplet_2d dp 5e-5 t 0.2: mean %.3f Pa, RMSE %.4f Pa (NRMSE %.5f), RMSE all %.4f\n",
              e.mean_interior, e.rmse, e.nrmse, e.rmse_all);
  return e;
}

// The lattice start with the Cen model alone (the shipped case until issue #20 item 5):
// measured 1.220 Pa (mean 36.10 Pa) before the mixed precision and the capillary refresh became the
// defaults; with them 1.618 Pa (mean 35.75 Pa) at c0dc8ef and 1.554 Pa (mean 35.81 Pa) at 32326f5,
// the drop's shape mode at another phase at t = 0.2 s (the 0.10-0.20 s window means: 1.547
// and 1.557 Pa). The poster's 0.4960 Pa is not reached from this start: the square outline of the
// lattice excites the n = 4 shape mode (period 8.5 ms, viscous decay time 0.17 s at nu = 1e-6), and
// the RMSE at 0.2 s is that mode's amplitude at its phase there (1.0 to 2.4 Pa over 0.08-0.12 s;
// docs/validation.md). Asserted: the Laplace mean within 3%, and the RMSE no worse than the
// measured figure plus a quarter (a regression bound, not the poster's figure).
// VRSPH_SLOW_SHIFTING=skillen runs the Skillen variant (unstable from this start at t = 0.129 s).
TEST(SlowDroplet, LatticeStartCenModelAloneHoldsTheLaplaceMean) {
  const char* model = std::getenv("VRSPH_SLOW_SHIFTING");
  std::vector<std::string> sets = droplet_lattice_cen_alone();
  if (model != nullptr && std::string(model) == "skillen") {
    sets = droplet_lattice_cen_alone(
        {"numerics.shifting.model=skillen", "numerics.shifting.coefficient=2.0"});
  }
  const LaplaceError e = run_droplet(sets);
  EXPECT_NEAR(e.mean_interior, 36.4, 0.03 * 36.4);
  EXPECT_LT(e.rmse, 1.25 * 1.554);
}

// The same drop started on concentric rings at the Laplace pressure, with the CSF curvature
// referred to the free surface (surface_offset, not part of Cen et al.) and the net capillary
// force removed (zero_net_force: the seam-free ring fill of commit c1d97cd has no mirror
// symmetry, and without it the drop drifts into the domain's edge by 0.19 s). Measured on that
// fill: RMSE 0.330 Pa (mean 36.71 Pa; 0.43 Pa averaged over the outputs of 0.10-0.20 s), one
// thread, 1,460 s, against the poster's 0.4960 Pa.
TEST(SlowDroplet, RingsWithSurfaceOffsetReachThePosterRmse) {
  const LaplaceError e = run_droplet({"fluid_block.0.fill=rings", "fluid_block.0.pressure=36.4",
                                      "numerics.surface_tension.surface_offset=true",
                                      "numerics.surface_tension.curvature_correction=false",
                                      "numerics.surface_tension.zero_net_force=true"});
  EXPECT_NEAR(e.mean_interior, 36.4, 0.02 * 36.4);
  EXPECT_LT(e.rmse, 0.4960);
}

// Rings at the Laplace pressure with the three options that are not part of Cen et al. 2024: the
// curvature referred to the free surface (surface_offset), the stencil-consistent curvature
// (curvature_correction) and zero_net_force. Measured on the seam-free fill: RMSE 0.321 Pa
// (NRMSE 0.0088, mean 36.68 Pa; 0.20 Pa averaged over the outputs of 0.10-0.20 s), one thread,
// 1,460 s: our goal of 0.35 Pa. (Without zero_net_force: 0.363 Pa; docs/validation.md.)
TEST(SlowDroplet, RingsWithOffsetAndCurvatureCorrectionReachTheGoal) {
  const LaplaceError e = run_droplet({"fluid_block.0.fill=rings", "fluid_block.0.pressure=36.4",
                                      "numerics.surface_tension.surface_offset=true",
                                      "numerics.surface_tension.curvature_correction=true",
                                      "numerics.surface_tension.zero_net_force=true"});
  EXPECT_NEAR(e.mean_interior, 36.4, 0.015 * 36.4);
  EXPECT_LT(e.rmse, 0.35);
}

// cases/droplet_3d.toml (dp 2e-4, R/dp = 10, 0.05 s) with surface_offset and
// curvature_correction: mean pressure within R/2 against 2 sigma / R = 72.8 Pa. Measured 72.84 Pa
// (+0.05%; the Cen model alone: 81.8 Pa, +12%), about 300 s on one thread.
TEST(SlowDroplet, SphereWithOffsetAndCurvatureCorrection) {
  CaseSpec spec =
      load_case("droplet_3d.toml", {"numerics.surface_tension.surface_offset=true",
                                    "numerics.surface_tension.curvature_correction=true"});
  Simulation<3> sim(spec);
  run_to(sim, spec.end_time);
  const auto& ps = sim.particles();
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.kind[i] == Kind::fluid && norm(ps.pos[i]) < 1e-3)
      sum += sim.params().eos.pressure(ps.rho[i]), ++n;
  ASSERT_GT(n, 200);
  std::printf("droplet_3d dp 2e-4 t 0.05: mean pressure within R/2 %.2f Pa (2 sigma / R = 72.8)\n",
              sum / n);
  EXPECT_NEAR(sum / n, 72.8, 0.05 * 72.8);
}

// Mean over the 11 outputs from 0.40 to 0.50 s of a VR drop case's Laplace error along its line
// (all levels), with the steps landing on every 10 ms as `vrsph run` does with its outputs, so
// the figures equal those of the CLI run's series.csv. Each sample is printed.
struct WindowError {
  double rmse = 0.0;
  double mean_interior = 0.0;
};
WindowError vr_window_error(const char* case_file, double expected,
                            const std::vector<std::string>& sets = {}) {
  CaseSpec spec = load_case(case_file, sets);
  Simulation<2> sim(spec);
  WindowError w;
  int n = 0;
  for (int k = 1; k <= 50; ++k) {
    run_to(sim, 0.01 * k);
    if (k < 40) continue;
    const LaplaceError e = levels_laplace_error(sim, spec.lines.front(), expected);
    EXPECT_GT(e.n_points, 0u) << "no particle on the line at t = " << sim.time();
    std::printf("%s t %.2f: mean %.3f Pa, RMSE %.4f Pa (NRMSE %.5f), RMSE all %.4f\n", case_file,
                sim.time(), e.mean_interior, e.rmse, e.nrmse, e.rmse_all);
    w.rmse += e.rmse, w.mean_interior += e.mean_interior, ++n;
  }
  w.rmse /= n, w.mean_interior /= n;
  std::printf("%s 0.4-0.5 s: mean RMSE %.4f Pa, mean interior %.3f Pa\n", case_file, w.rmse,
              w.mean_interior);
  return w;
}

// cases/droplet_vr_2d.toml (dp 1e-4 / 5e-5, 4h buffers, the case's options: rings, Shepard buffer
// values) to t = 0.5 s: the window mean of the RMSE against the poster's VR figure, 0.7708 Pa.
// The CLI runs of the case (two draws, build 9593495) measured window means of 0.42 and 0.45 Pa,
// mean interior 36.82-36.85 Pa; the lattice start with first-order values it replaced, 2.15 Pa
// and 38.2 Pa (docs/validation.md, "The shipped VR drop becomes the quiet combination"). On an
// AMD EPYC (build 0a8c4c7) the draw this test runs (cfl 0.2) gave 0.368 Pa; the draw at cfl
// 0.2000001 2.01 Pa and 38.40 Pa, the drop held elongated by the face from 0.21 s
// (docs/validation.md, "The shipped VR drop's second draw").
TEST(SlowDroplet, VariableResolutionBeatsThePosterRmse) {
  const WindowError w = vr_window_error("droplet_vr_2d.toml", 36.4);
  EXPECT_NEAR(w.mean_interior, 36.4, 0.03 * 36.4);
  EXPECT_LT(w.rmse, 0.7708);
}

// The draw that "edge" holds elongated (cfl 0.2000001: 2.01 Pa, mean interior 38.40 Pa) with
// vres_buffer_surface = "edge_kink" and the threshold of the drop's radius (R_k = 2 mm, a =
// dp_coarse / R_k = 0.05): the buffer normals take the other level's at the notch, and the drop
// stays round. Measured 0.417 Pa, mean interior 36.82 Pa, aspect 0.8% (docs/validation.md, "The
// threshold from the resolution"). Bounds: the poster's VR figure and 3% of sigma / R, which the
// pinned run misses (2.01 Pa, +5.5%).
TEST(SlowDroplet, EdgeKinkKeepsThePinnedDrawRound) {
  const WindowError w =
      vr_window_error("droplet_vr_2d.toml", 36.4,
                      {"numerics.cfl=0.2000001", "numerics.vres_buffer_surface=\"edge_kink\"",
                       "numerics.vres_kink_radius=0.002"});
  EXPECT_NEAR(w.mean_interior, 36.4, 0.03 * 36.4);
  EXPECT_LT(w.rmse, 0.7708);
}

// cases/square_droplet_vr_2d.toml (the square of side 4 mm relaxing to a circle of equal area,
// 32.26 Pa; same levels and options, both levels filled at their cell centres, deletion at fill
// 0.4): the window mean against the poster's VR square figure, 1.1036 Pa, and the mean interior
// pressure within 3%. Measured: 0.1756 Pa, mean interior 32.434 Pa (2,196 s on one thread); the CLI
// run of the case 0.183 Pa (docs/validation.md).
TEST(SlowDroplet, SquareVariableResolutionBeatsThePosterRmse) {
  const WindowError w = vr_window_error("square_droplet_vr_2d.toml", 32.26);
  EXPECT_NEAR(w.mean_interior, 32.26, 0.03 * 32.26);
  EXPECT_LT(w.rmse, 1.1036);
}

}  // namespace
}  // namespace vrsph

namespace vrsph {
namespace {

// Mean EOS pressure of each level's fluid particles within `radius` of the fluid's centre of mass.
std::array<double, 2> side_pressures(const Simulation<2>& sim, double radius) {
  Vec<2> c{};
  double m = 0.0;
  for (std::size_t l = 0; l < 2; ++l) {
    const auto& ps = sim.level(l).ps;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.kind[i] == Kind::fluid) c += ps.mass_of(i) * ps.pos[i], m += ps.mass_of(i);
  }
  c = (1.0 / m) * c;
  std::array<double, 2> mean{};
  for (std::size_t l = 0; l < 2; ++l) {
    const Level<2>& L = sim.level(l);
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < L.ps.size(); ++i)
      if (L.ps.kind[i] == Kind::fluid && norm(L.ps.pos[i] - c) < radius)
        sum += L.prm.eos.pressure(L.ps.rho[i]), ++n;
    EXPECT_GT(n, 20) << "level " << l << " at t = " << sim.time();
    mean[l] = sum / n;
  }
  return mean;
}

// Issue #20, item 6: the drop straddling the face (droplet_vr_2d at half the poster's resolution,
// coarse 2e-4, fine 1e-4) reaches the same Laplace pressure on both sides: the mean pressure of
// each level's fluid within 1.5 mm of the centroid, averaged over the outputs of 0.10-0.30 s,
// within 1% between the levels and within 3% of sigma / R. Three runs: the shipped case (rings,
// Shepard buffer values) with the face through the centre, the combination shipped before
// (lattice, first-order buffer values), and the shipped case with the face at x = 1 mm, off the
// drop's centre. Measured (build 9b07041, docs/validation.md): -0.05% (36.290 / 36.272 Pa),
// -0.08% (36.805 / 36.775 Pa), and off the centre -0.99% (36.249 / 35.889 Pa), on the target's
// edge. About 65 s each on one thread (OMP_NUM_THREADS=1).
class SlowVresSides : public ::testing::TestWithParam<std::vector<std::string>> {};

TEST_P(SlowVresSides, BothLevelsReachTheSameLaplacePressure) {
  std::vector<std::string> sets = {"resolution.dp=2e-4", "case.end_time=0.3"};
  sets.insert(sets.end(), GetParam().begin(), GetParam().end());
  CaseSpec spec = load_case("droplet_vr_2d.toml", sets);
  Simulation<2> sim(spec);
  ASSERT_EQ(sim.level_count(), 2u);
  std::array<double, 2> sum{};
  int n = 0;
  for (int k = 1; k <= 30; ++k) {  // landing on every 10 ms, as the CLI run with its outputs
    run_to(sim, 0.01 * k);
    if (k < 10) continue;
    const std::array<double, 2> p = side_pressures(sim, 1.5e-3);
    sum[0] += p[0], sum[1] += p[1], ++n;
  }
  const double coarse = sum[0] / n, fine = sum[1] / n;
  std::printf(
      "droplet_vr_2d dp 2e-4, 0.1-0.3 s: coarse side %.3f Pa, fine side %.3f Pa (%+.2f%%)\n",
      coarse, fine, 100.0 * (fine / coarse - 1.0));
  EXPECT_NEAR(fine / coarse, 1.0, 0.01);
  EXPECT_NEAR(coarse, 36.4, 0.03 * 36.4);
  EXPECT_NEAR(fine, 36.4, 0.03 * 36.4);
}

INSTANTIATE_TEST_SUITE_P(
    Combinations, SlowVresSides,
    ::testing::Values(
        std::vector<std::string>{},  // the shipped case: rings, Shepard buffer values
        std::vector<std::string>{"fluid_block.0.fill=\"lattice\"", "numerics.vres_shepard_fill=0"},
        std::vector<std::string>{"refinement.0.min=[0.001,-0.003]",
                                 "refinement.0.max=[0.0045,0.003]", "domain.max=[0.005,0.004]"}));

}  // namespace
}  // namespace vrsph
