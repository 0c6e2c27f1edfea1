// The surface-tension and shifting passes of a simulation (Simulation members): when they run
// (every evaluation, or on the capillary refresh clock of sim/surface_refresh.hpp), on all levels
// together (one global dt) or on one level (local time stepping), and the fields for outputs.
#include <chrono>
#include <limits>

#include "vrsph/sim/simulation.hpp"
#include "vrsph/solver/stepper.hpp"

namespace vrsph {
namespace {

double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

}  // namespace

// The capillary refresh: the interval is refresh_interval capillary limits of the level's own h
// (local time stepping), or of the finest level (one clock for all levels: clock 0); every level
// then holds its capillary acceleration (SurfaceFields::held). With local time stepping lambda,
// the normal and the curvature are held too (held_geometry), also when they are refreshed at
// every evaluation: a level's buffers read the other levels' lambda and normal between those
// levels' own passes.
template <int D>
void Simulation<D>::start_refresh_clocks() {
  refresh_.assign(levels_.size(), RefreshClock());
  const SurfaceTensionParams& st = spec_.numerics.surface_tension;
  const bool sigma = spec_.fluid.surface_tension > 0.0;
  if (sigma && local_)
    for (Level<D>& L : levels_) L.sf.held = L.sf.held_geometry = true;
  if (!sigma || st.refresh != SurfaceRefresh::capillary) return;
  double dt_min = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    const SolverParams<D>& p = levels_[k].prm;
    const double dt_st = capillary_dt(p.eos.rho0, p.h, p.sigma);
    dt_min = std::min(dt_min, dt_st);
    refresh_[k] = RefreshClock(st.refresh_interval * dt_st);
    levels_[k].sf.held = true;
  }
  if (!local_) refresh_[0] = RefreshClock(st.refresh_interval * dt_min);
}

// Passes 2 and 3 of every level, each on all levels before the next, so that the coupling can
// give buffer particles lambda (after pass 1) and the normal (after pass 2) from the other level
// before the next pass uses them.
template <int D>
void Simulation<D>::capillary_passes() {
  coupling_.after_surface_sums(levels_);
  for (Level<D>& L : levels_) surface_pass_normals(L);
  coupling_.after_normals(levels_);
  for (Level<D>& L : levels_) surface_pass_curvature(L);
}

// A capillary refresh of every level after pass 1: passes 2 and 3, the held acceleration's
// history, the clock.
template <int D>
void Simulation<D>::refresh_all(double t_eval) {
  RefreshClock& clock = refresh_[0];
  capillary_passes();
  if (!clock.every_step())
    for (Level<D>& L : levels_) L.sf.take_refresh(t_eval - clock.last());
  clock.mark(t_eval);
  ++times_.capillary_passes;
}

// The surface fields a force evaluation at t_eval needs, before its force pass. The capillary
// acceleration: at every evaluation, or when the refresh clock says so (extrapolated from the last
// two refreshes in between, SurfaceFields::extrapolate). At a refresh the force pass sums pass 1
// for the fluid particles where it can (surface_pass_sums_in_forces: one sweep for both), and
// passes 2 and 3 then follow it (refresh_after_forces); elsewhere they run here. Without a
// refresh, pass 1 alone at the corrector's stage, for shifting's grad C and div r (over buffer
// particles only, the force pass summing the fluid's); the first stage's pass 1 would feed
// nothing but passes 2 and 3. Returns whether passes 2 and 3 wait for the force pass.
template <int D>
bool Simulation<D>::surface_fields_all(double t_eval, bool corrector_stage) {
  if (!has_surface_fields()) return false;
  RefreshClock& clock = refresh_[0];  // one clock for all levels, as for dt
  const bool sigma = levels_[0].prm.sigma > 0.0;
  const bool capillary = sigma && clock.due(t_eval, corrector_stage);
  if (sigma && !capillary)
    for (Level<D>& L : levels_) L.sf.extrapolate(t_eval - clock.last());
  const bool shifting = levels_[0].prm.shifting.on();
  if (!capillary && !(shifting && corrector_stage)) return false;
  const double t0 = now_seconds();
  bool folded = false;
  for (Level<D>& L : levels_) {
    if (capillary)
      folded = surface_pass_sums_in_forces(L) || folded;
    else
      surface_pass_shifting_sums(L);
  }
  if (capillary && !folded) refresh_all(t_eval);
  times_.surface += now_seconds() - t0;
  return folded;
}

// After the force pass of an evaluation whose passes 2 and 3 waited for it (surface_fields_all
// returned true): the refresh, and the capillary acceleration added to each level's forces
// (whose statistics `per_level` it updates).
template <int D>
void Simulation<D>::refresh_after_forces(double t_eval, std::vector<ForceStats>& per_level) {
  const double t0 = now_seconds();
  refresh_all(t_eval);
  for (std::size_t k = 0; k < levels_.size(); ++k) add_capillary(levels_[k], per_level[k]);
  times_.surface += now_seconds() - t0;
}

// refresh_all for level k alone (local time stepping): its buffers take lambda and the normal
// from the other levels' held fields.
template <int D>
void Simulation<D>::refresh_level(std::size_t k, double t_eval) {
  Level<D>& L = levels_[k];
  RefreshClock& clock = refresh_[k];
  coupling_.after_surface_sums(levels_, k);
  surface_pass_normals(L);
  coupling_.after_normals(levels_, k);
  surface_pass_curvature(L);
  if (!clock.every_step()) L.sf.take_refresh(t_eval - clock.last());
  clock.mark(t_eval);
  ++times_.capillary_passes;
}

// The surface fields of level k alone at t_eval (local time stepping), before its force pass: as
// surface_fields_all, on the level's own clock.
template <int D>
bool Simulation<D>::surface_fields_level(std::size_t k, double t_eval, bool corrector_stage) {
  if (!has_surface_fields()) return false;
  Level<D>& L = levels_[k];
  RefreshClock& clock = refresh_[k];
  const bool sigma = L.prm.sigma > 0.0;
  const bool capillary = sigma && clock.due(t_eval, corrector_stage);
  if (sigma && !capillary) L.sf.extrapolate(t_eval - clock.last());
  const bool shifting = L.prm.shifting.on();
  if (!capillary && !(shifting && corrector_stage)) return false;
  const double t0 = now_seconds();
  bool folded = false;
  if (capillary) {
    folded = surface_pass_sums_in_forces(L);
    if (!folded) refresh_level(k, t_eval);
  } else {
    surface_pass_shifting_sums(L);
  }
  times_.surface += now_seconds() - t0;
  return folded;
}

// refresh_after_forces for level k alone.
template <int D>
void Simulation<D>::refresh_level_after_forces(std::size_t k, double t_eval, ForceStats& s) {
  const double t0 = now_seconds();
  refresh_level(k, t_eval);
  add_capillary(levels_[k], s);
  times_.surface += now_seconds() - t0;
}

// Every surface field of every level for the current state (outputs). Held fields are swapped
// out first, so that an output never changes the run.
template <int D>
void Simulation<D>::update_surface_fields() {
  const double keep = times_.surface;  // output work, not stepping time
  const bool hold = holds_surface_fields();
  if (hold) {
    output_sf_.resize(levels_.size());
    for (std::size_t k = 0; k < levels_.size(); ++k) std::swap(levels_[k].sf, output_sf_[k]);
  }
  for (std::size_t k = 0; k < levels_.size(); ++k) pack(k);
  for (Level<D>& L : levels_) surface_pass_sums(L);
  if (has_surface_fields() && levels_[0].prm.sigma > 0.0) capillary_passes();
  if (hold) {
    for (std::size_t k = 0; k < levels_.size(); ++k) std::swap(levels_[k].sf, output_sf_[k]);
  }
  times_.surface = keep;
}

template void Simulation<2>::start_refresh_clocks();
template void Simulation<3>::start_refresh_clocks();
template void Simulation<2>::capillary_passes();
template void Simulation<3>::capillary_passes();
template void Simulation<2>::refresh_all(double);
template void Simulation<3>::refresh_all(double);
template void Simulation<2>::refresh_level(std::size_t, double);
template void Simulation<3>::refresh_level(std::size_t, double);
template bool Simulation<2>::surface_fields_all(double, bool);
template bool Simulation<3>::surface_fields_all(double, bool);
template void Simulation<2>::refresh_after_forces(double, std::vector<ForceStats>&);
template void Simulation<3>::refresh_after_forces(double, std::vector<ForceStats>&);
template bool Simulation<2>::surface_fields_level(std::size_t, double, bool);
template bool Simulation<3>::surface_fields_level(std::size_t, double, bool);
template void Simulation<2>::refresh_level_after_forces(std::size_t, double, ForceStats&);
template void Simulation<3>::refresh_level_after_forces(std::size_t, double, ForceStats&);
template void Simulation<2>::update_surface_fields();
template void Simulation<3>::update_surface_fields();

}  // namespace vrsph
