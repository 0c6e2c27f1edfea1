// Where the particles of a block will lie and how many there will be, from the case alone, before
// any particle is made: the set-up checks (setup/case_checks.cpp, sim/preflight.hpp) refuse a
// case from these figures instead of filling it first. Sizes are doubles, so absurd values (a
// block of 1e20 dp) give a large count, not an integer overflow.
#pragma once

#include "vrsph/setup/case_spec.hpp"

namespace vrsph {

// The number of lattice nodes a + k dp <= b along one axis, as the fill makes them (0 when b < a).
double nodes_between(double a, double b, double dp);

// A box holding every particle of a block (lo > hi on some axis when the block makes none).
struct Extent {
  Vec3d lo{};
  Vec3d hi{};
};

// Box fluid blocks: their lattice or cell-centre nodes exactly; round blocks: center -+ radius.
Extent fluid_extent(const FluidBlock& b, double dp, int dim);
// Wall blocks: their nodes exactly (a tank's layers lie outside its min..max).
Extent wall_extent(const WallBlock& w, double dp, int dim);

// Particles of a block at spacing dp: exact for boxes and walls, volume / dp^dim for round
// blocks (the lattice or the rings hold that many to within their outer row).
double fluid_count(const FluidBlock& b, double dp, int dim);
double wall_count(const WallBlock& w, double dp, int dim);

// The largest side of the box lo..hi over the first dim axes.
double largest_extent(const Extent& e, int dim);

// The union of the extents of every fluid block (with_walls: and every wall block) at spacing dp.
Extent case_extent(const CaseSpec& spec, double dp, bool with_walls);

// The default domain (no [domain]): the bounding box lo..hi of the particles grown on each side
// by m = max(0.1 x its extent on that axis, 4h, L), L the largest extent of the fluid
// (case_extent without walls), and against gravity (up) by a further half of that extent, where
// splashes go. L is the room a free body needs to deform: a body may turn into a circle (sphere)
// of the same area, or splash, and then reaches about L beyond where it started (a 4 x 3 mm
// rectangle of water relaxing towards a circle overshoots its 3 mm side by about 1 mm on each
// face, and left the earlier margin, max(0.1 x extent, 4h) = 0.52 mm at dp = 1e-4, at 2.7 ms).
// cell_origin gets the domain's min under that earlier margin: the cell grid is laid from there,
// so a run that stays inside the earlier domain sorts, and computes, bit for bit as before.
void grow_default_domain(Vec3d& lo, Vec3d& hi, int dim, double fluid_extent, const Vec3d& up,
                         double h, Vec3d& cell_origin);

// The default domain of a case estimated from its blocks (case_extent with walls, grown as
// above with level 0's h): it holds the domain the run will take from its particles.
Extent default_domain_extent(const CaseSpec& spec);

}  // namespace vrsph
