// The set-up checks that need the levels and the speed of sound but no particle: `vrsph check`,
// `run` and `bench` call preflight() before anything is filled or written, so a case that would
// not fit the machine, or would stall or fly apart at its first step, is refused at once with
// one line naming the key (CONTRACT.md "Refused at set-up"):
//  - the particle count and memory need, estimated from the geometry (each block's size and
//    dp, wall layers, each refinement level's dp_ratio), against --max-particles and the memory
//    available;
//  - the first time step: zero, not finite, or too small to advance the clock;
//  - output.interval at or below the first time step (a snapshot at every step or more often);
//  - values that would throw the fluid out of any domain in the first step (gravity, a block's
//    initial pressure) or put its density outside the stability window at once.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vrsph/setup/case_spec.hpp"
#include "vrsph/solver/timestep.hpp"

namespace vrsph {

// What the machine (or the user) allows; an absent limit is not checked.
struct PreflightLimits {
  std::optional<double> max_particles;  // --max-particles
  std::optional<double> memory_bytes;   // memory available (MemAvailable)
};

// One level as the set-up will fill it: the whole case at the level's dp (then cut to its region).
struct LevelEstimate {
  double dp = 0.0;
  double h = 0.0;
  double fluid = 0.0;  // particles of the fluid blocks
  double wall = 0.0;   // particles of the wall blocks
};

struct SetupEstimate {
  std::vector<LevelEstimate> levels;
  double particles = 0.0;  // over all levels
  double bytes = 0.0;      // memory need of a run, bytes
  double c0 = 0.0;         // speed of sound, m/s
  double dt0 = 0.0;        // first time step (the minimum over levels), s
  DtLimit limit = DtLimit::acoustic;
};

// Bytes a run needs per particle in D dimensions, and before any particle (see preflight.cpp).
double bytes_per_particle(int dimension);
inline constexpr double kBaseBytes = 32.0 * 1024 * 1024;

// The speed of sound of a case (PHYSICS.md section 2): eos.sound_speed, or sound_speed_factor x
// max_speed, where max_speed, when not given, is sqrt(g H) with gravity (H: fluid_height) or the
// largest initial speed (vmax). Fills spec.eos.max_speed when derived. Throws std::invalid_argument
// when neither can be had.
double resolve_sound_speed(CaseSpec& spec, double fluid_height, double vmax);

// The extent of the fluid blocks along the vertical axis (H above).
double fluid_height(const CaseSpec& spec);

// Estimates the case and refuses it (CaseError "<source>: <key> = <value>: <reason>") when it
// breaks a limit or one of the checks above.
SetupEstimate preflight(const CaseSpec& spec, const std::string& source,
                        const PreflightLimits& limits);

}  // namespace vrsph
