// A resolution level that holds no particle: the VR drop laid wholly outside its refinement box
// (and the box's buffer shell), so the fine level starts empty. Before the fix the first capillary
// refresh stopped the run ("force pass: cannot sum 7 terms of surface pass 1"): surface pass 1 had
// inferred whether it sums G from the size of its G array, which an empty level leaves empty with
// surface tension on. A drop that drifts out of a box empties its level mid-run in the same way.
// The run must step on, with the global dt and with local time stepping, both precisions, and
// keep the fluid's mass.
#include <gtest/gtest.h>

#include <string>

#include "case_util.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {
namespace {

using test::load_case;

TEST(VresEmptyLevel, DropOutsideTheBoxStepsOn) {
  for (const bool local : {false, true}) {
    for (const char* precision : {"double", "mixed"}) {
      CaseSpec spec = load_case(
          "droplet_vr_2d.toml",
          {"resolution.dp=2e-4", "fluid_block.0.center=[-0.004,0.0]", "domain.min=[-0.008,-0.004]",
           "case.end_time=0.0001", std::string("numerics.precision=\"") + precision + "\"",
           std::string("numerics.local_time_stepping=") + (local ? "true" : "false")});
      Simulation<2> sim(spec);
      ASSERT_EQ(sim.level_count(), 2u);
      EXPECT_EQ(sim.level(1).ps.size(), 0u) << "the fine level should start empty";
      double m0 = 0.0;
      sim.fluid_momentum(m0);
      int steps = 0;
      while (sim.time() < spec.end_time - 1e-12) {
        ASSERT_NO_THROW(sim.step()) << "local " << local << ", " << precision;
        ++steps;
      }
      double m1 = 0.0;
      sim.fluid_momentum(m1);
      EXPECT_GT(steps, 10);
      EXPECT_EQ(sim.level(1).ps.size(), 0u);
      EXPECT_EQ(m1, m0) << "local " << local << ", " << precision;
    }
  }
}

}  // namespace
}  // namespace vrsph
