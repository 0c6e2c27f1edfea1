// The case-file layer: defaults and the round trip through case_to_toml (docs/cases.md); errors
// and --set overrides: test_case_errors.cpp.
#include <gtest/gtest.h>

#include <string>

#include "case_parser_fixtures.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace vrsph {
namespace {

using namespace case_fixtures;

// A 2D case that sets every key of the format to a non-default value.
constexpr const char* kEveryKey = R"(
[case]
name = "every_key"
dimension = 2
end_time = 0.5
[fluid]
density = 998.2
kinematic_viscosity = 1.1e-6
surface_tension = 0.0728
gravity = [0.1, -9.81]
[eos]
gamma = 7.5
max_speed = 0.5
sound_speed_factor = 15
sound_speed = 12.5
[resolution]
dp = 5.0e-5
h_over_dp = 1.5
[numerics]
cfl = 0.25
viscosity = { model = "artificial", alpha = 0.02 }
density_diffusion = { model = "fourtakas", delta = 0.12 }
shifting = { model = "skillen", coefficient = 1.5, surface_threshold = 1.4 }
surface_tension = { lambda_threshold = 0.75, normal_epsilon = 0.11, surface_offset = true, curvature_correction = true }
hydrostatic_initial_density = false
vres_conserve_momentum = true
vres_buffer_fill_min = 0.3
vres_buffer_surface = "donor"
vres_shepard_fill = 0.9
start_damping_time = 0.03
start_damping_tau = 0.002
[[fluid_block]]
shape = "circle"
center = [0.001, -0.0005]
radius = 0.002
fill = "rings"
velocity = [0.01, 0.02]
[[fluid_block]]
shape = "box"
min = [-0.003, -0.003]
max = [-0.002, 1e-3]
[[wall_block]]
shape = "tank"
min = [-0.0035, -0.0035]
max = [0.0035, 0.0035]
layers = 4
[[wall_block]]
shape = "box"
min = [0.0, -0.0035]
max = [0.001, -0.003]
[domain]
min = [-0.004, -0.004]
max = [0.004, 0.004]
max_lost_fraction = 0.05
[[refinement]]
min = [0.0, -0.003]
max = [0.003, 0.003]
dp_ratio = 3
buffer_width = 2.0
buffer_rounding = "whole_dp"
[[refinement]]
min = [0.001, -0.001]
max = [0.002, 0.001]
[output]
interval = 0.01
formats = ["csv"]
precision = "float32"
compression = "zlib"
[[output.line]]
name = "diameter"
from = [-0.002, 0.0]
to = [0.002, 0.0]
[[output.line]]
name = "vertical-2"
from = [0.0, -0.002]
to = [0.0, 0.002]
[analysis]
laplace_pressure = 36.4
)";

TEST(CaseParser, MinimalCaseGetsPhysicsDefaults) {
  const CaseSpec s = parse_text(kMinimal);
  EXPECT_EQ(s.name, "droplet");
  EXPECT_EQ(s.dimension, 2);
  EXPECT_DOUBLE_EQ(s.end_time, 0.2);
  EXPECT_DOUBLE_EQ(s.fluid.density, 1000.0);
  EXPECT_DOUBLE_EQ(s.fluid.kinematic_viscosity, 1e-6);
  EXPECT_DOUBLE_EQ(s.fluid.surface_tension, 0.0);
  EXPECT_EQ(s.fluid.gravity, (Vec3d{0, 0, 0}));
  EXPECT_DOUBLE_EQ(s.eos.gamma, 7.0);
  EXPECT_FALSE(s.eos.max_speed.has_value());
  EXPECT_DOUBLE_EQ(s.eos.sound_speed_factor, 20.0);
  EXPECT_FALSE(s.eos.sound_speed.has_value());
  EXPECT_DOUBLE_EQ(s.dp, 1e-4);
  EXPECT_DOUBLE_EQ(s.h_over_dp, 1.3);
  EXPECT_DOUBLE_EQ(s.numerics.cfl, 0.2);
  EXPECT_EQ(s.numerics.viscosity.model, ViscosityModel::laminar);
  EXPECT_DOUBLE_EQ(s.numerics.viscosity.alpha, 0.01);
  EXPECT_EQ(s.numerics.density_diffusion.model, DiffusionModel::molteni);
  EXPECT_DOUBLE_EQ(s.numerics.density_diffusion.delta, 0.1);
  EXPECT_EQ(s.numerics.shifting.model, ShiftingModel::none);
  EXPECT_DOUBLE_EQ(s.numerics.shifting.surface_threshold, 1.5);
  EXPECT_DOUBLE_EQ(s.numerics.surface_tension.lambda_threshold, 0.7);
  EXPECT_DOUBLE_EQ(s.numerics.surface_tension.normal_epsilon, 0.1);
  EXPECT_DOUBLE_EQ(s.vres_buffer_fill_min, 0.0);  // Ricci et al.'s rule only
  EXPECT_TRUE(s.numerics.hydrostatic_initial_density);
  ASSERT_EQ(s.fluid_blocks.size(), 1u);
  EXPECT_EQ(s.fluid_blocks[0].shape, BlockShape::circle);
  EXPECT_DOUBLE_EQ(s.fluid_blocks[0].radius, 0.002);
  EXPECT_EQ(s.fluid_blocks[0].fill, FillMode::lattice);
  EXPECT_EQ(s.fluid_blocks[0].velocity, (Vec3d{0, 0, 0}));
  EXPECT_TRUE(s.wall_blocks.empty());
  EXPECT_FALSE(s.domain_min.has_value());
  EXPECT_DOUBLE_EQ(s.max_lost_fraction, 0.01);
  EXPECT_TRUE(s.refinements.empty());
  EXPECT_DOUBLE_EQ(s.output_interval, 0.0);
  EXPECT_TRUE(s.write_vtp);
  EXPECT_TRUE(s.write_csv);
  EXPECT_EQ(s.output_precision, OutputPrecision::float64);
  EXPECT_EQ(s.output_compression, OutputCompression::none);
  EXPECT_TRUE(s.lines.empty());
  EXPECT_FALSE(s.laplace_pressure.has_value());
}

TEST(CaseParser, ModelAndDimensionDependentDefaults) {
  const std::string sphere =
      edited("dimension = 2", "dimension = 3",
             edited("\"circle\"\ncenter = [0.0, 0.0]", "\"sphere\"\ncenter = [0.0, 0.0, 0.0]"));
  const CaseSpec s3 = parse_text(sphere + "[numerics]\nshifting = { model = \"skillen\" }\n");
  EXPECT_DOUBLE_EQ(s3.numerics.shifting.surface_threshold, 2.75);
  EXPECT_DOUBLE_EQ(s3.numerics.shifting.coefficient, 2.0);
  EXPECT_EQ(s3.fluid.gravity, (Vec3d{0, 0, 0}));
  const CaseSpec lind =
      parse_text(std::string(kMinimal) + "[numerics]\nshifting = { model = \"lind\" }\n");
  EXPECT_DOUBLE_EQ(lind.numerics.shifting.coefficient, 0.05);
}

TEST(CaseParser, IntegersAcceptedForFloats) {
  const CaseSpec s =
      parse_text(edited("dp = 1e-4", "dp = 1", edited("radius = 0.002", "radius = 2")));
  EXPECT_DOUBLE_EQ(s.dp, 1.0);
  EXPECT_DOUBLE_EQ(s.fluid_blocks[0].radius, 2.0);
}

TEST(CaseParser, RoundTripEveryKey) {
  const CaseSpec s = parse_text(kEveryKey);
  const std::string text = case_to_toml(s);
  const CaseSpec r = reparse(text);
  // Field by field first, for readable failures, then the whole struct.
  EXPECT_EQ(r.name, s.name);
  EXPECT_EQ(r.dimension, s.dimension);
  EXPECT_EQ(r.end_time, s.end_time);
  EXPECT_EQ(r.fluid.density, s.fluid.density);
  EXPECT_EQ(r.fluid.kinematic_viscosity, s.fluid.kinematic_viscosity);
  EXPECT_EQ(r.fluid.surface_tension, s.fluid.surface_tension);
  EXPECT_EQ(r.fluid.gravity, s.fluid.gravity);
  EXPECT_EQ(r.eos.gamma, s.eos.gamma);
  EXPECT_EQ(r.eos.max_speed, s.eos.max_speed);
  EXPECT_EQ(r.eos.sound_speed_factor, s.eos.sound_speed_factor);
  EXPECT_EQ(r.eos.sound_speed, s.eos.sound_speed);
  EXPECT_EQ(r.dp, s.dp);
  EXPECT_EQ(r.h_over_dp, s.h_over_dp);
  EXPECT_EQ(r.numerics.cfl, s.numerics.cfl);
  EXPECT_EQ(r.numerics.viscosity.model, s.numerics.viscosity.model);
  EXPECT_EQ(r.numerics.viscosity.alpha, s.numerics.viscosity.alpha);
  EXPECT_EQ(r.numerics.density_diffusion.model, s.numerics.density_diffusion.model);
  EXPECT_EQ(r.numerics.density_diffusion.delta, s.numerics.density_diffusion.delta);
  EXPECT_EQ(r.numerics.shifting.model, s.numerics.shifting.model);
  EXPECT_EQ(r.numerics.shifting.coefficient, s.numerics.shifting.coefficient);
  EXPECT_EQ(r.numerics.shifting.surface_threshold, s.numerics.shifting.surface_threshold);
  EXPECT_EQ(r.numerics.surface_tension.lambda_threshold,
            s.numerics.surface_tension.lambda_threshold);
  EXPECT_EQ(r.numerics.surface_tension.normal_epsilon, s.numerics.surface_tension.normal_epsilon);
  EXPECT_EQ(r.numerics.surface_tension.surface_offset, s.numerics.surface_tension.surface_offset);
  EXPECT_EQ(r.numerics.surface_tension.curvature_correction,
            s.numerics.surface_tension.curvature_correction);
  EXPECT_EQ(r.numerics.surface_tension.zero_net_force, s.numerics.surface_tension.zero_net_force);
  EXPECT_EQ(r.vres_conserve_momentum, s.vres_conserve_momentum);
  EXPECT_EQ(r.vres_buffer_fill_min, s.vres_buffer_fill_min);
  EXPECT_EQ(r.numerics.hydrostatic_initial_density, s.numerics.hydrostatic_initial_density);
  EXPECT_EQ(r.fluid_blocks, s.fluid_blocks);
  EXPECT_EQ(r.wall_blocks, s.wall_blocks);
  EXPECT_EQ(r.domain_min, s.domain_min);
  EXPECT_EQ(r.domain_max, s.domain_max);
  EXPECT_EQ(r.max_lost_fraction, s.max_lost_fraction);
  EXPECT_EQ(r.refinements, s.refinements);
  EXPECT_EQ(r.output_interval, s.output_interval);
  EXPECT_EQ(r.write_vtp, s.write_vtp);
  EXPECT_EQ(r.write_csv, s.write_csv);
  EXPECT_EQ(r.lines, s.lines);
  EXPECT_EQ(r.laplace_pressure, s.laplace_pressure);
  EXPECT_TRUE(r == s) << text;
  EXPECT_EQ(case_to_toml(r), text);  // stable: writing the re-read spec gives the same text
  // Spot checks that the every-key case really is off the defaults.
  EXPECT_EQ(s.fluid_blocks[0].fill, FillMode::rings);
  EXPECT_EQ(s.refinements[1].dp_ratio, 2);
  EXPECT_FALSE(s.write_vtp);
  EXPECT_EQ(s.output_precision, OutputPrecision::float32);
  EXPECT_EQ(s.output_compression, OutputCompression::zlib);
  EXPECT_TRUE(s.numerics.surface_tension.curvature_correction);
  EXPECT_TRUE(s.vres_conserve_momentum);
  EXPECT_EQ(s.vres_buffer_fill_min, 0.3);
}

// The vres_ keys of the every-key case (their round trip is in RoundTripEveryKey).
TEST(CaseParser, EveryKeyCaseSetsTheVresKeys) {
  const CaseSpec s = parse_text(kEveryKey);
  EXPECT_EQ(s.vres_buffer_surface, BufferSurface::donor);
  EXPECT_EQ(s.vres_shepard_fill, 0.9);
}

// The damped start of the every-key case, read and written back (only when on).
TEST(CaseParser, EveryKeyCaseSetsTheDampedStart) {
  const CaseSpec s = parse_text(kEveryKey);
  EXPECT_EQ(s.numerics.start_damping_time, 0.03);
  EXPECT_EQ(s.numerics.start_damping_tau, 0.002);
  const CaseSpec r = reparse(case_to_toml(s));
  EXPECT_EQ(r.numerics.start_damping_time, 0.03);
  EXPECT_EQ(r.numerics.start_damping_tau, 0.002);
  EXPECT_EQ(case_to_toml(parse_text(kMinimal)).find("start_damping"), std::string::npos);
}

// buffer_rounding is per box, "none" where not given.
TEST(CaseParser, BufferRoundingPerBox) {
  const CaseSpec s = parse_text(kEveryKey);
  EXPECT_EQ(s.refinements[0].buffer_rounding, BufferRounding::whole_dp);
  EXPECT_EQ(s.refinements[1].buffer_rounding, BufferRounding::none);
}

// zero_net_force is for closed free surfaces: it round-trips on a drop and is refused with walls
// (the every-key case has walls, so it is checked here).
TEST(CaseParser, ZeroNetSurfaceForceOnlyWithoutWalls) {
  const std::string drop =
      std::string(kMinimal) + "[numerics]\nsurface_tension = { zero_net_force = true }\n";
  const CaseSpec s = parse_text(drop);
  EXPECT_TRUE(s.numerics.surface_tension.zero_net_force);
  EXPECT_EQ(reparse(case_to_toml(s)), s);
  expect_contains(
      error_of(drop + "[[wall_block]]\nshape = \"box\"\nmin = [0, 0]\nmax = [1, 1]\n"),
      {"numerics.surface_tension.zero_net_force", "true with walls", "closed free surface"});
}

TEST(CaseParser, RoundTripMinimalAnd3D) {
  for (const std::string& text :
       {std::string(kMinimal), edited("dimension = 2", "dimension = 3",
                                      edited("\"circle\"\ncenter = [0.0, 0.0]",
                                             "\"sphere\"\ncenter = [0.0, 0.1, 1e-7]"))}) {
    const CaseSpec s = parse_text(text);
    EXPECT_EQ(reparse(case_to_toml(s)), s);
  }
}

}  // namespace
}  // namespace vrsph
