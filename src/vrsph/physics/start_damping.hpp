// Damped start (numerics.start_damping_time, start_damping_tau; not part of the cited models):
// while t < T_d, every step ends with the fluid velocities multiplied by exp(-dt / tau), a drag
// of rate 1/tau. A case that starts out of equilibrium (a drop whose surface particles must
// settle, a fill that does not match the pressure field) then creeps into it instead of ringing.
// Buffer particles (their velocity is the donor level's) and walls are not damped. Measured on
// the VR drop (docs/validation.md, "A damped start").
#pragma once

#include <cmath>

namespace vrsph {

// The factor of a step of length dt that starts at t: exp(-dt / tau) while t < t_end, else 1.
inline double start_damping_factor(double t, double dt, double t_end, double tau) {
  return t < t_end ? std::exp(-dt / tau) : 1.0;
}

}  // namespace vrsph
