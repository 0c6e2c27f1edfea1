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
// with b = 3a. Where either normal is zero (no surface by that level's lambda) the own one stays.
// The noise of a smooth surface's normals scales with dp / R (the normal turns by about
// dp_coarse / R between neighbours), a kink's turn does not, so a = dp_coarse / R_k, dp_coarse the
// larger dp of the two levels and R_k = numerics.vres_kink_radius, the radius of curvature the
// case resolves (default 10 dp of level 0). Measured on the VR drop (docs/validation.md, "A buffer
// normal that sees the kink"): a = 0.1 at R / dp_coarse = 10 and a = 0.05 at 20, both a =
// dp_coarse / R; 0.05 at R / dp_coarse = 10 switched on the noise of the smooth surface (the drop
// at rest got noisier), 0.1 at 20 let the kink grow before it was seen (the drop oscillated).
#pragma once

#include <algorithm>

#include "vrsph/core/vec.hpp"

namespace vrsph {

// The normal of a buffer particle of own normal n_o where the other level's normal is n_d, with
// threshold a (the donor's is taken whole from 3a on).
template <int D>
Vec<D> kink_normal(const Vec<D>& n_own, const Vec<D>& n_donor, double a) {
  if (norm2(n_own) == 0.0 || norm2(n_donor) == 0.0) return n_own;
  const double s = std::clamp((norm(n_donor - n_own) - a) / (2.0 * a), 0.0, 1.0);  // b - a = 2a
  if (s <= 0.0) return n_own;
  const Vec<D> b = n_own + (n_donor - n_own) * s;
  const double m = norm(b);
  return m > 0.0 ? b * (1.0 / m) : n_own;
}

}  // namespace vrsph
