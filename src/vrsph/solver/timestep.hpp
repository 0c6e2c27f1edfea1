// Variable time step (Monaghan & Kos 1999, as DualSPHysics' DtVariable), plus the viscous and
// capillary limits of docs/physics.md section 8:
//   dt = min( cfl min(dt_f, dt_cv), dt_visc, dt_st )
//   dt_f  = sqrt(h / max|a|)                       (a without gravity)
//   dt_cv = h / (max(c0, 10 v_max) + h max_ij v_ij.r_ij/(r^2 + eta^2))
//   dt_visc = 0.125 h^2 / nu                        (laminar viscosity only)
//   dt_st = 0.25 sqrt(rho0 h^3 / (2 pi sigma))     (Brackbill 1992 / Morris 2000, sigma > 0 only)
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>

namespace vrsph {

enum class DtLimit : int { force = 0, acoustic = 1, viscous = 2, capillary = 3 };
inline constexpr std::array<std::string_view, 4> kDtLimitNames = {"force", "acoustic", "viscous",
                                                                  "capillary"};

struct DtChoice {
  double dt = 0.0;
  DtLimit limit = DtLimit::acoustic;
};

struct DtInputs {
  double h = 0.0;
  double cfl = 0.2;
  double c0 = 0.0;
  double max_acc = 0.0;      // max |a| over fluid, gravity excluded
  double max_speed = 0.0;    // max |v| over fluid
  double max_visc_dt = 0.0;  // max over pairs of v_ij.r_ij/(r^2+eta^2)
  double nu = 0.0;           // 0 when laminar viscosity is off
  double rho0 = 1000.0;
  double sigma = 0.0;
};

// dt_st, the capillary limit (infinite without surface tension).
inline double capillary_dt(double rho0, double h, double sigma) {
  return sigma > 0.0 ? 0.25 * std::sqrt(rho0 * h * h * h / (2.0 * std::numbers::pi * sigma))
                     : std::numeric_limits<double>::infinity();
}

inline DtChoice choose_dt(const DtInputs& in) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double dt_f = in.max_acc > 0.0 ? std::sqrt(in.h / in.max_acc) : inf;
  const double dt_cv =
      in.h / (std::max(in.c0, 10.0 * in.max_speed) + in.h * std::max(0.0, in.max_visc_dt));
  const double dt_visc = in.nu > 0.0 ? 0.125 * in.h * in.h / in.nu : inf;
  const double dt_st = capillary_dt(in.rho0, in.h, in.sigma);
  DtChoice c{in.cfl * dt_f, DtLimit::force};
  if (in.cfl * dt_cv <= c.dt) c = {in.cfl * dt_cv, DtLimit::acoustic};
  if (dt_visc < c.dt) c = {dt_visc, DtLimit::viscous};
  if (dt_st < c.dt) c = {dt_st, DtLimit::capillary};
  return c;
}

}  // namespace vrsph
