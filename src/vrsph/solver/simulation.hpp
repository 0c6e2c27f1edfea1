// One simulation: the particles of a single resolution level, its cell grid and parameters, and
// the symplectic time stepping of PHYSICS.md section 2. The driver (run.cpp) owns outputs,
// checkpoints and the progress line; this class only advances the physics and checks stability.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/setup/case_spec.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/params.hpp"
#include "vrsph/solver/surface_pass.hpp"
#include "vrsph/solver/timestep.hpp"

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
  std::uint64_t lost_fluid = 0;      // fluid particles that left the domain
  double wall_seconds = 0.0;         // wall time spent stepping (resumed runs accumulate)
};

// Wall-clock share per pass (seconds), for the benchmark profile.
struct PassTimes {
  double sort = 0.0;
  double surface = 0.0;  // surface-tension and shifting neighbour passes
  double forces = 0.0;
  double update = 0.0;
  double checks = 0.0;
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
  // derived (so the resolved case records it).
  explicit Simulation(CaseSpec& spec, int cells_per_support = 2);

  void step();  // one symplectic step of size dt_next(), then chooses the next dt

  double time() const { return t_; }
  std::int64_t step_count() const { return step_; }
  double dt_next() const { return dt_next_; }
  double dt_last() const { return dt_last_; }
  const Setup& setup() const { return setup_; }
  const SolverParams<D>& params() const { return prm_; }
  ParticleSet<D>& particles() { return ps_; }
  const ParticleSet<D>& particles() const { return ps_; }
  const CellGrid<D>& grid() const { return grid_; }
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

  // Pressure of every particle from its current density (outputs).
  void update_pressure();

  // lambda, normals, curvature, ... of the current state (outputs); recomputed on each call.
  const SurfaceFields<D>& surface_fields_now();
  bool has_surface_fields() const {
    return prm_.sigma > 0.0 || prm_.shifting.model != ShiftingModel::none;
  }

 private:
  void sort_particles();
  void predictor(double dt);
  void corrector(double dt);
  void check_state() const;
  ForceStats evaluate_forces();
  DtChoice next_dt(const ForceStats& a, const ForceStats& b) const;

  CaseSpec spec_;
  Setup setup_;
  SolverParams<D> prm_;
  ParticleSet<D> ps_;
  CellGrid<D> grid_;
  ForceWorkspace<D> force_ws_;
  SurfaceFields<D> sf_;
  double t_ = 0.0;
  double stop_time_ = 0.0;
  std::int64_t step_ = 0;
  double dt_next_ = 0.0;
  double dt_last_ = 0.0;
  std::size_t initial_fluid_ = 0;
  RunCounters counters_;
  PassTimes times_;
};

}  // namespace vrsph
