// Per-level parameters (solver/level_setup.hpp): each [numerics] model table reaches the passes
// as its physics/ struct, copied whole, next to the numbers derived from it for the level.
#include <gtest/gtest.h>

#include "case_util.hpp"
#include "vrsph/sim/level_setup.hpp"

namespace vrsph {
namespace {

TEST(LevelParams, ModelStructsCopiedWholeWithDerivedNumbers) {
  const CaseSpec spec = test::load_case(
      "droplet_2d.toml",
      {"numerics.viscosity.model=artificial", "numerics.viscosity.alpha=0.3",
       "numerics.density_diffusion.model=fourtakas", "numerics.density_diffusion.delta=0.2",
       "numerics.shifting.model=skillen", "numerics.shifting.surface_threshold=1.2",
       "numerics.surface_tension.surface_offset=true",
       "numerics.surface_tension.normal_epsilon=0.05", "fluid.gravity=[0, -9.81]"});
  const NumericsSpec& n = spec.numerics;
  const double dp = 2.0e-4, c0 = 50.0;
  const SolverParams<2> prm = level_params<2>(spec, dp, c0);
  const double h = spec.h_over_dp * dp;
  ASSERT_DOUBLE_EQ(prm.h, h);

  EXPECT_EQ(static_cast<const ViscosityParams&>(prm.viscosity), n.viscosity);
  EXPECT_EQ(prm.viscosity.nu, 0.0);  // artificial: no laminar term
  EXPECT_DOUBLE_EQ(prm.viscosity.alpha_c0_h, 0.3 * c0 * h);

  EXPECT_EQ(static_cast<const DiffusionParams&>(prm.density_diffusion), n.density_diffusion);
  EXPECT_DOUBLE_EQ(prm.density_diffusion.two_delta_h_c0, 2.0 * 0.2 * h * c0);
  EXPECT_DOUBLE_EQ(prm.density_diffusion.rho0_g_over_b, spec.fluid.density * 9.81 / prm.eos.b);
  // k_1 = rho0 (1 / gamma) (rho0 g / B): the EOS's gamma reaches the folded Fourtakas series.
  EXPECT_DOUBLE_EQ(prm.density_diffusion.hydrostatic[0],
                   spec.fluid.density / spec.eos.gamma * prm.density_diffusion.rho0_g_over_b);

  EXPECT_EQ(static_cast<const ShiftingParams&>(prm.shifting), n.shifting);
  EXPECT_EQ(prm.shifting.model, ShiftingModel::skillen);
  EXPECT_EQ(prm.shifting.surface_threshold, 1.2);
  EXPECT_EQ(prm.shifting.h, h);
  EXPECT_EQ(prm.shifting.dp, dp);

  EXPECT_EQ(prm.surface_tension, n.surface_tension);
  EXPECT_TRUE(prm.surface_tension.surface_offset);
  EXPECT_EQ(prm.sigma, spec.fluid.surface_tension);

  // Laminar: the fluid's kinematic viscosity.
  CaseSpec lam = spec;
  lam.numerics.viscosity.model = ViscosityModel::laminar;
  EXPECT_EQ(level_params<2>(lam, dp, c0).viscosity.nu, spec.fluid.kinematic_viscosity);
}

}  // namespace
}  // namespace vrsph
