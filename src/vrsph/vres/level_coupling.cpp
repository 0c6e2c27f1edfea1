#include "vrsph/vres/level_coupling.hpp"

#include <algorithm>
#include <limits>
#include <type_traits>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/vres/buffer_spacing.hpp"
#include "vrsph/vres/interpolation.hpp"
#include "vrsph/vres/kink_normal.hpp"
#include "vrsph/vres/momentum.hpp"

namespace vrsph {
namespace {

// Whether a level's particles changed since its last sort: buffers moved apart, particles
// created or deleted. Kind changes alone keep the order (buffer and fluid particles share the
// grid's fluid group), and the stable sort of particles that did not move is the identity, so
// the sort after the kind updates is skipped then (about one level step in several creates or
// deletes anything on the shipped VR drop).
bool changed_since_sort(std::size_t moved, const CouplingTally& tally) {
  return moved > 0 || tally.created > 0 || tally.deleted > 0;
}

// Whether the fluid set changed in the coupling: kinds, creations, deletions (a deletion of buffer
// particles moves the fluid ones to other places of the sums). Where none did, the fluid momentum
// after equals the one before bit for bit, and conserve_momentum has nothing to remove.
bool fluid_changed(const CouplingTally& tally) {
  return tally.kind_changes > 0 || tally.created > 0 || tally.deleted > 0;
}

// Reach, in h of the level, of a buffer particle's own lambda and normal (see
// exchange_buffer_field); infinite: every buffer particle takes the donor's value.
constexpr double kBufferLambdaReach = 1.0;
constexpr double kBufferNormalReach = 2.0;
constexpr double kEverywhere = std::numeric_limits<double>::infinity();

}  // namespace

// Surface-tension quantities of buffer particles near the outer edge of their shell. A buffer
// particle's own lambda sums over neighbours within 2h, and its normal over their lambda: where
// that reach goes past the shell (depth + reach > shell width), its own value sees a free surface
// that is not there and bends the normals and the curvature of the fluid next to the interface.
// Those particles take the value from the other level's fluid (Shepard average), where the
// support is full: the remedy the poster proposes for the lambda mismatch across the interface.
// Buffer particles closer to the fluid keep their own values, which match their own level
// (lambda rises from 1/2 to 1 over about 2h of each level; an averaged lambda from the other
// level has the other level's profile, and averaged normals are not consistent enough with the
// level's own for the curvature, which differences neighbouring normals).
// The reaches (1h for lambda, 2h for normals) were chosen by measurement on the 2D VR droplet
// (docs/validation.md, "Figures formerly in code comments"), not derived. An averaged normal keeps
// its direction where most of the donor weight has a normal (|average| >= 1/2), and is zero
// otherwise.
// numerics.vres_buffer_surface: "edge" is the above; "donor" gives every buffer particle the
// other level's value (reach without limit); "own" none (the published coupling);
// "donor_normals" lambda as "edge" and every buffer particle the other level's normal. With own
// normals in the inner part of the shell, each level's buffer continues the level's own surface
// up to the face, so where the two levels' surfaces meet at an angle (a notch at a crossing) the
// curvature of neither level sees the kink, and a VR drop could stay pinned in a deformed shape
// (docs/validation.md, "The shipped VR drop's second draw"). "edge_kink": as "edge", and in the
// inner part of the shell the normal moves to the other level's where the two disagree by more
// than a surface without a kink does (kink: vres/kink_normal.hpp).
template <int D>
template <class T>
void LevelCoupling<D>::exchange_buffer_field(std::vector<Level<D>>& levels, std::size_t l,
                                             std::vector<T> SurfaceFields<D>::*field,
                                             double reach_h, bool kink) const {
  Level<D>& L = levels[l];
  const LevelRegion<D>& region = links_[l].region;
  std::vector<T>& own = L.sf.*field;
  // The donors of the buffers (the parent and the children) as columns for the sums in lanes.
  field_cols_.resize(levels.size());
  for (std::size_t d = 0; d < levels.size(); ++d) {
    const Level<D>& dl = levels[d];
    const bool donor = static_cast<int>(d) == region.parent ||
                       std::any_of(region.children.begin(), region.children.end(),
                                   [d](const auto& c) { return c.level == static_cast<int>(d); });
    if (donor && (dl.sf.*field).size() == dl.ps.size())
      fill_field_columns(dl.ps, dl.sf.*field, field_cols_[d]);
    else
      field_cols_[d].vol_fluid.clear();  // not a donor of l, or no such field yet
  }
  exec::for_each_dynamic(static_cast<std::int64_t>(L.ps.size()), 64, [&](std::int64_t ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (L.ps.kind[i] != Kind::buffer) return;
    const ZoneInfo<D> z = region.classify(L.ps.pos[i]);
    if (z.donor < 0) return;  // moved into the fluid region during the step: kind changes later
    const bool inner = z.depth + reach_h * L.prm.h <= z.width;  // own support in fluid + shell
    if (inner && !kink) return;
    if constexpr (std::is_same_v<T, Vec<D>>) {
      if (inner && norm2(own[i]) == 0.0) return;  // kink_normal keeps a zero own normal
    }
    const Level<D>& dl = levels[static_cast<std::size_t>(z.donor)];
    const LaneColumns<D>& cols = field_cols_[static_cast<std::size_t>(z.donor)];
    if (cols.vol_fluid.empty()) return;  // the donor holds no such field yet
    T v = shepard_field<D, T>(L.ps.pos[i], dl.grid, dl.prm.kernel, cols, T{});
    if constexpr (std::is_same_v<T, Vec<D>>) {
      const double m = norm(v);
      v = m >= 0.5 ? v * (1.0 / m) : Vec<D>{};
      if (inner) v = kink_normal(own[i], v, std::max(L.prm.dp, dl.prm.dp) / opt_.kink_radius);
    }
    own[i] = v;
  });
}

// omega of every particle of level l for its next pack (numerics.vres_buffer_ramp): buffer
// particles by their distance inside the shell's outer edge (region.hpp), everything else 1.
// Off (or a single level): no weights.
template <int D>
void LevelCoupling<D>::volume_weights(std::vector<Level<D>>& levels, std::size_t l) const {
  Level<D>& L = levels[l];
  if (!multi_level() || opt_.buffer_ramp <= 0.0) {
    L.cols.weight.clear();
    return;
  }
  const LevelRegion<D>& region = links_[l].region;
  const double ramp = opt_.buffer_ramp * L.prm.dp;
  L.cols.weight.resize(L.ps.size());
  exec::for_each(static_cast<std::int64_t>(L.ps.size()), [&](std::int64_t i) {
    const bool buffer = L.ps.kind[i] == Kind::buffer;
    L.cols.weight[i] = buffer ? buffer_volume_weight(region.classify(L.ps.pos[i]), ramp) : 1.0;
  });
}

// The levels next to l (its parent and its children) as sources of l's surface passes; none when
// off or with a single level. Kernels (solver/cross_level.hpp): each particle sums with one h
// over all its neighbours (a gather kernel), so that every neighbour set it sees is resolved:
// the level's own h, except where a coarser parent's fluid is in reach. There, within 2 h_p of
// the box (the parent's whole support) the particle takes h_p for every neighbour, own and
// parent alike, and over the next 2 h_p its h falls linearly to the level's own (sf.h_wide).
template <int D>
void LevelCoupling<D>::cross_sources(std::vector<Level<D>>& levels, std::size_t l) const {
  Level<D>& L = levels[l];
  L.sf.cross.clear();
  L.sf.wide.clear();
  L.sf.h_wide.clear();
  const bool on = multi_level() && opt_.surface_across_levels;
  L.cols.surface_without_buffers = on;
  if (!on) return;
  const LevelRegion<D>& region = links_[l].region;
  std::vector<int> others;
  if (region.parent >= 0) others.push_back(region.parent);
  for (const auto& c : region.children) others.push_back(c.level);
  for (const int o : others) {
    const Level<D>& O = levels[static_cast<std::size_t>(o)];
    L.sf.cross.push_back({&O.ps, &O.grid, &O.sf.lambda, &O.sf.normal, false});
  }
  if (region.parent < 0 || !region.has_box) return;
  const double h_p = levels[static_cast<std::size_t>(region.parent)].prm.h, h = L.prm.h;
  if (h_p <= h) return;
  L.sf.wide.push_back({&L.ps, &L.grid, &L.sf.lambda, &L.sf.normal, true});
  L.sf.wide.insert(L.sf.wide.end(), L.sf.cross.begin(), L.sf.cross.end());
  L.sf.h_wide.assign(L.ps.size(), 0.0);
  exec::for_each(static_cast<std::int64_t>(L.ps.size()), [&](std::int64_t i) {
    if (L.ps.kind[i] == Kind::wall) return;
    const Vec<D>& x = L.ps.pos[i];
    const double d = region.box.contains(x) ? region.box.distance_inside(x) : 0.0;
    const double s = (d - 2.0 * h_p) / (2.0 * h_p);  // 0 .. 1 across the blend
    if (s < 1.0) L.sf.h_wide[i] = s <= 0.0 ? h_p : h_p + s * (h - h_p);
  });
}

template <int D>
void LevelCoupling<D>::before_pack(std::vector<Level<D>>& levels, std::size_t l) const {
  volume_weights(levels, l);
  cross_sources(levels, l);
}

template <int D>
void LevelCoupling<D>::after_surface_sums(std::vector<Level<D>>& levels, std::size_t l) const {
  if (exchanges_buffer_fields())
    exchange_buffer_field(
        levels, l, &SurfaceFields<D>::lambda,
        opt_.buffer_surface == BufferSurface::donor ? kEverywhere : kBufferLambdaReach);
}

template <int D>
void LevelCoupling<D>::after_normals(std::vector<Level<D>>& levels, std::size_t l) const {
  if (!exchanges_buffer_fields()) return;
  const BufferSurface mode = opt_.buffer_surface;
  const bool whole_shell = mode == BufferSurface::donor || mode == BufferSurface::donor_normals;
  exchange_buffer_field(levels, l, &SurfaceFields<D>::normal,
                        whole_shell ? kEverywhere : kBufferNormalReach,
                        mode == BufferSurface::edge_kink);
}

template <int D>
void LevelCoupling<D>::after_surface_sums(std::vector<Level<D>>& levels) const {
  for (std::size_t l = 0; l < levels.size(); ++l) after_surface_sums(levels, l);
}

template <int D>
void LevelCoupling<D>::after_normals(std::vector<Level<D>>& levels) const {
  for (std::size_t l = 0; l < levels.size(); ++l) after_normals(levels, l);
}

// The optional corrections of momentum.hpp: the net coupling force F_c (variable resolution) and
// the net capillary force F_st, removed as a uniform acceleration of the fluid.
template <int D>
void LevelCoupling<D>::after_forces(std::vector<Level<D>>& levels, bool capillary) const {
  const bool coupling = wants_pair_acc();
  const bool net_st = opt_.zero_net_surface_force && capillary;
  if (!coupling && !net_st) return;
  Vec<D> f{};
  if (coupling) f += coupling_net_force(levels);
  double mass = 0.0;
  if (net_st)
    f += surface_net_force(levels, mass);
  else
    mass = fluid_mass(levels);
  if (mass > 0.0) set_uniform_fluid_acceleration(levels, f * (-1.0 / mass));
}

template <int D>
void LevelCoupling<D>::before_corrector(std::vector<Level<D>>& levels, std::size_t l) const {
  if (!multi_level()) return;
  Level<D>& L = levels[l];
  if (!L.prm.shifting.on()) {  // the corrector shifts nothing
    L.buffer_shift_normal.clear();
    return;
  }
  const LevelRegion<D>& region = links_[l].region;
  L.buffer_shift_normal.resize(L.ps.size());
  exec::for_each(static_cast<std::int64_t>(L.ps.size()), [&](std::int64_t i) {
    L.buffer_shift_normal[i] =
        L.ps.kind[i] == Kind::buffer ? region.classify(L.ps.pos0[i]).face_normal : Vec<D>{};
  });
}

template <int D>
void LevelCoupling<D>::before_corrector(std::vector<Level<D>>& levels) const {
  for (std::size_t l = 0; l < levels.size(); ++l) before_corrector(levels, l);
}

// Variable resolution after a step (docs/physics.md section 10): mass points, kind changes and
// deletions, then buffer values from the other levels; with conserve_momentum, the fluid
// momentum jump of the kind changes is removed as a uniform velocity (momentum.hpp).
template <int D>
CouplingTally LevelCoupling<D>::after_step(std::vector<Level<D>>& levels, double dt,
                                           std::uint64_t& next_id,
                                           const std::function<void()>& sort) {
  CouplingTally tally;
  if (!multi_level()) return tally;
  double mass = 0.0;
  const Vec<D> p_before = opt_.conserve_momentum ? fluid_momentum(levels, mass) : Vec<D>{};
  std::size_t moved = 0;
  for (Level<D>& L : levels) moved += space_buffers(L, opt_.buffer_spacing);
  accumulate_and_create(levels, links_, dt, entry_depth(), donor_rule(), next_id, tally,
                        donor_store_);
  for (std::size_t l = 0; l < levels.size(); ++l) update_kinds(levels[l], links_[l], tally);
  if (changed_since_sort(moved, tally)) sort();
  if (interpolate_buffers(levels, links_, tally, donor_rule(), donor_store_) > 0) sort();
  if (opt_.conserve_momentum && fluid_changed(tally)) {
    const Vec<D> dp = fluid_momentum(levels, mass) - p_before;
    if (mass > 0.0) add_to_fluid_velocity(levels, dp * (-1.0 / mass));
  }
  return tally;
}

template <int D>
Vec<D> LevelCoupling<D>::net_force(const std::vector<Level<D>>& levels, std::size_t l,
                                   bool capillary) const {
  const Level<D>& L = levels[l];
  const bool st = opt_.zero_net_surface_force && capillary && L.sf.acc_st.size() == L.ps.size();
  const bool coupling = wants_pair_acc();
  if (!st && !coupling) return {};
  // In blocks of particles, each summed in index order, the blocks in parallel and then added in
  // block order: the same bits for any thread count (one serial loop over the level was 2.7% of
  // the VR drop's samples on two threads, the other thread idle).
  constexpr std::size_t kBlock = 512;
  const std::size_t n = L.ps.size(), blocks = (n + kBlock - 1) / kBlock;
  std::vector<Vec<D>> part(blocks);
  exec::for_each(static_cast<std::int64_t>(blocks), [&](std::int64_t b) {
    Vec<D> f{};
    const auto i0 = static_cast<std::size_t>(b) * kBlock;
    for (std::size_t i = i0; i < std::min(n, i0 + kBlock); ++i) {
      if (L.ps.kind[i] != Kind::fluid) continue;
      if (coupling) add_coupling_force(L, i, f);
      if (st) f += L.ps.mass_of(i) * L.sf.acc_st[i];
    }
    part[static_cast<std::size_t>(b)] = f;
  });
  Vec<D> f{};
  for (const Vec<D>& p : part) f += p;
  return f;
}

template <int D>
void LevelCoupling<D>::remove_impulse(std::vector<Level<D>>& levels, const Vec<D>& impulse) const {
  const double mass = fluid_mass(levels);
  if (mass > 0.0) add_to_fluid_velocity(levels, impulse * (-1.0 / mass));
}

template <int D>
CouplingTally LevelCoupling<D>::after_level_step(std::vector<Level<D>>& levels, std::size_t l,
                                                 double dt, const std::vector<double>& donor_a,
                                                 std::uint64_t& next_id,
                                                 const std::function<void()>& sort) {
  CouplingTally tally;
  if (!multi_level()) return tally;
  const std::size_t moved = space_buffers(levels[l], opt_.buffer_spacing);
  // The other levels do not change in this level's coupling: one donor state each serves the
  // mass points and the buffer values.
  const DonorStates<D> donors(levels, l, donor_a, donor_rule(), donor_store_);
  accumulate_and_create_level(levels, links_[l], l, dt, donors, entry_depth(), donor_rule(),
                              next_id, tally);
  // Only kind changes and deletions move fluid momentum here (created particles are buffer, and
  // buffer values touch buffer particles alone): update_kinds gives the jump from the particles
  // concerned, instead of the fluid momentum of every level summed before and after.
  const Vec<D> jump = update_kinds(levels[l], links_[l], tally);
  if (changed_since_sort(moved, tally)) sort();
  if (interpolate_buffers_level(levels, links_[l], l, tally, donor_rule(), donors) > 0) sort();
  if (opt_.conserve_momentum && norm2(jump) > 0.0) remove_impulse(levels, jump);
  return tally;
}

template class LevelCoupling<2>;
template class LevelCoupling<3>;

}  // namespace vrsph
