// Numerical parameters of one resolution level, resolved from the case (PHYSICS.md sections 1-2).
// Everything a pass needs is here, precomputed once, so hot loops read plain numbers.
#pragma once

#include "vrsph/core/kernel.hpp"
#include "vrsph/core/vec.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/density_diffusion.hpp"
#include "vrsph/physics/viscosity.hpp"

namespace vrsph {

template <int D>
struct SolverParams {
  double dp = 0.0;
  double h = 0.0;
  double eta2 = 0.0;  // (0.1 h)^2, regularises 1/r^2 terms
  WendlandC2<D> kernel;
  TaitEos eos;
  double mass = 0.0;  // particle mass rho0 dp^D

  ViscosityModel viscosity = ViscosityModel::laminar;
  double nu = 0.0;                 // kinematic viscosity (laminar)
  double alpha_c0_h = 0.0;         // alpha c0 h (artificial)
  DiffusionModel diffusion = DiffusionModel::molteni;
  double two_delta_h_c0 = 0.0;     // 2 delta h c0
  double rho0_g_over_b = 0.0;      // rho0 |g| / B (Fourtakas)
  double inv_gamma = 1.0 / 7.0;

  Vec<D> gravity{};
  Vec<D> up{};  // unit vector against gravity (zero without gravity)

  double cfl = 0.2;
  double sigma = 0.0;     // surface tension coefficient
  double lambda_threshold = 0.7;  // surface-tension normal: difference form above this lambda
  double normal_epsilon = 0.1;    // surface-tension normal: |grad lambda| > eps lambda / h
  bool surface_offset = false;    // curvature_at_surface() in the CSF force
  bool curvature_correction = false;  // corrected_curvature() in step 3
  ShiftingParams shifting;
  double dt_min = 0.0;    // 0.05 h / c0 (DualSPHysics CoefDtMin): below this the run is unstable
};

}  // namespace vrsph
