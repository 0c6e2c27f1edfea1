// Dynamic boundary particles (Crespo et al. 2007, as DualSPHysics): wall particles carry a
// density from the continuity equation over their fluid neighbours (physics/continuity.hpp) and a
// pressure from the EOS, fixed positions and velocities. Two rules of ours sit on top:
//  - the wall density never falls below rho0 (a wall never pulls fluid towards it);
//  - buffer particles of variable resolution count with zero volume in the wall's continuity sum
//    (their motion is imposed by another level and must not compress the wall).
#pragma once

#include <algorithm>

namespace vrsph {

inline double wall_density(double rho, double rho0) { return std::max(rho, rho0); }

// The volume a neighbour of kind buffer (is_buffer) or fluid presents to a wall's continuity sum.
inline double wall_continuity_volume(double vol_j, bool is_buffer) {
  return is_buffer ? 0.0 : vol_j;
}

}  // namespace vrsph
