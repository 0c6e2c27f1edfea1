// Shared case texts of the variable-resolution tests, and a run of the uniform flow.
#pragma once

#include <gtest/gtest.h>

#include "vrsph/sim/simulation.hpp"

namespace vrsph::test {

// A block moving at U = 1 m/s with no gravity through the face x = 0 of a refinement box
// (VresFlux.CreatedMassMatchesFlux, VresRamp.FlowThroughAnInterfaceKeepsItsMass and the
// local-stepping flux tests).
inline constexpr const char* kUniformFlowThroughAFace = R"(
[case]
name = "flux"
dimension = 2
end_time = 0.1
[fluid]
kinematic_viscosity = 1.0e-4
gravity = [0.0, 0.0]
[eos]
max_speed = 1.0
[resolution]
dp = 0.01
[numerics]
viscosity = { model = "laminar" }
density_diffusion = { model = "molteni", delta = 0.1 }
[[fluid_block]]
shape = "box"
min = [-0.6, 0.0]
max = [0.3, 0.39]
velocity = [1.0, 0.0]
[domain]
min = [-1.0, -0.5]
max = [1.5, 0.9]
[[refinement]]
min = [0.0, -0.3]
max = [0.8, 0.7]
[output]
interval = 0.1
)";

// kUniformFlowThroughAFace (with the options `spec` sets) run to its end: the mass the flow
// carries across the face (rho U H t), the mass created and deleted, the fluid mass before and
// after.
struct FaceFlow {
  double flux = 0.0, created = 0.0, deleted = 0.0, m0 = 0.0, m1 = 0.0;
};
inline FaceFlow run_face_flow(CaseSpec& spec) {
  Simulation<2> sim(spec);
  FaceFlow f;
  sim.fluid_momentum(f.m0);
  while (sim.time() < spec.end_time - 1e-12) sim.step();
  sim.fluid_momentum(f.m1);
  f.flux = 1000.0 * 1.0 * 0.4 * spec.end_time;
  f.created = sim.counters().created_mass;
  f.deleted = sim.counters().deleted_mass;
  return f;
}
// Created and deleted mass within 1% of the flux, and the fluid mass kept within 1%.
inline void expect_face_flow_keeps_mass(const FaceFlow& f) {
  EXPECT_NEAR(f.created, f.flux, 0.01 * f.flux);
  EXPECT_NEAR(f.deleted, f.flux, 0.01 * f.flux);
  EXPECT_NEAR(f.m1 / f.m0, 1.0, 0.01);
}

}  // namespace vrsph::test
