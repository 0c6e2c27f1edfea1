#include "vrsph/solver/simulation.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <type_traits>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/walls.hpp"
#include "vrsph/setup/geometry.hpp"
#include "vrsph/solver/level_setup.hpp"
#include "vrsph/solver/momentum.hpp"
#include "vrsph/vres/coupling.hpp"
#include "vrsph/vres/interpolation.hpp"
#include "vrsph/vres/levels.hpp"

namespace vrsph {
namespace {

// Reach, in h of the level, of a buffer particle's own lambda and normal (see
// exchange_buffer_surface_field).
constexpr double kBufferLambdaReach = 1.0;
constexpr double kBufferNormalReach = 2.0;

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

}  // namespace

template <int D>
Simulation<D>::Simulation(CaseSpec& spec, int cells_per_support) : spec_(spec) {
  const std::vector<LevelLayout<D>> layout = make_level_layout<D>(spec);
  levels_.resize(layout.size());

  // Speed of sound (common to all levels): given, or sound_speed_factor x max_speed, with
  // max_speed = sqrt(g H) for gravity cases when not given (PHYSICS.md section 2). H and initial
  // velocities come from the level-0 fill, which level 0 then takes its particles from.
  InitialSet<D> init0 = level_fill<D>(spec, spec.dp);
  {
    setup_.fluid_height = init0.fluid_height;
    const double g = norm(to_vec<D>(spec.fluid.gravity));
    if (!spec.eos.max_speed) {
      if (g > 0.0 && setup_.fluid_height > 0.0) {
        spec.eos.max_speed = std::sqrt(g * setup_.fluid_height);
      } else {
        double vmax = 0.0;
        for (const auto& v : init0.particles.vel) vmax = std::max(vmax, norm(v));
        if (vmax > 0.0) spec.eos.max_speed = vmax;
      }
    }
  }
  if (!spec.eos.sound_speed && !spec.eos.max_speed) {
    throw std::invalid_argument(
        "eos.max_speed: missing: needed to set the speed of sound when there is no gravity and no "
        "initial velocity (give eos.max_speed or eos.sound_speed)");
  }
  setup_.max_speed = spec.eos.max_speed.value_or(0.0);
  setup_.c0 = spec.eos.sound_speed ? *spec.eos.sound_speed : spec.eos.sound_speed_factor * *spec.eos.max_speed;

  std::uint64_t next_id = 0;
  for (std::size_t k = 0; k < layout.size(); ++k) {
    Level<D>& L = levels_[k];
    L.prm = level_params<D>(spec, layout[k].dp, setup_.c0);
    L.region = layout[k].region;
    L.ps = level_particles<D>(spec, layout[k], L.prm, next_id,
                              k == 0 ? std::move(init0) : level_fill<D>(spec, layout[k].dp));
    next_id += L.ps.size();
    L.mass_points = level_mass_points<D>(L.region, L.prm.dp);
  }
  counters_.next_id = next_id;

  // One domain for all levels, from the level-0 particles.
  Vec<D> lo, hi;
  default_domain<D>(levels_[0].ps, levels_[0].prm.up, levels_[0].prm.h, lo, hi);
  if (spec.domain_min) lo = to_vec<D>(*spec.domain_min);
  if (spec.domain_max) hi = to_vec<D>(*spec.domain_max);
  for (Level<D>& L : levels_) {
    L.grid = CellGrid<D>(lo, hi, L.prm.kernel.support(), cells_per_support);
    L.ps.resize(L.ps.size());
    sort_particles(L);
  }
  initial_fluid_ = count(Kind::fluid);
  stop_time_ = spec.end_time;
  if (levels_.size() > 1) couple_levels(0.0);  // buffer values from the other levels

  // First step: the acoustic limit of a fluid at rest, with the viscous and capillary limits.
  dt_next_ = 1e300;
  for (const Level<D>& L : levels_) {
    DtInputs in{L.prm.h, L.prm.cfl, setup_.c0, 0.0, 0.0, 0.0, L.prm.viscosity.nu, spec.fluid.density, L.prm.sigma};
    for (const auto& v : L.ps.vel) in.max_speed = std::max(in.max_speed, norm(v));
    dt_next_ = std::min(dt_next_, choose_dt(in).dt);
  }
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
void Simulation<D>::sort_particles(Level<D>& L) {
  const double t0 = now_seconds();
  const auto lost = L.grid.sort(L.ps);
  times_.sort += now_seconds() - t0;
  if (lost.empty()) return;
  // Lost wall particles can only be a set-up error (walls never move).
  counters_.lost_fluid += lost.size();
  const double frac = static_cast<double>(counters_.lost_fluid) /
                      static_cast<double>(std::max<std::size_t>(initial_fluid_, 1));
  if (initial_fluid_ > 0 && frac > spec_.max_lost_fraction) {
    throw InstabilityError(fmt::format(
        "unstable at t = {:.6g} s, step {}: {} fluid particles ({:.3g}% of {}) have left the "
        "domain (last: id {}) (check: domain, limit domain.max_lost_fraction = {})",
        t_, step_, counters_.lost_fluid, 100.0 * frac, initial_fluid_, lost.back(),
        spec_.max_lost_fraction));
  }
}

template <int D>
void Simulation<D>::sort_all() {
  for (Level<D>& L : levels_) sort_particles(L);
}

template <int D>
void Simulation<D>::resort() {
  for (Level<D>& L : levels_) L.ps.resize(L.ps.size());
  sort_all();
}

template <int D>
void Simulation<D>::update_pressure() {
  for (Level<D>& L : levels_) {
    L.ps.p.resize(L.ps.size());
    for (std::size_t i = 0; i < L.ps.size(); ++i) L.ps.p[i] = L.prm.eos.pressure(L.ps.rho[i]);
  }
}

// Predictor (dt/2): x+ = x + dt/2 v, v+ = v + dt/2 (a + g), rho+ = rho + dt/2 drho.
// Walls keep position and velocity; their density is clamped at >= rho0 (dynamic boundary).
// Buffer particles move with their velocity; their v and rho come from the other level
// (PHYSICS.md section 5) and are not integrated.
template <int D>
void Simulation<D>::predictor(Level<D>& L, double dt) {
  ParticleSet<D>& ps = L.ps;
  const double half = 0.5 * dt;
  const double rho0 = L.prm.eos.rho0;
  const Vec<D> g = L.prm.gravity;
  exec::for_each(static_cast<std::int64_t>(ps.size()), [&](std::int64_t i) {
    ps.pos0[i] = ps.pos[i];
    ps.vel0[i] = ps.vel[i];
    ps.rho0[i] = ps.rho[i];
    if (ps.kind[i] == Kind::buffer) {
      ps.pos[i] += half * ps.vel[i];
      return;
    }
    ps.rho[i] = ps.rho[i] + half * ps.drho[i];
    if (ps.kind[i] == Kind::wall) {
      ps.rho[i] = wall_density(ps.rho[i], rho0);
      return;
    }
    ps.pos[i] += half * ps.vel[i];
    ps.vel[i] += half * (ps.acc[i] + g);
  });
}

// Corrector: v' = v + dt (a+ + g), x' = x + dt (v + v')/2 + dr_shift, rho' = rho (2 - eps)/(2 + eps),
// eps = -(drho+/rho+) dt. Buffer particles: x' = x + dt v + dr_shift without its component
// normal to the nearest interface face (PHYSICS.md section 5); v and rho unchanged.
template <int D>
void Simulation<D>::corrector(Level<D>& L, double dt) {
  ParticleSet<D>& ps = L.ps;
  const SolverParams<D>& prm = L.prm;
  const double rho0 = prm.eos.rho0;
  const bool shifting = prm.shifting.model != ShiftingModel::none;
  exec::for_each(static_cast<std::int64_t>(ps.size()), [&](std::int64_t i) {
    if (ps.kind[i] == Kind::wall) {
      const double eps = -(ps.drho[i] / ps.rho[i]) * dt;
      ps.rho[i] = wall_density(ps.rho0[i] * (2.0 - eps) / (2.0 + eps), rho0);
      return;
    }
    if (shifting) {  // from the half-step sums and velocity
      ps.shift[i] = shifting_displacement<D>(prm.shifting, L.sf.grad_c[i], L.sf.div_r[i],
                                             norm(ps.vel[i]), dt);
    }
    if (ps.kind[i] == Kind::buffer) {
      if (shifting) {
        const Vec<D> nf = L.region.classify(ps.pos0[i]).face_normal;
        ps.shift[i] -= dot(ps.shift[i], nf) * nf;
      }
      ps.rho[i] = ps.rho0[i];
      ps.vel[i] = ps.vel0[i];
      ps.pos[i] = ps.pos0[i] + dt * ps.vel0[i] + ps.shift[i];
      return;
    }
    const double eps = -(ps.drho[i] / ps.rho[i]) * dt;
    ps.rho[i] = ps.rho0[i] * (2.0 - eps) / (2.0 + eps);
    ps.vel[i] = ps.vel0[i] + dt * (ps.acc[i] + prm.gravity);
    ps.pos[i] = ps.pos0[i] + (0.5 * dt) * (ps.vel0[i] + ps.vel[i]) + ps.shift[i];
  });
}

// Next dt: the minimum over levels (one global dt, PHYSICS.md section 5); `s` holds the maxima
// of both stages over all levels, and the speeds are taken per level.
template <int D>
DtChoice Simulation<D>::next_dt(const ForceStats& s) const {
  DtChoice best{1e300, DtLimit{}};
  bool first = true;
  for (const Level<D>& L : levels_) {
    double vmax2 = 0.0;
    for (std::size_t i = 0; i < L.ps.size(); ++i) {
      if (L.ps.kind[i] != Kind::wall) vmax2 = std::max(vmax2, norm2(L.ps.vel[i]));
    }
    const DtInputs in{L.prm.h, L.prm.cfl, setup_.c0, s.max_acc, std::sqrt(vmax2),
                      s.max_visc_dt, L.prm.viscosity.nu, L.prm.eos.rho0, L.prm.sigma};
    const DtChoice c = choose_dt(in);
    if (first || c.dt < best.dt) best = c;
    first = false;
  }
  return best;
}

// The surface passes of every level (when surface tension or shifting is on), each pass on all
// levels before the next, so that buffer particles can take lambda (after pass 1) and the normal
// (after pass 2) from the other level before the next pass uses them.
template <int D>
void Simulation<D>::surface_fields_all() {
  if (!has_surface_fields()) return;
  const double t0 = now_seconds();
  const bool st = levels_[0].prm.sigma > 0.0;
  const bool vres = levels_.size() > 1;
  for (Level<D>& L : levels_) surface_sums(L.prm, L.ps, L.grid, L.cols, L.sf);
  if (st) {
    if (vres) exchange_buffer_surface_field(&SurfaceFields<D>::lambda, kBufferLambdaReach);
    for (Level<D>& L : levels_) surface_normals(L.prm, L.ps, L.grid, L.cols, L.sf);
    if (vres) exchange_buffer_surface_field(&SurfaceFields<D>::normal, kBufferNormalReach);
    for (Level<D>& L : levels_) surface_curvature_force(L.prm, L.ps, L.grid, L.cols, L.sf);
  }
  times_.surface += now_seconds() - t0;
}

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
// The reaches are measured, not derived: the kernel's outer half-h carries little weight, so a
// reach of 1h for lambda and 2h for normals (4h shells: only lambda within h of the outer edge is
// replaced) gave curvatures within 10% of the rest of the surface at the crossings of the 2D VR
// droplet (rings, t = 0: fine 445 vs 458 1/m, coarse 483 vs 484), where reaches of 2h and 4h gave
// 552 and 393, and the other level's lambda in the whole shell gave 3653 and -577.
// An averaged normal keeps its direction where most of the donor weight has a normal
// (|average| >= 1/2), and is zero otherwise.
template <int D>
template <class T>
void Simulation<D>::exchange_buffer_surface_field(std::vector<T> SurfaceFields<D>::*field,
                                                  double reach_h) {
  for (Level<D>& L : levels_) {
    const auto n = static_cast<std::int64_t>(L.ps.size());
    std::vector<T>& own = L.sf.*field;
    exec::for_each_dynamic(n, 64, [&](std::int64_t ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (L.ps.kind[i] != Kind::buffer) return;
      const ZoneInfo<D> z = L.region.classify(L.ps.pos[i]);
      if (z.donor < 0) return;  // moved into the fluid region during the step: kind changes later
      if (z.depth + reach_h * L.prm.h <= z.width) return;  // own support inside fluid + shell
      const Level<D>& dl = levels_[static_cast<std::size_t>(z.donor)];
      T v = shepard_field<D, T>(L.ps.pos[i], dl.ps, dl.grid, dl.prm.kernel, dl.sf.*field, T{});
      if constexpr (std::is_same_v<T, Vec<D>>) {
        const double m = norm(v);
        v = m >= 0.5 ? v * (1.0 / m) : Vec<D>{};
      }
      own[i] = v;
    });
  }
}

// The optional corrections of momentum.hpp: the net coupling force F_c (variable resolution) and
// the net capillary force F_st, removed as a uniform acceleration of the fluid.
template <int D>
void Simulation<D>::remove_spurious_net_force(bool surface_tension) {
  const bool coupling = spec_.vres_conserve_momentum && levels_.size() > 1;
  const bool capillary = spec_.numerics.surface_tension.zero_net_force && surface_tension;
  if (!coupling && !capillary) return;
  Vec<D> f{};
  if (coupling) f += coupling_net_force(levels_);
  if (capillary) f += surface_net_force(levels_);
  double mass = 0.0;
  fluid_momentum(mass);
  if (mass > 0.0) add_to_fluid(levels_, f * (-1.0 / mass), false);
}

// One force evaluation of all levels: the surface passes, then the pair forces of each level
// with the surface-tension acceleration added.
template <int D>
ForceStats Simulation<D>::evaluate_forces() {
  for (Level<D>& L : levels_) L.cols.pack(L.ps, L.prm.eos);  // once, for every pass below
  surface_fields_all();
  const double t0 = now_seconds();
  const bool st = levels_[0].prm.sigma > 0.0;
  ForceStats s;
  const bool reaction = spec_.vres_conserve_momentum && levels_.size() > 1;
  for (Level<D>& L : levels_) {
    s.merge(compute_forces_packed(L.prm, L.ps, L.grid, L.cols,
                                  st ? L.sf.acc_st.data() : nullptr, reaction));
  }
  remove_spurious_net_force(st);
  times_.forces += now_seconds() - t0;
  return s;
}

template <int D>
void Simulation<D>::update_surface_fields() {
  const double keep = times_.surface;  // output work, not stepping time
  for (Level<D>& L : levels_) L.cols.pack(L.ps, L.prm.eos);
  if (has_surface_fields()) {
    surface_fields_all();
  } else {
    for (Level<D>& L : levels_) surface_sums(L.prm, L.ps, L.grid, L.cols, L.sf);
  }
  times_.surface = keep;
}

// Variable resolution after a step (PHYSICS.md section 5): mass points, kind changes and
// deletions, then buffer values from the other levels.
template <int D>
void Simulation<D>::couple_levels(double dt) {
  const double t0 = now_seconds();
  double mass = 0.0;
  const bool conserve = spec_.vres_conserve_momentum;
  const Vec<D> p_before = conserve ? fluid_momentum(mass) : Vec<D>{};
  CouplingTally tally;
  accumulate_and_create(levels_, dt, counters_.next_id, tally);
  for (Level<D>& L : levels_) update_kinds(L, tally);
  sort_all();
  if (interpolate_buffers(levels_, tally, spec_.vres_buffer_fill_min) > 0) sort_all();
  if (conserve) {  // momentum.hpp: the jump dP_c of the kind changes, as a uniform velocity
    const Vec<D> dp = fluid_momentum(mass) - p_before;
    if (mass > 0.0) add_to_fluid(levels_, dp * (-1.0 / mass), true);
  }
  counters_.created += tally.created;
  counters_.deleted += tally.deleted;
  counters_.created_mass += tally.created_mass;
  counters_.deleted_mass += tally.deleted_mass;
  times_.coupling += now_seconds() - t0;
}

template <int D>
void Simulation<D>::step() {
  double dt = dt_next_;
  const bool lands = stop_time_ > t_ && t_ + dt >= stop_time_;
  if (lands) dt = stop_time_ - t_;
  ForceStats s = evaluate_forces();
  double t0 = now_seconds();
  for (Level<D>& L : levels_) predictor(L, dt);
  times_.update += now_seconds() - t0;
  sort_all();
  s.merge(evaluate_forces());
  t0 = now_seconds();
  for (Level<D>& L : levels_) corrector(L, dt);
  times_.update += now_seconds() - t0;
  counters_.particle_steps += total_particles();
  sort_all();
  if (levels_.size() > 1) couple_levels(dt);
  t0 = now_seconds();
  t_ = lands ? stop_time_ : t_ + dt;
  ++step_;
  dt_last_ = dt;
  counters_.pairs += s.pairs;
  const DtChoice c = next_dt(s);
  dt_next_ = c.dt;
  ++counters_.dt_limit_counts[static_cast<std::size_t>(c.limit)];
  for (const Level<D>& L : levels_) check_state(L);
  check_dt();
  times_.checks += now_seconds() - t0;
}

// Stops the run with a diagnosis: non-finite values, or fluid density outside [0.5, 2] rho0.
template <int D>
void Simulation<D>::check_state(const Level<D>& L) const {
  const ParticleSet<D>& ps = L.ps;
  const double rho0 = L.prm.eos.rho0;
  const auto n = static_cast<std::int64_t>(ps.size());
  auto finite = [&](std::size_t i) {
    return std::isfinite(ps.rho[i]) && std::isfinite(norm2(ps.vel[i])) &&
           std::isfinite(norm2(ps.pos[i]));
  };
  auto bad = [&](std::size_t i) {
    if (ps.kind[i] == Kind::wall) return false;
    return !finite(i) || ps.rho[i] < 0.5 * rho0 || ps.rho[i] > 2.0 * rho0;
  };
  // The lowest failing index: the same report for any thread count.
  const std::int64_t first =
      exec::first_index(n, [&](std::int64_t i) { return bad(static_cast<std::size_t>(i)); });
  if (first < n) {
    const auto i = static_cast<std::size_t>(first);
    const bool is_finite = finite(i);
    throw InstabilityError(fmt::format(
        "unstable at t = {:.6g} s, step {}: {} particle id {} at {} {} (check: {})", t_, step_,
        kind_name(ps.kind[i]), ps.id[i], position_text<D>(ps.pos[i]),
        is_finite ? fmt::format("has density {:.6g} kg/m^3 outside [{:.6g}, {:.6g}]", ps.rho[i],
                                0.5 * rho0, 2.0 * rho0)
                  : std::string("has a non-finite position, velocity or density"),
        is_finite ? "density" : "finite"));
  }
}

// Stops the run when the global dt collapsed below 0.05 h / c0 of the finest level (the level
// that sets dt; a coarser level's bound would fire on a legitimate fine-level step), naming the
// fluid particle with the largest acceleration over all levels: where to look.
template <int D>
void Simulation<D>::check_dt() const {
  double dt_min = 1e300;
  for (const Level<D>& L : levels_) dt_min = std::min(dt_min, L.prm.dt_min);
  if (dt_next_ >= dt_min) return;
  std::string culprit = "the fastest particles or largest accelerations";
  double amax = -1.0;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const ParticleSet<D>& q = levels_[l].ps;
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (q.kind[i] != Kind::fluid || norm(q.acc[i]) <= amax) continue;
      amax = norm(q.acc[i]);
      culprit = fmt::format("largest acceleration {:.3g} m/s^2 at fluid particle id {} of level {} at {}",
                            amax, q.id[i], l, position_text<D>(q.pos[i]));
    }
  }
  throw InstabilityError(fmt::format(
      "unstable at t = {:.6g} s, step {}: time step {:.3g} s fell below 0.05 h/c0 = {:.3g} s "
      "(check: dt; {})",
      t_, step_, dt_next_, dt_min, culprit));
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
