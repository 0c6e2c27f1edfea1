// One simulation: the resolution levels (one without [[refinement]]), their coupling
// (vres/level_coupling.hpp) and the scheduler that advances them: the symplectic step of
// docs/physics.md section 9 on every level with one global dt (solver/stepper.hpp), the coupling's
// hooks in between. Local time stepping per level plugs in here (docs/architecture.md). The
// driver (run.cpp) owns outputs, checkpoints and the progress line; this class only advances the
// physics and checks stability.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/setup/case_spec.hpp"
#include "vrsph/sim/surface_refresh.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/level.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/surface_pass.hpp"
#include "vrsph/solver/timestep.hpp"
#include "vrsph/solver/wall_reaction.hpp"
#include "vrsph/vres/level_coupling.hpp"

namespace vrsph {

// Thrown when a run goes unstable; the message names time, step, particle and the failed check.
struct InstabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Counters kept across a run (and across a resume, through the checkpoint).
struct RunCounters {
  std::uint64_t particle_steps = 0;  // sum over steps of particles stepped
  std::uint64_t pairs = 0;           // pair interactions within 2h, both stages
  std::array<std::uint64_t, 4> dt_limit_counts{};
  std::uint64_t lost_fluid = 0;  // fluid particles that left the domain
  double wall_seconds = 0.0;     // wall time spent stepping (resumed runs accumulate)
  // Variable resolution: particles created at mass points, and deleted (left their level's
  // region, or no donor fluid around a buffer particle), with their masses.
  std::uint64_t created = 0;
  std::uint64_t deleted = 0;
  double created_mass = 0.0;
  double deleted_mass = 0.0;
  std::uint64_t next_id = 0;  // id of the next created particle
};

// Wall-clock share per pass (seconds), for the benchmark profile.
struct PassTimes {
  double sort = 0.0;
  double surface = 0.0;  // surface-tension and shifting neighbour passes
  double forces = 0.0;
  double update = 0.0;
  double checks = 0.0;
  double coupling = 0.0;  // variable resolution: mass points, kinds, buffer interpolation
  std::uint64_t capillary_passes = 0;  // force evaluations that ran surface passes 2 and 3
};

// The length of the next step, and whether it ends exactly at the stop time.
struct StepPlan {
  double dt = 0.0;
  bool lands = false;
};

// The resolved physical set-up shared by check and run.
struct Setup {
  double c0 = 0.0;
  double max_speed = 0.0;
  double fluid_height = 0.0;
};

template <int D>
class Simulation {
 public:
  // Builds particles and parameters from a validated case. Fills spec.max_speed when it was
  // derived (so the resolved case records it). cells: the neighbour cells (0: the default of
  // the dimension, resolve_cell_layout).
  explicit Simulation(CaseSpec& spec, CellLayout cells = {});

  void step();  // one symplectic step of size dt_next(), then chooses the next dt

  double time() const { return t_; }
  std::int64_t step_count() const { return step_; }
  double dt_next() const { return dt_next_; }
  double dt_last() const { return dt_last_; }
  const Setup& setup() const { return setup_; }
  // Level 0 (the only level without [[refinement]]).
  const SolverParams<D>& params() const { return levels_[0].prm; }
  ParticleSet<D>& particles() { return levels_[0].ps; }
  const ParticleSet<D>& particles() const { return levels_[0].ps; }
  const CellGrid<D>& grid() const { return levels_[0].grid; }
  std::size_t level_count() const { return levels_.size(); }
  Level<D>& level(std::size_t k) { return levels_[k]; }
  const Level<D>& level(std::size_t k) const { return levels_[k]; }
  // Region and mass points of level k (variable resolution).
  LevelLink<D>& link(std::size_t k) { return coupling_.link(k); }
  const LevelLink<D>& link(std::size_t k) const { return coupling_.link(k); }
  RunCounters& counters() { return counters_; }
  const RunCounters& counters() const { return counters_; }
  const PassTimes& pass_times() const { return times_; }
  std::size_t initial_fluid() const { return initial_fluid_; }

  // Restores the stepping state (checkpoint); particles are set through particles().
  void restore(double t, std::int64_t step, double dt_next, const RunCounters& c,
               std::size_t initial_fluid);
  // The next step is shortened so as to end exactly at t_stop when it would pass it (output
  // times and the end time): snapshots fall on their nominal times, and a run extended from its
  // end time retraces an uninterrupted one.
  void set_stop_time(double t_stop) { stop_time_ = t_stop; }
  // Re-sorts after the particle arrays were replaced (resume).
  void resort();
  // Keeps the optional arrays of level k that its models read and gives back the others: shift
  // where the level shifts, pos0 where the level coupling reads it (several levels).
  void keep_optional_arrays(std::size_t k);
  // Number of particles of all levels.
  std::size_t total_particles() const;
  std::size_t count(Kind k) const;
  // Fluid momentum sum m v over all levels (buffer and wall particles excluded); mass gets the
  // fluid mass (vres/momentum.hpp).
  Vec<D> fluid_momentum(double& mass) const;

  // The force of the fluid on each [[wall_block]] (case order), summed over the levels' wall
  // particles of that block (solver/wall_reaction.hpp).
  std::vector<Vec<D>> wall_block_forces() const;

  // Recomputes lambda, normals, curvature, ... of every level for the current state (outputs);
  // surface_fields(k) then reads level k.
  // With the capillary refresh the held fields stay as they are: the outputs' fields are
  // computed apart.
  void update_surface_fields();
  const SurfaceFields<D>& surface_fields(std::size_t k = 0) const {
    return holds_surface_fields() ? output_sf_[k] : levels_[k].sf;
  }
  // Capillary refresh (sim/surface_refresh.hpp): the capillary acceleration is held between
  // refreshes; checkpoints keep it and the time of the last refresh.
  bool holds_surface_fields() const {
    for (const RefreshClock& c : refresh_)
      if (!c.every_step()) return true;
    return false;
  }
  // One clock per level (local time stepping) or clock 0 for all.
  const std::vector<RefreshClock>& refresh_clocks() const { return refresh_; }
  void restore_refresh(std::size_t k, double last) { refresh_[k].restore(last); }

  // Local time stepping (numerics.local_time_stepping, sim/local_stepping.cpp).
  bool local_time_stepping() const { return local_; }
  // The time level k has reached (the end of its last step), its steps so far, and the dt it
  // allows after its last step (checkpoints keep these; level 0's is dt_next()).
  double level_time(std::size_t k) const { return local_ ? level_t1_[k] : t_; }
  std::uint64_t level_steps(std::size_t k) const {
    return local_ ? level_steps_[k] : static_cast<std::uint64_t>(step_);
  }
  const std::vector<double>& level_dts() const { return level_dt_; }
  void restore_level_dts(const std::vector<double>& dts);
  bool has_surface_fields() const { return params().sigma > 0.0 || params().shifting.on(); }

 private:
  void sort_particles(Level<D>& L, bool step_copies = true);
  // Packs level k's columns for the passes of one evaluation, with the coupling's volume weights.
  void pack(std::size_t k);
  void sort_all(bool step_copies = true);
  void check_state(const Level<D>& L) const;
  void check_dt() const;
  // The fastest fluid particle of levels [first, last), as a diagnosis names it.
  std::string fastest_fluid(std::size_t first, std::size_t last) const;
  ForceStats evaluate_forces(double t_eval, bool corrector_stage);
  // Surface passes of levels [first, last) (sim/simulation_surface.cpp): all levels with one dt,
  // one level with local time stepping.
  bool surface_fields(std::size_t first, std::size_t last, double t_eval, bool corrector_stage);
  void refresh_after_forces(std::size_t first, std::size_t last, double t_eval, ForceStats* stats);
  void capillary_passes(std::size_t first, std::size_t last);
  void refresh(std::size_t first, std::size_t last, double t_eval);
  void start_refresh_clocks();
  // Local time stepping (sim/local_stepping.cpp).
  void start_local_stepping();
  void step_local(const StepPlan& plan);
  void advance_level(std::size_t k, double t0, double t1);
  void cycle_child(std::size_t c, double t0, double t1);
  void step_one_level(std::size_t k, double t0, double dt);
  ForceStats evaluate_level(std::size_t k, double t_eval, bool corrector_stage, double dt);
  void couple_level(std::size_t k, double dt, double t);
  std::vector<double> donor_fractions(double t) const;
  void check_level_dt(std::size_t k) const;
  double effective_dt(std::size_t k) const;
  double subtree_rate(std::size_t k, double dt) const;
  std::uint64_t substeps(std::size_t c, double dt) const;
  DtChoice next_dt(const ForceStats& s) const;
  void couple_levels(double dt);
  StepPlan plan_step() const;
  void advance_clock(const StepPlan& plan, const ForceStats& s);

  CaseSpec spec_;
  Setup setup_;
  std::vector<Level<D>> levels_;
  std::vector<std::vector<IdRange>> wall_ids_;  // per level, the ids of each wall block
  LevelCoupling<D> coupling_;
  double t_ = 0.0;
  double stop_time_ = 0.0;
  std::int64_t step_ = 0;
  double dt_next_ = 0.0;
  double dt_last_ = 0.0;
  std::size_t initial_fluid_ = 0;
  RunCounters counters_;
  PassTimes times_;
  std::vector<RefreshClock> refresh_;
  std::vector<SurfaceFields<D>> output_sf_;  // held fields only: what outputs read
  std::vector<ForceStats> level_stats_;      // one evaluation's force statistics per level
  // Local time stepping: the level tree, each level's last step [t0, t1], its allowed dt and
  // step count, and the net-force impulse summed since the levels last met.
  bool local_ = false;
  std::vector<std::vector<std::size_t>> children_;
  std::vector<double> level_t0_, level_t1_, level_dt_;
  std::vector<std::uint64_t> level_steps_;
  Vec<D> impulse_{};
};

}  // namespace vrsph
