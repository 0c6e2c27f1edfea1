// The coupling of the resolution levels of one simulation (docs/physics.md section 10), as one
// object the scheduler (sim/simulation.cpp) calls through a few named hooks, in this order per
// force evaluation and step:
//   after_surface_sums -> after_normals -> after_forces      (each force evaluation)
//   before_corrector -> after_step                           (each step)
// It owns what ties levels together: regions, buffer shells and mass points (vres/coupling.hpp),
// the exchange of surface fields into buffer shells, and the optional net-force and momentum
// corrections (vres/momentum.hpp), which also serve a single level (zero_net_force on a drop).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "vrsph/setup/case_spec.hpp"
#include "vrsph/solver/level.hpp"
#include "vrsph/vres/coupling.hpp"

namespace vrsph {

struct CouplingOptions {
  bool conserve_momentum = false;       // numerics.vres_conserve_momentum
  bool zero_net_surface_force = false;  // numerics.surface_tension.zero_net_force
  double buffer_fill_min = 0.0;         // numerics.vres_buffer_fill_min
  double buffer_ramp = 0.0;             // numerics.vres_buffer_ramp, in dp of each level
  bool surface_across_levels = false;   // numerics.vres_surface_across_levels
  BufferSurface buffer_surface = BufferSurface::edge;  // numerics.vres_buffer_surface
  double shepard_fill = 0.0;                           // numerics.vres_shepard_fill
  double buffer_spacing = 0.0;  // numerics.vres_buffer_spacing, in dp of each level
  double flux_edge = 0.0;       // numerics.vres_flux_edge
  double kink_radius = 0.0;     // numerics.vres_kink_radius, resolved (> 0)
};

// The options as the case gives them.
inline CouplingOptions coupling_options(const CaseSpec& spec) {
  return {spec.vres_conserve_momentum,
          spec.numerics.surface_tension.zero_net_force,
          spec.vres_buffer_fill_min,
          spec.vres_buffer_ramp,
          spec.vres_surface_across_levels,
          spec.vres_buffer_surface,
          spec.vres_shepard_fill,
          spec.vres_buffer_spacing,
          spec.vres_flux_edge,
          spec.vres_kink_radius > 0.0 ? spec.vres_kink_radius : 10.0 * spec.dp};
}

template <int D>
class LevelCoupling {
 public:
  LevelCoupling() = default;
  LevelCoupling(std::vector<LevelLink<D>> links, const CouplingOptions& opt)
      : links_(std::move(links)), opt_(opt) {}

  bool multi_level() const { return links_.size() > 1; }
  // Whether buffer particles take lambda and the normal from the other level
  // (exchange_buffer_field).
  bool exchanges_buffer_fields() const {
    return multi_level() && !opt_.surface_across_levels &&
           opt_.buffer_surface != BufferSurface::own;
  }
  // Whether the force pass must keep the fluid's pair acceleration (Level::pair_acc), from which
  // momentum.hpp measures the net force of the buffers.
  bool wants_pair_acc() const { return opt_.conserve_momentum && multi_level(); }
  const LevelLink<D>& link(std::size_t k) const { return links_[k]; }
  LevelLink<D>& link(std::size_t k) { return links_[k]; }

  // After surface pass 1: lambda of buffer particles near the outer edge of their shell from the
  // donor level. After pass 2: the same for the normal.
  void after_surface_sums(std::vector<Level<D>>& levels) const;
  void after_normals(std::vector<Level<D>>& levels) const;
  // The same for level l's buffers alone (local time stepping: a level's passes run on their own;
  // the donors' fields are those of their last passes, held with their particles).
  void after_surface_sums(std::vector<Level<D>>& levels, std::size_t l) const;
  void after_normals(std::vector<Level<D>>& levels, std::size_t l) const;
  // Before each pack of level l: the weights of its particles' volumes (LevelColumns::weight;
  // numerics.vres_buffer_ramp, none when off) and, with surface_across_levels, the neighbouring
  // levels' fluid as sources of its surface passes (solver/cross_level.hpp).
  void before_pack(std::vector<Level<D>>& levels, std::size_t l) const;
  // After the pair forces: removes the net coupling force and/or net capillary force (capillary:
  // surface tension is on) as a uniform acceleration of the fluid.
  void after_forces(std::vector<Level<D>>& levels, bool capillary) const;
  // Before the corrector: the interface normal along which buffer particles are not shifted
  // (levels with shifting only).
  void before_corrector(std::vector<Level<D>>& levels) const;
  void before_corrector(std::vector<Level<D>>& levels, std::size_t l) const;
  // After a step of dt (0: at start): mass points, kind changes, deletions and buffer values;
  // `sort` re-sorts every level (and counts what left the domain). Returns what was created and
  // deleted; new particles take ids from next_id.
  CouplingTally after_step(std::vector<Level<D>>& levels, double dt, std::uint64_t& next_id,
                           const std::function<void()>& sort);

  // Local time stepping (sim/local_stepping.cpp).
  // After a step of level l alone, of length dt: its mass points, kinds, deletions and buffer
  // values, each donor level d read at the fraction donor_a[d] of its last step; `sort` re-sorts
  // level l. With conserve_momentum the momentum jump is removed at once.
  CouplingTally after_level_step(std::vector<Level<D>>& levels, std::size_t l, double dt,
                                 const std::vector<double>& donor_a, std::uint64_t& next_id,
                                 const std::function<void()>& sort);
  // The net force that after_forces would remove, from level l alone: F_c of its buffer on its
  // fluid (conserve_momentum) plus F_st of its fluid (zero_net_force, when capillary).
  Vec<D> net_force(const std::vector<Level<D>>& levels, std::size_t l, bool capillary) const;
  // Removes an impulse (the sum of net_force x dt over the levels' corrector stages since the
  // levels last met) as a uniform velocity of all fluid.
  void remove_impulse(std::vector<Level<D>>& levels, const Vec<D>& impulse) const;
  bool corrects_net_force(bool capillary) const {
    return wants_pair_acc() || (opt_.zero_net_surface_force && capillary);
  }

 private:
  void volume_weights(std::vector<Level<D>>& levels, std::size_t l) const;
  void cross_sources(std::vector<Level<D>>& levels, std::size_t l) const;
  // How buffer values and mass fluxes are read from the donor (coupling.hpp).
  DonorRule donor_rule() const { return {opt_.buffer_fill_min, opt_.shepard_fill, opt_.flux_edge}; }
  // Where a created particle is placed, in dp inside the buffer's outer face: 0.5 (Ricci et al.),
  // or, with the volume ramp, just inside the face, where its weight starts from about 0.
  double entry_depth() const { return opt_.buffer_ramp > 0.0 ? kRampEntryDepth : 0.5; }
  static constexpr double kRampEntryDepth = 0.01;
  template <class T>
  void exchange_buffer_field(std::vector<Level<D>>& levels, std::size_t l,
                             std::vector<T> SurfaceFields<D>::*field, double reach_h,
                             bool kink = false) const;

  std::vector<LevelLink<D>> links_;
  CouplingOptions opt_;
  std::vector<DonorStorage<D>> donor_store_;        // the donor states' arrays, one set per level
  mutable std::vector<LaneColumns<D>> field_cols_;  // exchange_buffer_field's donors, per level
};

}  // namespace vrsph
