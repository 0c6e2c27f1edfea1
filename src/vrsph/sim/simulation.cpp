#include "vrsph/sim/simulation.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>

#include "vrsph/core/to_vec.hpp"
#include "vrsph/physics/start_damping.hpp"
#include "vrsph/setup/block_extent.hpp"
#include "vrsph/setup/geometry.hpp"
#include "vrsph/sim/level_setup.hpp"
#include "vrsph/sim/preflight.hpp"
#include "vrsph/solver/stepper.hpp"
#include "vrsph/vres/flux_edge.hpp"
#include "vrsph/vres/levels.hpp"
#include "vrsph/vres/momentum.hpp"

namespace vrsph {
namespace {

// "(x, y[, z])" with 6 significant digits, for diagnoses.
template <int D>
std::string position_text(const Vec<D>& x) {
  std::string s = fmt::format("({:.6g}", x[0]);
  for (int k = 1; k < D; ++k) s += fmt::format(", {:.6g}", x[k]);
  return s + ")";
}

double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

// Speed of sound (common to all levels), resolve_sound_speed (sim/preflight.hpp) with H and
// the initial velocities from the level-0 fill. Fills spec.eos.max_speed when it was derived, so
// that the resolved case records it.
template <int D>
Setup resolve_setup(CaseSpec& spec, const InitialSet<D>& init0) {
  Setup setup;
  setup.fluid_height = init0.fluid_height;
  double vmax = 0.0;
  for (const auto& v : init0.particles.vel) vmax = std::max(vmax, norm(v));
  setup.c0 = resolve_sound_speed(spec, setup.fluid_height, vmax);
  setup.max_speed = spec.eos.max_speed.value_or(0.0);
  return setup;
}

}  // namespace

template <int D>
Simulation<D>::Simulation(CaseSpec& spec, CellLayout cells) : spec_(spec) {
  cells = resolve_cell_layout<D>(cells);
  const std::vector<LevelLayout<D>> layout = make_level_layout<D>(spec);
  levels_.resize(layout.size());
  wall_ids_.resize(layout.size());

  InitialSet<D> init0 = level_fill<D>(spec, spec.dp);
  setup_ = resolve_setup<D>(spec, init0);

  std::uint64_t next_id = 0;
  std::vector<LevelLink<D>> links(layout.size());
  for (std::size_t k = 0; k < layout.size(); ++k) {
    Level<D>& L = levels_[k];
    L.prm = level_params<D>(spec, layout[k].dp, setup_.c0);
    L.ps = level_particles<D>(spec, layout[k], L.prm, next_id,
                              k == 0 ? std::move(init0) : level_fill<D>(spec, layout[k].dp),
                              &wall_ids_[k]);
    keep_optional_arrays(k);
    next_id += L.ps.size();
    links[k].region = layout[k].region;
    links[k].mass_points = level_mass_points<D>(links[k].region, L.prm.dp);
    if (spec.vres_flux_edge > 0.0)
      links[k].point_neighbours = mass_point_neighbours(links[k].mass_points, L.prm.dp);
  }
  counters_.next_id = next_id;
  coupling_ = LevelCoupling<D>(std::move(links), coupling_options(spec));

  // One domain for all levels, from the level-0 particles.
  Vec<D> lo, hi, origin;
  const double fluid_extent = largest_extent(case_extent(spec, spec.dp, false), D);
  default_domain<D>(levels_[0].ps, levels_[0].prm.up, levels_[0].prm.h, fluid_extent, lo, hi,
                    origin);
  if (spec.domain_min) lo = origin = to_vec<D>(*spec.domain_min);
  if (spec.domain_max) hi = to_vec<D>(*spec.domain_max);
  for (Level<D>& L : levels_) {
    L.grid = CellGrid<D>(lo, hi, L.prm.kernel.support(), cells.cells_per_support, origin);
    L.grid.set_block_width(cells.cells_per_block);
    L.ps.resize(L.ps.size());
    sort_particles(L);
  }
  initial_fluid_ = count(Kind::fluid);
  stop_time_ = spec.end_time;
  if (coupling_.multi_level()) couple_levels(0.0);  // buffer values from the other levels

  // First step: the acoustic limit of a fluid at rest, with the viscous and capillary limits.
  dt_next_ = 1e300;
  for (const Level<D>& L : levels_)
    dt_next_ = std::min(dt_next_, level_dt_at_start(L, setup_.c0).dt);
  start_local_stepping();
  start_refresh_clocks();
}

template <int D>
void Simulation<D>::keep_optional_arrays(std::size_t k) {
  Level<D>& L = levels_[k];
  L.ps.keep_shift(L.prm.shifting.on());
  L.ps.keep_pos0(levels_.size() > 1);
}

template <int D>
std::size_t Simulation<D>::total_particles() const {
  std::size_t n = 0;
  for (const Level<D>& L : levels_) n += L.ps.size();
  return n;
}

template <int D>
std::size_t Simulation<D>::count(Kind k) const {
  std::size_t n = 0;
  for (const Level<D>& L : levels_) n += L.ps.count(k);
  return n;
}

template <int D>
Vec<D> Simulation<D>::fluid_momentum(double& mass) const {
  return vrsph::fluid_momentum(levels_, mass);
}

template <int D>
void Simulation<D>::sort_particles(Level<D>& L, bool step_copies) {
  const double t0 = now_seconds();
  const auto lost = L.grid.sort(L.ps, step_copies);
  L.sf.carry(L.grid);
  times_.sort += now_seconds() - t0;
  if (lost.empty()) return;
  // Lost wall particles can only be a set-up error (walls never move).
  counters_.lost_fluid += lost.size();
  const double frac = static_cast<double>(counters_.lost_fluid) /
                      static_cast<double>(std::max<std::size_t>(initial_fluid_, 1));
  if (initial_fluid_ > 0 && frac > spec_.max_lost_fraction) {
    const std::string hint =
        spec_.domain_min ? ""
                         : "; this is the default domain, the particles' bounding box plus a "
                           "margin: [domain] min and max set it";
    throw InstabilityError(fmt::format(
        "unstable at t = {:.6g} s, step {}: {} fluid particles ({:.3g}% of {}) have left the "
        "domain (last: id {}) (check: domain, limit domain.max_lost_fraction = {}{})",
        t_, step_, counters_.lost_fluid, 100.0 * frac, initial_fluid_, lost.back(),
        spec_.max_lost_fraction, hint));
  }
}

template <int D>
void Simulation<D>::pack(std::size_t k) {
  coupling_.before_pack(levels_, k);
  pack_level(levels_[k]);
}

template <int D>
void Simulation<D>::sort_all(bool step_copies) {
  for (Level<D>& L : levels_) sort_particles(L, step_copies);
}

template <int D>
void Simulation<D>::resort() {
  for (Level<D>& L : levels_) L.ps.resize(L.ps.size());
  sort_all();
}

template <int D>
std::vector<Vec<D>> Simulation<D>::wall_block_forces() const {
  std::vector<Vec<D>> total(spec_.wall_blocks.size());
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const std::vector<Vec<D>> f = vrsph::wall_block_forces(levels_[l], wall_ids_[l]);
    for (std::size_t b = 0; b < total.size() && b < f.size(); ++b) total[b] += f[b];
  }
  return total;
}

// Next dt: the minimum over levels (one global dt, docs/physics.md section 10); `s` holds the
// maxima of both stages over all levels, and the speeds are taken per level.
template <int D>
DtChoice Simulation<D>::next_dt(const ForceStats& s) const {
  DtChoice best{1e300, DtLimit{}};
  bool first = true;
  for (const Level<D>& L : levels_) {
    const DtChoice c = level_dt(L, s, setup_.c0);
    if (first || c.dt < best.dt) best = c;
    first = false;
  }
  return best;
}

// One force evaluation of all levels at t_eval: the surface passes, then the pair forces of each
// level with the surface-tension acceleration added (at a capillary refresh: passes 2 and 3 after
// the force pass, which summed pass 1), then the coupling's net-force corrections.
template <int D>
ForceStats Simulation<D>::evaluate_forces(double t_eval, bool corrector_stage) {
  for (std::size_t k = 0; k < levels_.size(); ++k) pack(k);  // once, for every pass below
  const bool after = surface_fields(0, levels_.size(), t_eval, corrector_stage);  // 2, 3 after
  double t0 = now_seconds();
  const bool st = levels_[0].prm.sigma > 0.0;
  level_stats_.resize(levels_.size());
  for (std::size_t k = 0; k < levels_.size(); ++k)
    level_stats_[k] = level_forces(levels_[k], st && !after, coupling_.wants_pair_acc());
  times_.forces += now_seconds() - t0;
  if (after) refresh_after_forces(0, levels_.size(), t_eval, level_stats_.data());
  t0 = now_seconds();
  ForceStats s;
  for (const ForceStats& ls : level_stats_) s.merge(ls);
  coupling_.after_forces(levels_, st);
  times_.forces += now_seconds() - t0;
  return s;
}

// The coupling after a step (or at the start, dt = 0): mass points, kind changes, buffer values.
template <int D>
void Simulation<D>::couple_levels(double dt) {
  const double t0 = now_seconds();
  const CouplingTally tally =
      coupling_.after_step(levels_, dt, counters_.next_id, [this] { sort_all(false); });
  counters_.created += tally.created;
  counters_.deleted += tally.deleted;
  counters_.created_mass += tally.created_mass;
  counters_.deleted_mass += tally.deleted_mass;
  times_.coupling += now_seconds() - t0;
}

// The next step's length: dt_next(), shortened to land exactly on the stop time.
template <int D>
StepPlan Simulation<D>::plan_step() const {
  const bool lands = stop_time_ > t_ && t_ + dt_next_ >= stop_time_;
  return {lands ? stop_time_ - t_ : dt_next_, lands};
}

// One symplectic step of every level with one global dt, the coupling's hooks in between.
template <int D>
void Simulation<D>::step() {
  const StepPlan plan = plan_step();
  if (local_) {
    step_local(plan);
    return;
  }
  const double dt = plan.dt;
  ForceStats s = evaluate_forces(t_, false);
  double t0 = now_seconds();
  for (Level<D>& L : levels_) predictor(L, dt);
  times_.update += now_seconds() - t0;
  sort_all();
  s.merge(evaluate_forces(t_ + 0.5 * dt, true));
  coupling_.before_corrector(levels_);
  t0 = now_seconds();
  for (Level<D>& L : levels_) corrector(L, dt);
  const NumericsSpec& n = spec_.numerics;
  const double damping = start_damping_factor(t_, dt, n.start_damping_time, n.start_damping_tau);
  for (Level<D>& L : levels_) damp_fluid_velocities(L, damping);
  times_.update += now_seconds() - t0;
  counters_.particle_steps += total_particles();
  sort_all(false);  // the step copies are dead until the next predictor (one dt for all levels)
  if (coupling_.multi_level()) couple_levels(dt);
  t0 = now_seconds();
  advance_clock(plan, s);
  for (const Level<D>& L : levels_) check_state(L);
  check_dt();
  times_.checks += now_seconds() - t0;
}

// Time, step count and the next dt after the step `plan` with statistics s.
template <int D>
void Simulation<D>::advance_clock(const StepPlan& plan, const ForceStats& s) {
  t_ = plan.lands ? stop_time_ : t_ + plan.dt;
  ++step_;
  dt_last_ = plan.dt;
  counters_.pairs += s.pairs;
  const DtChoice c = next_dt(s);
  dt_next_ = c.dt;
  ++counters_.dt_limit_counts[static_cast<std::size_t>(c.limit)];
}

// Stops the run with a diagnosis: non-finite values, or fluid density outside [0.5, 2] rho0.
template <int D>
void Simulation<D>::check_state(const Level<D>& L) const {
  const ParticleSet<D>& ps = L.ps;
  const double rho0 = L.prm.eos.rho0;
  // The lowest failing index: the same report for any thread count.
  const std::size_t i = first_unstable(L);
  if (i < ps.size()) {
    const bool is_finite = state_is_finite(ps, i);
    throw InstabilityError(
        fmt::format("unstable at t = {:.6g} s, step {}: {} particle id {} at {} {} (check: {})", t_,
                    step_, kind_name(ps.kind[i]), ps.id[i], position_text<D>(ps.pos[i]),
                    is_finite ? fmt::format("has density {:.6g} kg/m^3 outside [{:.6g}, {:.6g}]",
                                            ps.rho[i], 0.5 * rho0, 2.0 * rho0)
                              : std::string("has a non-finite position, velocity or density"),
                    is_finite ? "density" : "finite"));
  }
}

// The fluid particle with the largest speed over levels [first, last). The dt checks name it
// rather than the largest acceleration: they run after the step's last sort, which leaves ps.acc
// to be recomputed (particles/cell_grid.cpp), so the accelerations no longer belong to their
// particles; a collapsing dt comes with a fast particle either way (the acoustic limit counts
// the largest speed, and a large acceleration makes one within a step).
template <int D>
std::string Simulation<D>::fastest_fluid(std::size_t first, std::size_t last) const {
  std::string culprit = "the fastest particles or largest accelerations";
  double vmax = -1.0;
  for (std::size_t l = first; l < last; ++l) {
    const ParticleSet<D>& q = levels_[l].ps;
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (q.kind[i] != Kind::fluid || !(norm(q.vel[i]) > vmax)) continue;
      vmax = norm(q.vel[i]);
      culprit = fmt::format("fastest fluid particle id {} of level {} at {}, speed {:.3g} m/s",
                            q.id[i], l, position_text<D>(q.pos[i]), vmax);
    }
  }
  return culprit;
}

// Stops the run when the global dt collapsed below 0.05 h / c0 of the finest level (the level
// that sets dt; a coarser level's bound would fire on a legitimate fine-level step), naming the
// fastest fluid particle over all levels: where to look.
template <int D>
void Simulation<D>::check_dt() const {
  double dt_min = 1e300;
  for (const Level<D>& L : levels_) dt_min = std::min(dt_min, L.prm.dt_min);
  if (dt_next_ >= dt_min) return;
  throw InstabilityError(fmt::format(
      "unstable at t = {:.6g} s, step {}: time step {:.3g} s fell below 0.05 h/c0 = {:.3g} s "
      "(check: dt; {})",
      t_, step_, dt_next_, dt_min, fastest_fluid(0, levels_.size())));
}

template <int D>
void Simulation<D>::restore(double t, std::int64_t step, double dt_next, const RunCounters& c,
                            std::size_t initial_fluid) {
  t_ = t;
  step_ = step;
  dt_next_ = dt_next;
  counters_ = c;
  initial_fluid_ = initial_fluid;
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace vrsph
