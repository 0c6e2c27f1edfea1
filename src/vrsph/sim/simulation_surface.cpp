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

// Passes 2 and 3 of levels [first, last), each pass on all of them before the next, so that the
// coupling can give buffer particles lambda (after pass 1) and the normal (after pass 2) from
// the other levels before the next pass uses them.
template <int D>
void Simulation<D>::capillary_passes(std::size_t first, std::size_t last) {
  for (std::size_t l = first; l < last; ++l) coupling_.after_surface_sums(levels_, l);
  for (std::size_t l = first; l < last; ++l) surface_pass_normals(levels_[l]);
  for (std::size_t l = first; l < last; ++l) coupling_.after_normals(levels_, l);
  for (std::size_t l = first; l < last; ++l) surface_pass_curvature(levels_[l]);
}

// A capillary refresh of levels [first, last) after pass 1, on the clock of level `first` (with
// one dt, clock 0 serves every level): passes 2 and 3, the held acceleration's history, the clock.
template <int D>
void Simulation<D>::refresh(std::size_t first, std::size_t last, double t_eval) {
  RefreshClock& clock = refresh_[first];
  capillary_passes(first, last);
  if (!clock.every_step())
    for (std::size_t l = first; l < last; ++l) levels_[l].sf.take_refresh(t_eval - clock.last());
  clock.mark(t_eval);
  ++times_.capillary_passes;
}

// The surface fields a force evaluation of levels [first, last) at t_eval needs, before its force
// pass: every level with one dt (on clock 0), or one level with local time stepping (on its own
// clock; its buffers take lambda and the normal from the other levels' held fields). The
// capillary acceleration: at every evaluation, or when the refresh clock says so (extrapolated
// from the last two refreshes in between, SurfaceFields::extrapolate). At a refresh the force pass
// sums pass 1 for the fluid particles where it can (surface_pass_sums_in_forces: one sweep for
// both), and passes 2 and 3 then follow it (refresh_after_forces); elsewhere they run here.
// Without a refresh, pass 1 alone at the corrector's stage, for shifting's grad C and div r (over
// buffer particles only, the force pass summing the fluid's); the first stage's pass 1 would feed
// nothing but passes 2 and 3. Returns whether passes 2 and 3 wait for the force pass.
template <int D>
bool Simulation<D>::surface_fields(std::size_t first, std::size_t last, double t_eval,
                                   bool corrector_stage) {
  if (!has_surface_fields()) return false;
  RefreshClock& clock = refresh_[first];
  const SolverParams<D>& prm = levels_[first].prm;
  const bool sigma = prm.sigma > 0.0;
  const bool capillary = sigma && clock.due(t_eval, corrector_stage);
  if (sigma && !capillary)
    for (std::size_t l = first; l < last; ++l) levels_[l].sf.extrapolate(t_eval - clock.last());
  if (!capillary && !(prm.shifting.on() && corrector_stage)) return false;
  const double t0 = now_seconds();
  bool folded = false;
  for (std::size_t l = first; l < last; ++l) {
    if (capillary)
      folded = surface_pass_sums_in_forces(levels_[l]) || folded;
    else
      surface_pass_shifting_sums(levels_[l]);
  }
  if (capillary && !folded) refresh(first, last, t_eval);
  times_.surface += now_seconds() - t0;
  return folded;
}

// After the force pass of an evaluation whose passes 2 and 3 waited for it (surface_fields
// returned true): the refresh, and the capillary acceleration added to each level's forces, whose
// statistics stats[l - first] it updates.
template <int D>
void Simulation<D>::refresh_after_forces(std::size_t first, std::size_t last, double t_eval,
                                         ForceStats* stats) {
  const double t0 = now_seconds();
  refresh(first, last, t_eval);
  for (std::size_t l = first; l < last; ++l) add_capillary(levels_[l], stats[l - first]);
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
  if (has_surface_fields() && levels_[0].prm.sigma > 0.0) capillary_passes(0, levels_.size());
  if (hold) {
    for (std::size_t k = 0; k < levels_.size(); ++k) std::swap(levels_[k].sf, output_sf_[k]);
  }
  times_.surface = keep;
}

template void Simulation<2>::start_refresh_clocks();
template void Simulation<3>::start_refresh_clocks();
template void Simulation<2>::capillary_passes(std::size_t, std::size_t);
template void Simulation<3>::capillary_passes(std::size_t, std::size_t);
template void Simulation<2>::refresh(std::size_t, std::size_t, double);
template void Simulation<3>::refresh(std::size_t, std::size_t, double);
template bool Simulation<2>::surface_fields(std::size_t, std::size_t, double, bool);
template bool Simulation<3>::surface_fields(std::size_t, std::size_t, double, bool);
template void Simulation<2>::refresh_after_forces(std::size_t, std::size_t, double, ForceStats*);
template void Simulation<3>::refresh_after_forces(std::size_t, std::size_t, double, ForceStats*);
template void Simulation<2>::update_surface_fields();
template void Simulation<3>::update_surface_fields();

}  // namespace vrsph
