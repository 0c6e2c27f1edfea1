// Local time stepping (numerics.local_time_stepping; docs/physics.md section 10): each resolution
// level advances with its own dt, and the levels meet at the ends of their parent's steps.
//
// One step of the root (level 0, dt from its own limits) is advance_level(0, t, t + dt):
//   1. the level takes one symplectic step on its own (solver/stepper.hpp), its buffer particles
//      holding the values they were given at its last step end;
//   2. each child level then catches up in 2^m steps of dt / 2^m, m the smallest that honours
//      the child's own limits (CFL, force, viscous, capillary) after its last step; m grows
//      within the parent's step if a child's limit falls, so the child still lands exactly on
//      the parent's step end. Each child step is advance_level(child, ...), so grandchildren
//      sub-cycle within it in turn;
//   3. at the step end, the level's coupling (vres/level_coupling.hpp, after_level_step): its
//      mass points accumulate over its own step, kinds change, and its buffer particles take
//      rho and v from the donor levels, each donor read at the same time: a parent that is ahead
//      is interpolated linearly between the states at the start and end of its step (pos0,
//      vel0, rho0 and pos, vel, rho); a child has just caught up.
// So a child's buffers follow the parent's motion within the parent's step, and the parent's
// buffers take the child's values where the two meet.
//
// The net-force corrections (zero_net_force, vres_conserve_momentum) do not alter the forces of
// a step: the net force of each level's corrector stage, times that step's dt (the corrector's
// velocity update uses the mid-step acceleration alone), is summed over all levels' steps, and
// the sum, an impulse, is removed as a uniform velocity of all fluid when the levels meet.
#include <fmt/format.h>

#include <chrono>
#include <cstdint>

#include "vrsph/physics/start_damping.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/solver/stepper.hpp"

namespace vrsph {
namespace {

constexpr std::uint64_t kMaxSubsteps = 1u << 12;  // per parent step

double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

}  // namespace

template <int D>
void Simulation<D>::start_local_stepping() {
  const std::size_t n = levels_.size();
  local_ = spec_.numerics.local_time_stepping && n > 1;
  level_t0_.assign(n, t_);
  level_t1_.assign(n, t_);
  level_steps_.assign(n, 0);
  level_dt_.assign(n, dt_next_);
  children_.assign(n, {});
  if (!local_) return;
  for (std::size_t k = 1; k < n; ++k)
    children_[static_cast<std::size_t>(coupling_.link(k).region.parent)].push_back(k);
  for (std::size_t k = 0; k < n; ++k) level_dt_[k] = level_dt_at_start(levels_[k], setup_.c0).dt;
  dt_next_ = effective_dt(0);
}

// Steps a child takes in a parent step of dt: the smallest power of two that keeps each within
// the child's effective dt (a little slack for the rounding of a power-of-two multiple of it).
template <int D>
std::uint64_t Simulation<D>::substeps(std::size_t c, double dt) const {
  const double limit = effective_dt(c) * (1.0 + 1e-9);
  std::uint64_t n = 1;
  while (dt / static_cast<double>(n) > limit && n < kMaxSubsteps) n *= 2;
  return n;
}

// Particle-steps per second of simulated time of level k's subtree when k steps with dt: the
// cost model that chooses between step lengths below.
template <int D>
double Simulation<D>::subtree_rate(std::size_t k, double dt) const {
  double r = static_cast<double>(levels_[k].ps.size()) / dt;
  for (std::size_t c : children_[k]) {
    const auto n = static_cast<double>(substeps(c, dt));
    r += subtree_rate(c, dt / n);
  }
  return r;
}

// The step level k takes with its subtree: its own limit, or shorter, a power-of-two multiple
// of a child's effective dt so that the child steps at exactly its limit, whichever costs less
// per unit time (subtree_rate). With the own limit alone a child whose limit lies just below
// half of its parent's would take quarter steps, twice as many as it needs.
template <int D>
double Simulation<D>::effective_dt(std::size_t k) const {
  const double own = level_dt_[k];
  double best = own, best_rate = children_[k].empty() ? 0.0 : subtree_rate(k, own);
  for (std::size_t c : children_[k]) {
    double fit = effective_dt(c);
    if (!(fit > 0.0) || fit >= own) continue;
    while (2.0 * fit <= own) fit *= 2.0;
    const double rate = subtree_rate(k, fit);
    if (rate < best_rate) best = fit, best_rate = rate;
  }
  return best;
}

template <int D>
void Simulation<D>::restore_level_dts(const std::vector<double>& dts) {
  if (dts.size() != level_dt_.size())
    throw std::invalid_argument(
        fmt::format("{} level dts for {} levels", dts.size(), level_dt_.size()));
  level_dt_ = dts;
  level_t0_.assign(levels_.size(), t_);
  level_t1_.assign(levels_.size(), t_);
}

// One step of the root, with every finer level sub-cycling inside it.
template <int D>
void Simulation<D>::step_local(const StepPlan& plan) {
  const double t0 = t_;
  const double t1 = plan.lands ? stop_time_ : t_ + plan.dt;
  impulse_ = Vec<D>{};
  advance_level(0, t0, t1);
  const bool st = levels_[0].prm.sigma > 0.0;
  if (coupling_.corrects_net_force(st)) coupling_.remove_impulse(levels_, impulse_);
  t_ = t1;
  ++step_;
  dt_last_ = t1 - t0;
  dt_next_ = effective_dt(0);
}

template <int D>
void Simulation<D>::advance_level(std::size_t k, double t0, double t1) {
  step_one_level(k, t0, t1 - t0);
  level_t0_[k] = t0;
  level_t1_[k] = t1;
  for (std::size_t c : children_[k]) cycle_child(c, t0, t1);
  couple_level(k, t1 - t0, t1);
}

// Child c from t0 to t1 (its parent's step) in equal steps of a power-of-two fraction of it,
// halved again (the remaining time is a whole number of half steps) if its limit falls.
template <int D>
void Simulation<D>::cycle_child(std::size_t c, double t0, double t1) {
  const double span = t1 - t0;
  std::uint64_t n = 1;  // steps of span / n
  std::uint64_t j = 0;  // steps done
  double t = t0;
  while (j < n) {
    const std::uint64_t need = substeps(c, span);
    while (n < need) n *= 2, j *= 2;
    const double te =
        j + 1 == n ? t1 : t0 + static_cast<double>(j + 1) * (span / static_cast<double>(n));
    advance_level(c, t, te);
    t = te;
    ++j;
  }
}

// One symplectic step of level k alone (the stages of Simulation::step), then its own dt.
template <int D>
void Simulation<D>::step_one_level(std::size_t k, double t0, double dt) {
  Level<D>& L = levels_[k];
  ForceStats s = evaluate_level(k, t0, false, dt);
  double tu = now_seconds();
  predictor(L, dt);
  times_.update += now_seconds() - tu;
  sort_particles(L);
  s.merge(evaluate_level(k, t0 + 0.5 * dt, true, dt));
  coupling_.before_corrector(levels_, k);
  tu = now_seconds();
  corrector(L, dt);
  const NumericsSpec& n = spec_.numerics;
  damp_fluid_velocities(L, start_damping_factor(t0, dt, n.start_damping_time, n.start_damping_tau));
  times_.update += now_seconds() - tu;
  counters_.particle_steps += L.ps.size();
  counters_.pairs += s.pairs;
  ++level_steps_[k];
  // The step copies stay with their particles only where children read this level between
  // its step's start and end (DonorState); elsewhere they are dead until the next predictor.
  sort_particles(L, !children_[k].empty());
  tu = now_seconds();
  const DtChoice c = level_dt(L, s, setup_.c0);
  level_dt_[k] = c.dt;
  ++counters_.dt_limit_counts[static_cast<std::size_t>(c.limit)];
  check_state(L);
  check_level_dt(k);
  times_.checks += now_seconds() - tu;
}

// One force evaluation of level k at t_eval; at the corrector stage the net force the
// corrections remove is added to the impulse, times the step's dt. The fluid's pair
// acceleration (vres_conserve_momentum) feeds only that impulse: the predictor's stage skips it.
template <int D>
ForceStats Simulation<D>::evaluate_level(std::size_t k, double t_eval, bool corrector_stage,
                                         double dt) {
  Level<D>& L = levels_[k];
  pack(k);
  const bool after = surface_fields(k, k + 1, t_eval, corrector_stage);  // passes 2, 3 after
  double t0 = now_seconds();
  const bool st = L.prm.sigma > 0.0;
  ForceStats s = level_forces(L, st && !after, corrector_stage && coupling_.wants_pair_acc());
  times_.forces += now_seconds() - t0;
  if (after) refresh_after_forces(k, k + 1, t_eval, &s);
  t0 = now_seconds();
  if (corrector_stage && coupling_.corrects_net_force(st))
    impulse_ += dt * coupling_.net_force(levels_, k, st);
  times_.forces += now_seconds() - t0;
  return s;
}

// Where each level stands at time t, as a fraction of its last step: 1 for a level that has
// reached t (a child that has caught up, the level itself), in (0, 1) for a parent that is ahead.
template <int D>
std::vector<double> Simulation<D>::donor_fractions(double t) const {
  std::vector<double> a(levels_.size(), 1.0);
  for (std::size_t d = 0; d < levels_.size(); ++d) {
    const double span = level_t1_[d] - level_t0_[d];
    if (level_t1_[d] != t && span > 0.0) a[d] = std::clamp((t - level_t0_[d]) / span, 0.0, 1.0);
  }
  return a;
}

template <int D>
void Simulation<D>::couple_level(std::size_t k, double dt, double t) {
  if (!coupling_.multi_level()) return;
  const double t0 = now_seconds();
  Level<D>& L = levels_[k];
  const CouplingTally tally =
      coupling_.after_level_step(levels_, k, dt, donor_fractions(t), counters_.next_id,
                                 [this, &L] { sort_particles(L, false); });
  counters_.created += tally.created;
  counters_.deleted += tally.deleted;
  counters_.created_mass += tally.created_mass;
  counters_.deleted_mass += tally.deleted_mass;
  times_.coupling += now_seconds() - t0;
}

// As check_dt, for level k's own dt against its own bound.
template <int D>
void Simulation<D>::check_level_dt(std::size_t k) const {
  const Level<D>& L = levels_[k];
  if (level_dt_[k] >= L.prm.dt_min) return;
  const std::string culprit = fastest_fluid(k, k + 1);
  throw InstabilityError(
      fmt::format("unstable at t = {:.6g} s, step {}: level {} time step {:.3g} s fell below "
                  "0.05 h/c0 = {:.3g} s (check: dt; {})",
                  level_t1_[k], step_, k, level_dt_[k], L.prm.dt_min, culprit));
}

template void Simulation<2>::start_local_stepping();
template void Simulation<3>::start_local_stepping();
template void Simulation<2>::restore_level_dts(const std::vector<double>&);
template void Simulation<3>::restore_level_dts(const std::vector<double>&);
template void Simulation<2>::step_local(const StepPlan&);
template void Simulation<3>::step_local(const StepPlan&);

}  // namespace vrsph
