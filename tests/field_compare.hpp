// Comparing a field computed two ways (double against mixed precision): shared by
// test_forces_mixed.cpp and test_surface_mixed.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace vrsph::test {

// Largest difference relative to the largest value of the field (pair terms cancel in the sum,
// so a particle's own value is no scale for its rounding). Infinite if either holds a NaN or an
// infinity (std::max skips NaN).
inline double max_rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) return INFINITY;
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(a[i]));
  }
  return scale > 0.0 ? diff / scale : diff;
}

}  // namespace vrsph::test
