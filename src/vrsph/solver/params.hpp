// Numerical parameters of one resolution level, resolved from the case (docs/physics.md sections
// 1-8). Everything a pass needs is here, precomputed once, so hot loops read plain numbers.
#pragma once

#include "vrsph/core/kernel.hpp"
#include "vrsph/core/precision.hpp"
#include "vrsph/core/vec.hpp"
#include "vrsph/physics/density_diffusion.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/surface_tension.hpp"
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

  Vec<D> gravity{};
  Vec<D> up{};  // unit vector against gravity (zero without gravity)

  double cfl = 0.2;
  Precision precision = Precision::double_precision;  // of the force pass
  double sigma = 0.0;  // surface tension coefficient (fluid.surface_tension, N/m)

  // The models of [numerics], each its case struct whole plus its numbers for this level.
  ViscosityLevel viscosity;
  DiffusionLevel density_diffusion;
  ShiftingLevel shifting;
  SurfaceTensionParams surface_tension;

  double dt_min = 0.0;  // 0.05 h / c0 (DualSPHysics CoefDtMin): below this the run is unstable
};

}  // namespace vrsph
