// Geometry of variable resolution (docs/physics.md section 10; Ricci, Vacondio & Tafuni 2024, CMAME
// 418:116500, as in DualSPHysics' VRes): which part of space each level owns and where its
// buffer particles live.
//
// Level 0 covers the domain. A refinement box R makes a child level with dp_child =
// dp_parent / dp_ratio. Around the common interface (the faces of R) each level has a buffer
// shell on its own side of the other level's fluid:
//   child:  fluid inside R; buffer in the shell R < x < R grown by w_c = buffer_width h_child;
//   parent: fluid outside R; buffer in the shell inside R, between R and R shrunk by
//           w_p = buffer_width h_parent; nothing deeper inside R.
// Buffer particles are moved with their velocity but take rho and v from the other level's
// fluid (vres/interpolation.hpp): the "donor" level.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "vrsph/core/vec.hpp"

namespace vrsph {

template <int D>
struct Box {
  Vec<D> lo{}, hi{};

  // Half-open, lo <= x < hi, so a lattice that fits the box gives each level the same volume.
  bool contains(const Vec<D>& x) const {
    for (int k = 0; k < D; ++k)
      if (x[k] < lo[k] || x[k] >= hi[k]) return false;
    return true;
  }
  Box grown(double w) const {  // w < 0 shrinks
    Box b = *this;
    for (int k = 0; k < D; ++k) {
      b.lo[k] -= w;
      b.hi[k] += w;
    }
    return b;
  }
  bool contains_box(const Box& o) const {
    for (int k = 0; k < D; ++k)
      if (o.lo[k] < lo[k] || o.hi[k] > hi[k]) return false;
    return true;
  }
  bool overlaps(const Box& o) const {
    for (int k = 0; k < D; ++k)
      if (o.hi[k] < lo[k] || o.lo[k] > hi[k]) return false;
    return true;
  }
  // Distance from x (outside) to the box, 0 inside.
  double distance_outside(const Vec<D>& x) const {
    double d2 = 0.0;
    for (int k = 0; k < D; ++k) {
      const double e = std::max({lo[k] - x[k], x[k] - hi[k], 0.0});
      d2 += e * e;
    }
    return std::sqrt(d2);
  }
  // Distance from x (inside) to the box's boundary, 0 outside.
  double distance_inside(const Vec<D>& x) const {
    double d = 1e300;
    for (int k = 0; k < D; ++k) d = std::min({d, x[k] - lo[k], hi[k] - x[k]});
    return std::max(d, 0.0);
  }
  // Unit outward normal of the face nearest to x (inside or outside the box).
  Vec<D> nearest_face_normal(const Vec<D>& x) const {
    int best_k = 0;
    double best = 1e300, sign = 1.0;
    for (int k = 0; k < D; ++k) {
      const double dl = std::abs(x[k] - lo[k]), dh = std::abs(x[k] - hi[k]);
      if (dl < best) {
        best = dl;
        best_k = k;
        sign = -1.0;
      }
      if (dh < best) {
        best = dh;
        best_k = k;
        sign = 1.0;
      }
    }
    Vec<D> n{};
    n[best_k] = sign;
    return n;
  }
};

enum class Zone : std::uint8_t { fluid = 0, buffer = 1, outside = 2 };

template <int D>
struct ZoneInfo {
  Zone zone = Zone::fluid;
  int donor = -1;        // buffer: level whose fluid supplies rho and v
  Vec<D> face_normal{};  // buffer: unit normal of the nearest interface face (shifting keeps
                         // only the tangential part)
  double depth = 0.0;    // buffer: distance from the level's fluid region into the shell; the
                       // kernel support (2h) lies inside fluid and shell while depth <= width - 2h
  double width = 0.0;  // buffer: the shell's thickness
};

// Weight of a buffer particle's volume in every sum of its level (numerics.vres_buffer_ramp, not
// part of Ricci et al. 2024): with s = (width - depth) / ramp, its distance inside the shell's
// outer edge in units of the ramp width,
//   omega = 3 s^2 - 2 s^3 for 0 <= s <= 1, and 1 deeper in,
// so that a particle deleted on crossing the outer edge has already faded out (omega = 0 there)
// and one created just inside it fades in as it is carried inward, with no step in any sum.
// omega and d omega / ds are continuous (C1); beyond the edge (zone outside, before the step's
// deletions) it is 0. ramp <= 0: 1 everywhere.
template <int D>
double buffer_volume_weight(const ZoneInfo<D>& z, double ramp) {
  if (ramp <= 0.0 || z.zone == Zone::fluid) return 1.0;
  const double s = std::clamp((z.width - z.depth) / ramp, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

// One point on the outer face of a buffer (the face away from its level's fluid) where the mass
// carried across by the other level's flow accumulates until a particle can be created.
template <int D>
struct MassPoint {
  Vec<D> x{};
  Vec<D> n{};         // unit normal out of the buffer: inflow into the buffer has u . n < 0
  double area = 0.0;  // face area (2D: length) the point stands for, about dp^(D-1)
  int donor = -1;     // level whose fluid flows across the face
  double mass = 0.0;  // accumulated mass, kg
};

// What one level owns. A child level has an own box (its refinement box); any level may have
// child boxes, inside which it keeps only a buffer shell.
template <int D>
struct LevelRegion {
  struct Child {
    int level = 0;
    Box<D> box;          // the child's refinement box
    double width = 0.0;  // this level's buffer inside it: buffer_width x h (this level)
  };
  int parent = -1;
  bool has_box = false;
  Box<D> box;          // own refinement box (has_box)
  double width = 0.0;  // own outer buffer shell: buffer_width x h (this level)
  std::vector<Child> children;

  ZoneInfo<D> classify(const Vec<D>& x) const {
    ZoneInfo<D> z;
    if (has_box && !box.contains(x)) {
      z.zone = box.grown(width).contains(x) ? Zone::buffer : Zone::outside;
      z.donor = parent;
      z.face_normal = box.nearest_face_normal(x);
      z.depth = box.distance_outside(x);
      z.width = width;
      return z;
    }
    for (const Child& c : children) {
      if (!c.box.contains(x)) continue;
      z.zone = c.box.grown(-c.width).contains(x) ? Zone::outside : Zone::buffer;
      z.donor = c.level;
      z.face_normal = c.box.nearest_face_normal(x);
      z.depth = c.box.distance_inside(x);
      z.width = c.width;
      return z;
    }
    return z;
  }

  // True where this level keeps wall particles: within `margin` (2h) of its fluid or buffer.
  bool covers(const Vec<D>& x, double margin) const {
    if (has_box && !box.grown(width + margin).contains(x)) return false;
    for (const Child& c : children)
      if (c.box.grown(-(c.width + margin)).contains(x)) return false;
    return true;
  }
};

// Points spaced about dp on each face of box b: x at the centres of a face's tiles, n = +-the
// face's outward normal (outward = true: pointing out of b).
template <int D>
std::vector<MassPoint<D>> face_points(const Box<D>& b, double dp, bool outward, int donor) {
  std::vector<MassPoint<D>> out;
  for (int a = 0; a < D; ++a) {
    for (int side = 0; side < 2; ++side) {
      std::array<long, 2> count{1, 1};
      std::array<int, 2> axis{0, 0};
      double area = 1.0;
      int m = 0;
      for (int k = 0; k < D; ++k) {
        if (k == a) continue;
        axis[m] = k;
        count[m] = std::max(1L, std::lround((b.hi[k] - b.lo[k]) / dp));
        area *= (b.hi[k] - b.lo[k]) / count[m];
        ++m;
      }
      for (long i = 0; i < count[0]; ++i) {
        for (long j = 0; j < (D == 3 ? count[1] : 1); ++j) {
          MassPoint<D> p;
          p.x[a] = side == 0 ? b.lo[a] : b.hi[a];
          p.n[a] = (side == 0 ? -1.0 : 1.0) * (outward ? 1.0 : -1.0);
          const std::array<long, 2> idx{i, j};
          for (int q = 0; q < D - 1; ++q) {
            const int k = axis[q];
            p.x[k] = b.lo[k] + (idx[q] + 0.5) * (b.hi[k] - b.lo[k]) / count[q];
          }
          p.area = area;
          p.donor = donor;
          out.push_back(p);
        }
      }
    }
  }
  return out;
}

// The mass points of one level: on the outer face of its own shell (fluid of the parent flows
// in there) and on the inner face of the shell inside each child box (fluid of the child).
template <int D>
std::vector<MassPoint<D>> level_mass_points(const LevelRegion<D>& r, double dp) {
  std::vector<MassPoint<D>> out;
  if (r.has_box) out = face_points<D>(r.box.grown(r.width), dp, true, r.parent);
  for (const auto& c : r.children) {
    auto in = face_points<D>(c.box.grown(-c.width), dp, false, c.level);
    out.insert(out.end(), in.begin(), in.end());
  }
  return out;
}

}  // namespace vrsph
