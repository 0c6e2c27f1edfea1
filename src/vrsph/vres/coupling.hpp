// Coupling of resolution levels after each step (docs/physics.md section 10; Ricci, Vacondio &
// Tafuni 2024, as DualSPHysics' VRes does it):
//  1. mass points on the outer face of each buffer accumulate the mass the other level's flow
//     carries into the buffer, dm = -rho (u . n) dA dt times the donor's smoothed fill (about 1
//     inside the fluid, 1/2 on its free surface, 0 outside); a stored mass above one particle
//     mass creates a buffer particle `entry` dp inside the face (0.5; just inside it with the
//     volume ramp, numerics.vres_buffer_ramp);
//  2. kinds follow positions: fluid entering its level's buffer becomes buffer, buffer entering
//     the fluid region becomes fluid, anything leaving the level's region is deleted;
//  3. every buffer particle takes rho and v from the other level's fluid by first-order
//     corrected interpolation (vres/interpolation.hpp), and is deleted where that level has
//     no fluid (Shepard sum < 0.05) or where it lies outside that level's free surface (donor
//     fill below numerics.vres_buffer_fill_min; 0, the default, turns that test off).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "vrsph/solver/level.hpp"
#include "vrsph/vres/interpolation.hpp"
#include "vrsph/vres/region.hpp"

namespace vrsph {

// What variable resolution keeps per level beside the level itself: the part of space it owns
// (fluid region, buffer shell, children) and the mass points on the outer faces of its buffers.
template <int D>
struct LevelLink {
  LevelRegion<D> region;                  // single-resolution runs: level 0 owns everything
  std::vector<MassPoint<D>> mass_points;  // where particles of this level are created
  std::vector<std::vector<std::uint32_t>> point_neighbours;  // on their face (vres/flux_edge.hpp)
};

// How buffer values and mass fluxes are read from the donor level (numerics.vres_buffer_fill_min,
// numerics.vres_shepard_fill; both 0, off, by default).
struct DonorRule {
  double fill_min = 0.0;      // buffer particles below this donor fill are deleted
  double shepard_fill = 0.0;  // below this donor fill, the Shepard average (interpolation.hpp)
  double flux_edge = 0.0;     // below this donor fill, mass points pass flux inward (flux_edge.hpp)
};

// The donor states of every level but l (vres/interpolation.hpp), each at its fraction a[d] of
// its last step (1: its current state), formed once for all the points of level l that read them
// before the donors change: with local time stepping, the mass points and the buffer values of
// one level step. Their arrays live in `store` (one per level, kept by the caller from one step
// to the next). With rule.shepard_fill above 1 they also hold the columns of the Shepard sums.
template <int D>
class DonorStates {
 public:
  DonorStates(const std::vector<Level<D>>& levels, std::size_t l, const std::vector<double>& a,
              const DonorRule& rule, std::vector<DonorStorage<D>>& store);
  const DonorState<D>& operator[](int d) const { return *states_[static_cast<std::size_t>(d)]; }

 private:
  std::vector<std::unique_ptr<DonorState<D>>> states_;
};

struct CouplingTally {
  std::uint64_t created = 0;
  std::uint64_t deleted = 0;
  std::uint64_t kind_changes = 0;  // fluid <-> buffer (update_kinds)
  double created_mass = 0.0;
  double deleted_mass = 0.0;
};

// Step 1 for all levels (dt = 0: no accumulation). New particles are appended (unsorted) with
// ids from next_id.
template <int D>
void accumulate_and_create(std::vector<Level<D>>& levels, std::vector<LevelLink<D>>& links,
                           double dt, double entry, const DonorRule& rule, std::uint64_t& next_id,
                           CouplingTally& tally, std::vector<DonorStorage<D>>& store);

// Step 1 for level l alone, each donor level read as `donors` holds it (DonorStates: at a
// fraction of its last step). Local time stepping calls it at the end of each of level l's own
// steps, with dt that step.
template <int D>
void accumulate_and_create_level(std::vector<Level<D>>& levels, LevelLink<D>& link, std::size_t l,
                                 double dt, const DonorStates<D>& donors, double entry,
                                 const DonorRule& rule, std::uint64_t& next_id,
                                 CouplingTally& tally);

// Step 2 for one level (particles are compacted; the level must be re-sorted afterwards).
// Returns the change of the level's fluid momentum, sum m v of the particles that turned fluid
// minus that of the fluid particles that turned buffer or were deleted (in index order).
template <int D>
Vec<D> update_kinds(Level<D>& L, const LevelLink<D>& link, CouplingTally& tally);

// Step 3 for all levels (needs sorted levels). Returns the number of deleted buffer particles
// (the levels must then be re-sorted).
template <int D>
std::size_t interpolate_buffers(std::vector<Level<D>>& levels,
                                const std::vector<LevelLink<D>>& links, CouplingTally& tally,
                                const DonorRule& rule, std::vector<DonorStorage<D>>& store);

// Step 3 for level l alone, donors as in accumulate_and_create_level. Returns the number deleted.
template <int D>
std::size_t interpolate_buffers_level(std::vector<Level<D>>& levels, const LevelLink<D>& link,
                                      std::size_t l, CouplingTally& tally, const DonorRule& rule,
                                      const DonorStates<D>& donors);

}  // namespace vrsph
