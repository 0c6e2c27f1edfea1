// A buffer particle's normal where the two levels' surfaces meet at an angle
// (numerics.vres_buffer_surface = "edge_kink"; not part of Ricci et al. 2024).
//
// In the inner part of its shell a buffer particle keeps the normal of its own level's sums
// ("edge"): those continue the level's own surface up to the face and beyond. Where the two
// levels' surfaces meet at a kink (a notch where a drop's surface crosses the face), each level's
// buffer then continues its own slope, neither level's curvature sees the kink, and a VR drop was
// seen held in an elongated shape (docs/validation.md, "The shipped VR drop's second draw"). The
// other level's normal at the particle (n_d, a Shepard average of its fluid's normals) carries
// the other surface's direction; taken everywhere ("donor_normals") it removes the pinning but
// makes drops at rest 3-6x noisier, since averaged normals beside the level's own enter the
// curvature's differences of neighbouring normals. So the donor's normal is taken only where it
// disagrees with the own normal n_o by more than the noise of a surface that has no kink:
//   s = clamp((|n_d - n_o| - a) / (b - a), 0, 1),   n = (n_o + s (n_d - n_o)) / |...|,
// with a = 0.1 and b = 0.3, chosen by measurement (docs/validation.md, "A buffer normal that sees
// the kink"). Where either normal is zero (no surface by that level's lambda) the own one stays.
#pragma once

#include <algorithm>

#include "vrsph/core/vec.hpp"

namespace vrsph {

inline constexpr double kKinkFrom = 0.1;  // |n_d - n_o| below which the own normal stays
inline constexpr double kKinkFull = 0.3;  // |n_d - n_o| from which the donor's is taken whole

// The normal of a buffer particle of own normal n_o where the other level's normal is n_d.
template <int D>
Vec<D> kink_normal(const Vec<D>& n_own, const Vec<D>& n_donor) {
  if (norm2(n_own) == 0.0 || norm2(n_donor) == 0.0) return n_own;
  const double s = std::clamp((norm(n_donor - n_own) - kKinkFrom) / (kKinkFull - kKinkFrom), 0.0,
                              1.0);
  if (s <= 0.0) return n_own;
  const Vec<D> b = n_own + (n_donor - n_own) * s;
  const double m = norm(b);
  return m > 0.0 ? b * (1.0 / m) : n_own;
}

}  // namespace vrsph
