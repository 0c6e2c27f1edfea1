#include "vrsph/vres/coupling.hpp"

#include <memory>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/within.hpp"
#include "vrsph/vres/flux_edge.hpp"
#include "vrsph/vres/interpolation.hpp"

namespace vrsph {
namespace {

constexpr double kMinSpacing = 0.5;  // x dp: no particle is created closer than this to another

// Mass the donor flow carries across a face element in dt: -rho (u . n) dA dt (n out of the
// buffer, so inflow into the buffer is positive).
inline double flux_mass(double rho, double u_n, double area, double dt) {
  return -rho * u_n * area * dt;
}
// The store after an increment dm: once it is negative only positive increments are kept, so
// outflow cannot pile up a debt that blocks later inflow.
inline double accumulate_mass(double stored, double dm) {
  return (stored < 0.0 && dm < 0.0) ? stored : stored + dm;
}

// True when a particle of the level (or one created in this pass) lies closer than `min_dist`
// to x: a new particle there would overlap it. This happens near box corners, where the points
// of two faces create at the same spot, and where the flow stalls. Uses the level's grid of
// the last sort (particles have moved less than a cell since).
template <int D>
bool crowded(const Level<D>& L, const Vec<D>& x, double min_dist, std::size_t first_new) {
  const double d2 = min_dist * min_dist;
  for (std::size_t i = first_new; i < L.ps.size(); ++i)
    if (norm2(L.ps.pos[i] - x) < d2) return true;
  std::int64_t c = 0;
  if (!L.grid.stencil_cell(x, c)) return false;
  bool found = false;
  auto at = [&](std::uint32_t j) { return L.ps.pos[j]; };
  for (Group g : {Group::fluid, Group::wall})
    for_each_within(L.grid, c, g, x, d2, at,
                    [&](std::uint32_t, const Vec<D>&, double) { found = true; });
  return found;
}

}  // namespace

template <int D>
DonorStates<D>::DonorStates(const std::vector<Level<D>>& levels, std::size_t l,
                            const std::vector<double>& a, const DonorRule& rule,
                            std::vector<DonorStorage<D>>& store) {
  if (store.size() < levels.size()) store.resize(levels.size());
  for (std::size_t d = 0; d < levels.size(); ++d) {
    const Level<D>& L = levels[d];
    states_.push_back(d == l ? nullptr
                             : std::make_unique<DonorState<D>>(L.ps, L.grid, L.prm.kernel, a[d],
                                                               store[d], rule.shepard_fill > 1.0));
  }
}

template <int D>
void accumulate_and_create_level(std::vector<Level<D>>& levels, LevelLink<D>& link, std::size_t l,
                                 double dt, const DonorStates<D>& donors, double entry,
                                 const DonorRule& rule, std::uint64_t& next_id,
                                 CouplingTally& tally) {
  if (dt <= 0.0) return;
  Level<D>& L = levels[l];
  std::vector<MassPoint<D>>& points = link.mass_points;
  const double m = L.prm.mass;
  std::vector<InterpolatedState<D>> st(points.size());
  // Dynamic: the points beyond the fluid (most of a face that the flow does not fill) cost
  // nothing, so equal halves of the list were unequal work.
  exec::for_each_dynamic(static_cast<std::int64_t>(points.size()), 16, [&](std::int64_t q) {
    const MassPoint<D>& P = points[static_cast<std::size_t>(q)];
    st[static_cast<std::size_t>(q)] =
        interpolate_values<D>(P.x, donors[P.donor], kVresCondLimit, rule.shepard_fill);
  });
  // The share of the face element that holds fluid: the donor's kernel-smoothed indicator
  // sum_j V_j W, walls counted (next to a wall the fluid sum alone falls to about 1/2 where
  // the element is full). Across a free surface the smoothed indicator integrates to the
  // fluid's true thickness, so the accumulated flux neither drops the top layers of a flow
  // (as a yes/no free-surface test on div r did) nor counts whole elements half in air.
  // Inside the fluid it is about 1. Points inside a wall (the wall sum exceeds the fluid sum)
  // accumulate nothing (fill -1 here). Measured: docs/validation.md, "Figures formerly in code
  // comments". With numerics.vres_flux_edge the increments of the outer points move inward.
  std::vector<double> fill(points.size(), -1.0), dm(points.size(), 0.0);
  for (std::size_t q = 0; q < points.size(); ++q) {
    const InterpolatedState<D>& s = st[q];
    if (s.shepard < kVresShepardMin || s.shepard_walls > s.shepard) continue;
    fill[q] = s.shepard + s.shepard_walls;
    dm[q] = flux_mass(s.rho, dot(s.vel, points[q].n), fill[q] * points[q].area, dt);
  }
  if (rule.flux_edge > 0.0) move_flux_inward(dm, fill, link.point_neighbours, rule.flux_edge);
  const std::size_t first_new = L.ps.size();
  for (std::size_t q = 0; q < points.size(); ++q) {
    MassPoint<D>& P = points[q];
    const InterpolatedState<D>& s = st[q];
    if (fill[q] < 0.0) continue;
    P.mass = accumulate_mass(P.mass, dm[q]);
    if (P.mass < m) continue;
    const Vec<D> x_new = P.x - (entry * L.prm.dp) * P.n;
    if (crowded(L, x_new, kMinSpacing * L.prm.dp, first_new)) continue;  // mass stays stored
    P.mass -= m;
    L.ps.push_back(next_id++, Kind::buffer, x_new, s.vel, s.rho, m);
    ++tally.created;
    tally.created_mass += m;
  }
  L.sf.fit_held(L.ps.size());
}

template <int D>
void accumulate_and_create(std::vector<Level<D>>& levels, std::vector<LevelLink<D>>& links,
                           double dt, double entry, const DonorRule& rule, std::uint64_t& next_id,
                           CouplingTally& tally, std::vector<DonorStorage<D>>& store) {
  const std::vector<double> now(levels.size(), 1.0);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const DonorStates<D> donors(levels, l, now, rule, store);  // after the levels before l created
    accumulate_and_create_level(levels, links[l], l, dt, donors, entry, rule, next_id, tally);
  }
}

template <int D>
Vec<D> update_kinds(Level<D>& L, const LevelLink<D>& link, CouplingTally& tally) {
  ParticleSet<D>& ps = L.ps;
  std::vector<std::uint8_t> keep(ps.size(), 1);  // 0: delete; 2: kept, kind changed
  exec::for_each(static_cast<std::int64_t>(ps.size()), [&](std::int64_t i) {
    if (ps.kind[i] == Kind::wall) return;
    const Kind was = ps.kind[i];
    switch (link.region.classify(ps.pos[i]).zone) {
      case Zone::fluid:
        ps.kind[i] = Kind::fluid;
        break;
      case Zone::buffer:
        ps.kind[i] = Kind::buffer;
        break;
      case Zone::outside:
        keep[i] = 0;
        return;
    }
    if (ps.kind[i] != was) keep[i] = 2;
  });
  std::size_t removed = 0;  // the deleted mass summed in index order, as on one thread
  Vec<D> gained{};          // the fluid's momentum: + what turned fluid, - what left it
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (keep[i] == 2) {
      ++tally.kind_changes;
      gained += (ps.kind[i] == Kind::fluid ? ps.mass_of(i) : -ps.mass_of(i)) * ps.vel[i];
    }
    if (keep[i]) continue;
    ++removed;
    tally.deleted_mass += ps.mass_of(i);
    if (ps.kind[i] == Kind::fluid) gained -= ps.mass_of(i) * ps.vel[i];
  }
  if (removed == 0) return gained;
  tally.deleted += removed;
  ps.compact(keep);
  L.sf.compact_held(keep);
  return gained;
}

namespace {

// Buffer values of level l from its donors (keep[i] = 0: delete particle i).
template <int D>
void buffer_values(std::vector<Level<D>>& levels, const LevelLink<D>& link, std::size_t l,
                   const DonorRule& rule, const DonorStates<D>& donors,
                   std::vector<std::uint8_t>& keep) {
  ParticleSet<D>& ps = levels[l].ps;
  keep.assign(ps.size(), 1);
  exec::for_each_dynamic(static_cast<std::int64_t>(ps.size()), 64, [&](std::int64_t ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (ps.kind[i] != Kind::buffer) return;
    const ZoneInfo<D> z = link.region.classify(ps.pos[i]);
    const InterpolatedState<D> s =
        interpolate_values<D>(ps.pos[i], donors[z.donor], kVresCondLimit, rule.shepard_fill);
    // No donor fluid in reach, or (numerics.vres_buffer_fill_min > 0, not part of Ricci et
    // al.) outside the donor's free surface. Buffer particles follow the donor's velocity and
    // nothing pulls them back to its surface: without the second test, those carried beyond
    // it stay there, and the level's surface can stand proud where it crosses the interface,
    // which lowers the drop's pressure (2D VR droplet; docs/validation.md, "Figures formerly
    // in code comments"). On the relaxing square drop the same test dented the top crossing
    // instead.
    if (s.shepard < kVresShepardMin || donor_fill(s) < rule.fill_min) {
      keep[i] = 0;
      return;
    }
    ps.rho[i] = s.rho;
    ps.vel[i] = s.vel;
  });
}

// Deletes the particles with keep[i] = 0 (the level must be re-sorted afterwards).
template <int D>
std::size_t remove_unkept(Level<D>& L, const std::vector<std::uint8_t>& keep,
                          CouplingTally& tally) {
  std::uint64_t removed = 0;
  for (std::size_t i = 0; i < L.ps.size(); ++i) {
    if (keep[i]) continue;
    tally.deleted_mass += L.ps.mass_of(i);
    ++removed;
  }
  if (removed == 0) return 0;
  tally.deleted += removed;
  const std::size_t r = L.ps.compact(keep);
  L.sf.compact_held(keep);
  return r;
}

}  // namespace

template <int D>
std::size_t interpolate_buffers_level(std::vector<Level<D>>& levels, const LevelLink<D>& link,
                                      std::size_t l, CouplingTally& tally, const DonorRule& rule,
                                      const DonorStates<D>& donors) {
  std::vector<std::uint8_t> keep;
  buffer_values(levels, link, l, rule, donors, keep);
  return remove_unkept(levels[l], keep, tally);
}

// Every level's values first, then the deletions: a level compacted before another had read it
// as a donor would leave that donor's grid pointing at the wrong particles.
template <int D>
std::size_t interpolate_buffers(std::vector<Level<D>>& levels,
                                const std::vector<LevelLink<D>>& links, CouplingTally& tally,
                                const DonorRule& rule, std::vector<DonorStorage<D>>& store) {
  const std::vector<double> now(levels.size(), 1.0);
  std::vector<std::vector<std::uint8_t>> keep(levels.size());
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const DonorStates<D> donors(levels, l, now, rule, store);
    buffer_values(levels, links[l], l, rule, donors, keep[l]);
  }
  std::size_t removed_all = 0;
  for (std::size_t l = 0; l < levels.size(); ++l)
    removed_all += remove_unkept(levels[l], keep[l], tally);
  return removed_all;
}

template class DonorStates<2>;
template class DonorStates<3>;
template void accumulate_and_create<2>(std::vector<Level<2>>&, std::vector<LevelLink<2>>&, double,
                                       double, const DonorRule&, std::uint64_t&, CouplingTally&,
                                       std::vector<DonorStorage<2>>&);
template void accumulate_and_create<3>(std::vector<Level<3>>&, std::vector<LevelLink<3>>&, double,
                                       double, const DonorRule&, std::uint64_t&, CouplingTally&,
                                       std::vector<DonorStorage<3>>&);
template void accumulate_and_create_level<2>(std::vector<Level<2>>&, LevelLink<2>&, std::size_t,
                                             double, const DonorStates<2>&, double,
                                             const DonorRule&, std::uint64_t&, CouplingTally&);
template void accumulate_and_create_level<3>(std::vector<Level<3>>&, LevelLink<3>&, std::size_t,
                                             double, const DonorStates<3>&, double,
                                             const DonorRule&, std::uint64_t&, CouplingTally&);
template std::size_t interpolate_buffers_level<2>(std::vector<Level<2>>&, const LevelLink<2>&,
                                                  std::size_t, CouplingTally&, const DonorRule&,
                                                  const DonorStates<2>&);
template std::size_t interpolate_buffers_level<3>(std::vector<Level<3>>&, const LevelLink<3>&,
                                                  std::size_t, CouplingTally&, const DonorRule&,
                                                  const DonorStates<3>&);
template Vec<2> update_kinds<2>(Level<2>&, const LevelLink<2>&, CouplingTally&);
template Vec<3> update_kinds<3>(Level<3>&, const LevelLink<3>&, CouplingTally&);
template std::size_t interpolate_buffers<2>(std::vector<Level<2>>&,
                                            const std::vector<LevelLink<2>>&, CouplingTally&,
                                            const DonorRule&, std::vector<DonorStorage<2>>&);
template std::size_t interpolate_buffers<3>(std::vector<Level<3>>&,
                                            const std::vector<LevelLink<3>>&, CouplingTally&,
                                            const DonorRule&, std::vector<DonorStorage<3>>&);

}  // namespace vrsph
