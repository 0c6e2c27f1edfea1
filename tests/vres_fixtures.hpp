// Shared case texts of the variable-resolution tests.
#pragma once

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

}  // namespace vrsph::test
