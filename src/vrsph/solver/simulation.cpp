#include "vrsph/solver/simulation.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>

#include "vrsph/physics/pair_terms.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/setup/geometry.hpp"

namespace vrsph {
namespace {

double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

// Default domain: bounding box of all particles grown by 10% of its size on each side (at least
// 4h) and by a further 50% upwards against gravity, where splashes go.
template <int D>
void default_domain(const ParticleSet<D>& ps, const Vec<D>& up, double h, Vec<D>& lo, Vec<D>& hi) {
  for (int k = 0; k < D; ++k) {
    lo[k] = 1e300;
    hi[k] = -1e300;
  }
  for (const auto& x : ps.pos) {
    for (int k = 0; k < D; ++k) {
      lo[k] = std::min(lo[k], x[k]);
      hi[k] = std::max(hi[k], x[k]);
    }
  }
  for (int k = 0; k < D; ++k) {
    const double ext = hi[k] - lo[k];
    const double m = std::max(0.1 * ext, 4.0 * h);
    lo[k] -= m + (up[k] < -0.5 ? 0.5 * ext : 0.0);
    hi[k] += m + (up[k] > 0.5 ? 0.5 * ext : 0.0);
  }
}

// Models the case format already accepts but this solver does not compute yet are refused, never
// silently skipped.
void refuse_unimplemented(const CaseSpec& spec) {
  if (!spec.refinements.empty()) {
    throw std::invalid_argument(
        "refinement: variable resolution is not implemented in this version (remove [[refinement]])");
  }
}

}  // namespace

template <int D>
Simulation<D>::Simulation(CaseSpec& spec, int cells_per_support) : spec_(spec) {
  refuse_unimplemented(spec);
  InitialSet<D> init = build_particles<D>(spec);
  ps_ = std::move(init.particles);
  setup_.fluid_height = init.fluid_height;

  prm_.dp = spec.dp;
  prm_.h = spec.h_over_dp * spec.dp;
  prm_.eta2 = 0.01 * prm_.h * prm_.h;
  prm_.kernel = WendlandC2<D>(prm_.h);
  prm_.mass = spec.density * std::pow(spec.dp, D);
  prm_.gravity = to_vec<D>(spec.gravity);
  const double g = norm(prm_.gravity);
  prm_.up = g > 0.0 ? prm_.gravity * (-1.0 / g) : Vec<D>{};

  // Speed of sound: given, or sound_speed_factor x max_speed, with max_speed = sqrt(g H) for
  // gravity cases when not given (PHYSICS.md section 2).
  if (!spec.max_speed) {
    if (g > 0.0 && setup_.fluid_height > 0.0) {
      spec.max_speed = std::sqrt(g * setup_.fluid_height);
    } else {
      double vmax = 0.0;
      for (const auto& v : ps_.vel) vmax = std::max(vmax, norm(v));
      if (vmax > 0.0) spec.max_speed = vmax;
    }
  }
  if (!spec.sound_speed && !spec.max_speed) {
    throw std::invalid_argument(
        "eos.max_speed: missing: needed to set the speed of sound when there is no gravity and no "
        "initial velocity (give eos.max_speed or eos.sound_speed)");
  }
  setup_.max_speed = spec.max_speed.value_or(0.0);
  setup_.c0 = spec.sound_speed ? *spec.sound_speed : spec.sound_speed_factor * *spec.max_speed;
  prm_.eos = TaitEos(spec.density, spec.gamma, setup_.c0);
  prm_.inv_gamma = 1.0 / spec.gamma;
  prm_.rho0_g_over_b = spec.density * g / prm_.eos.b;
  if (spec.density_diffusion == DiffusionModel::fourtakas &&
      prm_.rho0_g_over_b * prm_.kernel.support() > fourtakas_series_bound) {
    throw std::invalid_argument(fmt::format(
        "numerics.density_diffusion.model = \"fourtakas\": rho0 g 2h / B = {:.3g} exceeds {:g}: "
        "the speed of sound {:.4g} m/s is too low for this resolution (raise eos.sound_speed)",
        prm_.rho0_g_over_b * prm_.kernel.support(), fourtakas_series_bound, setup_.c0));
  }

  prm_.viscosity = spec.viscosity;
  prm_.nu = spec.viscosity == ViscosityModel::laminar ? spec.kinematic_viscosity : 0.0;
  prm_.alpha_c0_h = spec.artificial_alpha * setup_.c0 * prm_.h;
  prm_.diffusion = spec.density_diffusion;
  prm_.two_delta_h_c0 = 2.0 * spec.diffusion_delta * prm_.h * setup_.c0;
  prm_.cfl = spec.cfl;
  prm_.sigma = spec.surface_tension;
  prm_.lambda_threshold = spec.lambda_threshold;
  prm_.normal_epsilon = spec.normal_epsilon;
  prm_.shifting = {spec.shifting, spec.shifting_coefficient, spec.shifting_surface_threshold,
                   prm_.h, spec.dp};
  prm_.dt_min = 0.05 * prm_.h / setup_.c0;

  // Initial pressure of a fluid block (e.g. a droplet started at its Laplace pressure, as the
  // poster does): the density that the EOS maps to it.
  for (std::size_t i = 0; i < ps_.size(); ++i) {
    if (init.initial_pressure[i] != 0.0) ps_.rho[i] = prm_.eos.density(init.initial_pressure[i]);
  }
  if (spec.hydrostatic_initial_density && g > 0.0) {
    apply_hydrostatic_density<D>(ps_, prm_.gravity, spec.density, spec.dp, prm_.eos);
  }

  Vec<D> lo, hi;
  default_domain<D>(ps_, prm_.up, prm_.h, lo, hi);
  if (spec.domain_min) lo = to_vec<D>(*spec.domain_min);
  if (spec.domain_max) hi = to_vec<D>(*spec.domain_max);
  grid_ = CellGrid<D>(lo, hi, prm_.kernel.support(), cells_per_support);
  ps_.resize(ps_.size());
  sort_particles();
  initial_fluid_ = ps_.count(Kind::fluid);
  stop_time_ = spec.end_time;

  // First step: the acoustic limit of a fluid at rest, with the viscous and capillary limits.
  DtInputs in{prm_.h, prm_.cfl, setup_.c0, 0.0, 0.0, 0.0, prm_.nu, spec.density, prm_.sigma};
  for (const auto& v : ps_.vel) in.max_speed = std::max(in.max_speed, norm(v));
  dt_next_ = choose_dt(in).dt;
}

template <int D>
void Simulation<D>::sort_particles() {
  const double t0 = now_seconds();
  const auto lost = grid_.sort(ps_);
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
void Simulation<D>::resort() {
  ps_.resize(ps_.size());
  sort_particles();
}

template <int D>
void Simulation<D>::update_pressure() {
  ps_.p.resize(ps_.size());
  for (std::size_t i = 0; i < ps_.size(); ++i) ps_.p[i] = prm_.eos.pressure(ps_.rho[i]);
}

// Predictor (dt/2): x+ = x + dt/2 v, v+ = v + dt/2 (a + g), rho+ = rho + dt/2 drho.
// Walls keep position and velocity; their density is clamped at >= rho0 (dynamic boundary).
template <int D>
void Simulation<D>::predictor(double dt) {
  const double half = 0.5 * dt;
  const double rho0 = prm_.eos.rho0;
  const auto n = static_cast<std::int64_t>(ps_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    ps_.pos0[i] = ps_.pos[i];
    ps_.vel0[i] = ps_.vel[i];
    ps_.rho0[i] = ps_.rho[i];
    ps_.rho[i] = ps_.rho[i] + half * ps_.drho[i];
    if (ps_.kind[i] == Kind::wall) {
      ps_.rho[i] = std::max(ps_.rho[i], rho0);
      continue;
    }
    ps_.pos[i] += half * ps_.vel[i];
    ps_.vel[i] += half * (ps_.acc[i] + prm_.gravity);
  }
}

// Corrector: v' = v + dt (a+ + g), x' = x + dt (v + v')/2 + dr_shift, rho' = rho (2 - eps)/(2 + eps),
// eps = -(drho+/rho+) dt.
template <int D>
void Simulation<D>::corrector(double dt) {
  const double rho0 = prm_.eos.rho0;
  const bool shifting = prm_.shifting.model != ShiftingModel::none;
  const auto n = static_cast<std::int64_t>(ps_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const double eps = -(ps_.drho[i] / ps_.rho[i]) * dt;
    ps_.rho[i] = ps_.rho0[i] * (2.0 - eps) / (2.0 + eps);
    if (ps_.kind[i] == Kind::wall) {
      ps_.rho[i] = std::max(ps_.rho[i], rho0);
      continue;
    }
    if (shifting) {  // from the half-step sums and velocity
      ps_.shift[i] = shifting_displacement<D>(prm_.shifting, sf_.grad_c[i], sf_.div_r[i],
                                              norm(ps_.vel[i]), dt);
    }
    ps_.vel[i] = ps_.vel0[i] + dt * (ps_.acc[i] + prm_.gravity);
    ps_.pos[i] = ps_.pos0[i] + (0.5 * dt) * (ps_.vel0[i] + ps_.vel[i]) + ps_.shift[i];
  }
}

template <int D>
DtChoice Simulation<D>::next_dt(const ForceStats& a, const ForceStats& b) const {
  double vmax2 = 0.0;
  for (std::size_t i = 0; i < ps_.size(); ++i) {
    if (ps_.kind[i] != Kind::wall) vmax2 = std::max(vmax2, norm2(ps_.vel[i]));
  }
  const DtInputs in{prm_.h, prm_.cfl, setup_.c0, std::max(a.max_acc, b.max_acc),
                    std::sqrt(vmax2), std::max(a.max_visc_dt, b.max_visc_dt), prm_.nu,
                    prm_.eos.rho0, prm_.sigma};
  return choose_dt(in);
}

// One force evaluation: the surface passes (when surface tension or shifting is on), then the
// pair forces with the surface-tension acceleration added.
template <int D>
ForceStats Simulation<D>::evaluate_forces() {
  double t0 = now_seconds();
  const bool st = prm_.sigma > 0.0;
  if (st || prm_.shifting.model != ShiftingModel::none) surface_sums(prm_, ps_, grid_, sf_);
  if (st) surface_tension_force(prm_, ps_, grid_, sf_);
  times_.surface += now_seconds() - t0;
  t0 = now_seconds();
  const ForceStats s = compute_forces(prm_, ps_, grid_, force_ws_, st ? sf_.acc_st.data() : nullptr);
  times_.forces += now_seconds() - t0;
  return s;
}

template <int D>
const SurfaceFields<D>& Simulation<D>::surface_fields_now() {
  surface_sums(prm_, ps_, grid_, sf_);
  if (prm_.sigma > 0.0) surface_tension_force(prm_, ps_, grid_, sf_);
  return sf_;
}

template <int D>
void Simulation<D>::step() {
  double dt = dt_next_;
  const bool lands = stop_time_ > t_ && t_ + dt >= stop_time_;
  if (lands) dt = stop_time_ - t_;
  const ForceStats s1 = evaluate_forces();
  double t0 = now_seconds();
  t0 = now_seconds();
  predictor(dt);
  times_.update += now_seconds() - t0;
  sort_particles();
  const ForceStats s2 = evaluate_forces();
  t0 = now_seconds();
  corrector(dt);
  times_.update += now_seconds() - t0;
  counters_.particle_steps += ps_.size();
  sort_particles();
  t0 = now_seconds();
  t_ = lands ? stop_time_ : t_ + dt;
  ++step_;
  dt_last_ = dt;
  counters_.pairs += s1.pairs + s2.pairs;
  const DtChoice c = next_dt(s1, s2);
  dt_next_ = c.dt;
  ++counters_.dt_limit_counts[static_cast<std::size_t>(c.limit)];
  check_state();
  times_.checks += now_seconds() - t0;
}

// Stops the run with a diagnosis: non-finite values, fluid density outside [0.5, 2] rho0, or a
// time step collapsed below 0.05 h / c0.
template <int D>
void Simulation<D>::check_state() const {
  const double rho0 = prm_.eos.rho0;
  const auto n = static_cast<std::int64_t>(ps_.size());
  auto finite = [&](std::size_t i) {
    return std::isfinite(ps_.rho[i]) && std::isfinite(norm2(ps_.vel[i])) &&
           std::isfinite(norm2(ps_.pos[i]));
  };
  auto bad = [&](std::size_t i) {
    if (ps_.kind[i] == Kind::wall) return false;
    return !finite(i) || ps_.rho[i] < 0.5 * rho0 || ps_.rho[i] > 2.0 * rho0;
  };
  std::int64_t first = n;  // lowest failing index: the same report for any thread count
#pragma omp parallel for schedule(static) reduction(min : first)
  for (std::int64_t i = 0; i < n; ++i) {
    if (bad(static_cast<std::size_t>(i))) first = std::min(first, i);
  }
  if (first < n) {
    const auto i = static_cast<std::size_t>(first);
    const auto& x = ps_.pos[i];
    const bool is_finite = finite(i);
    std::string where = fmt::format("({:.6g}", x[0]);
    for (int k = 1; k < D; ++k) where += fmt::format(", {:.6g}", x[k]);
    where += ")";
    throw InstabilityError(fmt::format(
        "unstable at t = {:.6g} s, step {}: fluid particle id {} at {} {} (check: {})", t_, step_,
        ps_.id[i], where,
        is_finite ? fmt::format("has density {:.6g} kg/m^3 outside [{:.6g}, {:.6g}]", ps_.rho[i],
                                0.5 * rho0, 2.0 * rho0)
                  : std::string("has a non-finite position, velocity or density"),
        is_finite ? "density" : "finite"));
  }
  if (dt_next_ < prm_.dt_min) {
    throw InstabilityError(fmt::format(
        "unstable at t = {:.6g} s, step {}: time step {:.3g} s fell below 0.05 h/c0 = {:.3g} s "
        "(check: dt; limited by {})",
        t_, step_, dt_next_, prm_.dt_min, "the fastest particles or largest accelerations"));
  }
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
