// When the surface-tension passes 2 and 3 run (numerics.surface_tension.refresh; not part of Cen
// et al. 2024). The normals, the curvature and the capillary acceleration change on the capillary
// time scale, sqrt(rho h^3 / sigma), while the step is set by sound (dt = CFL h / c0): on the
// shipped drops the capillary limit of solver/timestep.hpp is 4-10 acoustic steps. With
// "capillary" the acceleration a_st is computed once per refresh_interval x that limit;
// shifting's grad C and div r are still summed at the corrector's stage of every step (by the
// force pass where no refresh falls there: surface_sums_for_shifting), so they stay current.
// Between refreshes a_st is extrapolated linearly from the last two refreshes (SurfaceFields::
// extrapolate), not held: a held force lags a capillary oscillation of frequency w by about half
// the interval, and a restoring force that lags does work on the mode at a rate of order
// w^2 x lag, which for the shortest capillary waves rivals their viscous damping (nu k^2). Held,
// interval 0.25 raised droplet_3d's parasitic speed by 30%; extrapolated, it stays within the
// draws of the every-step run up to interval 0.5 (docs/validation.md, "The held acceleration
// extrapolated").
#pragma once

#include <limits>

namespace vrsph {

class RefreshClock {
 public:
  RefreshClock() = default;
  // interval <= 0: every evaluation is a refresh ("every_step").
  explicit RefreshClock(double interval) : interval_(interval) {}

  bool every_step() const { return interval_ <= 0.0; }
  // Whether an evaluation at time t must refresh: always before the first refresh (and after a
  // resume from a checkpoint without held fields), then once the interval has passed. The small
  // tolerance absorbs the rounding of t as a sum of steps.
  // Held refreshes fall on corrector stages only (there shifting needs pass 1's grad C and div r
  // anyway), the very first one excepted.
  bool due(double t, bool corrector_stage) const {
    if (every_step() || !valid_) return true;
    return corrector_stage && t >= last_ + interval_ * (1.0 - 1e-9);
  }
  void mark(double t) {
    last_ = t;
    valid_ = true;
  }
  // The last refresh time, for checkpoints (NaN before the first).
  double last() const { return valid_ ? last_ : std::numeric_limits<double>::quiet_NaN(); }
  void restore(double last) {
    valid_ = last == last;  // NaN: no held fields
    last_ = valid_ ? last : 0.0;
  }

 private:
  double interval_ = 0.0;
  double last_ = 0.0;
  bool valid_ = false;
};

}  // namespace vrsph
