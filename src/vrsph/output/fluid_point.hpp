// The fluid's values at a point, as the probes (probe_<name>.csv) and the interpolated lines
// (line_<name>_interp_NNNN.csv) write them: kernel-interpolated p, rho and v
// (analysis/shepard.hpp), the Shepard sum there and the level they came from; a point outside the
// fluid has level -1 and no values.
#pragma once

#include <fmt/format.h>

#include "vrsph/core/vec.hpp"

namespace vrsph {

template <int D>
struct FluidPoint {
  double shepard = 0.0;  // sum_j V_j W(x - x_j) over the fluid particles used (about 1 inside)
  int level = -1;        // the level the values come from; -1: outside the fluid
  double p = 0.0;        // Pa
  double rho = 0.0;      // kg/m^3
  Vec<D> vel{};          // m/s

  bool inside() const { return level >= 0; }
};

// Appends ",p,rho,vx,vy[,vz]" of a point inside the fluid, or the same number of empty fields
// (",,,,") for a point outside.
template <int D>
void append_fluid_values(fmt::memory_buffer& buf, const FluidPoint<D>& f) {
  auto out = fmt::appender(buf);
  if (!f.inside()) {
    for (int k = 0; k < D + 2; ++k) fmt::format_to(out, ",");
    return;
  }
  fmt::format_to(out, ",{},{}", f.p, f.rho);
  for (int k = 0; k < D; ++k) fmt::format_to(out, ",{}", f.vel[k]);
}

}  // namespace vrsph
