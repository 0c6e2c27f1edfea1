// The plates of a tank wall block (setup/geometry.hpp): `layers` rows of nodes below the min face
// of the vertical axis and outside the faces of the other axes; the top stays open. Corner
// columns belong to the first axis' side walls. One list of plates serves the fill (nodes of
// each plate) and the set-up estimate (their count, sim/preflight.hpp), so both agree.
#pragma once

#include "vrsph/core/vec.hpp"

namespace vrsph {

// Calls plate(lo, hi) for each plate of lattice nodes lo + k dp <= hi (one per layer and face).
template <int D, class Fn>
void for_each_tank_plate(const Vec<D>& min, const Vec<D>& max, int layers, double dp, Fn&& plate) {
  const int vert = vertical_axis<D>();
  const double grow = (layers - 1) * dp;
  for (int l = 0; l < layers; ++l) {
    Vec<D> lo = min, hi = max;  // bottom plate, grown sideways to cover the side walls
    for (int k = 0; k < D; ++k) {
      if (k == vert) continue;
      lo[k] -= grow;
      hi[k] += grow;
    }
    lo[vert] = hi[vert] = min[vert] - l * dp;
    plate(lo, hi);
  }
  for (int axis = 0; axis < D; ++axis) {
    if (axis == vert) continue;
    for (int side = 0; side < 2; ++side) {
      for (int l = 0; l < layers; ++l) {
        Vec<D> lo = min, hi = max;
        lo[vert] = min[vert] + dp;
        for (int k = 0; k < D; ++k) {
          if (k == vert || k == axis) continue;
          // walls of the first horizontal axis span the grown extent; later ones fit inside
          if (k > axis) {
            lo[k] -= grow;
            hi[k] += grow;
          } else {
            lo[k] += dp;
            hi[k] -= dp;
          }
        }
        const double face = side == 0 ? min[axis] - l * dp : max[axis] + l * dp;
        lo[axis] = hi[axis] = face;
        plate(lo, hi);
      }
    }
  }
}

}  // namespace vrsph
