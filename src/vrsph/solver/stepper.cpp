#include "vrsph/solver/stepper.hpp"

#include <cmath>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/walls.hpp"

namespace vrsph {

template <int D>
void pack_level(Level<D>& L) {
  L.cols.pack(L.ps, L.grid, L.prm.eos, L.prm.precision);
}

template <int D>
void surface_pass_sums(Level<D>& L) {
  surface_sums(L.prm, L.ps, L.grid, L.cols, L.sf);
}

template <int D>
void surface_pass_normals(Level<D>& L) {
  surface_normals(L.prm, L.ps, L.grid, L.cols, L.sf);
}

template <int D>
void surface_pass_curvature(Level<D>& L) {
  surface_curvature_force(L.prm, L.ps, L.grid, L.cols, L.sf);
}

template <int D>
void surface_pass_shifting_sums(Level<D>& L) {
  surface_sums_for_shifting(L.prm, L.ps, L.grid, L.cols, L.sf);
}

template <int D>
bool surface_pass_sums_in_forces(Level<D>& L) {
  return surface_sums_in_forces(L.prm, L.ps, L.grid, L.cols, L.sf);
}

template <int D>
ForceStats level_forces(Level<D>& L, bool capillary, bool pair_acc) {
  const Pass1InForces mode = L.sf.in_forces;
  if (pair_acc) L.pair_acc.resize(L.ps.size());
  L.sf.in_forces = Pass1InForces::none;
  const Pass1Out<D> pass1 = L.sf.pass1_out(mode == Pass1InForces::full);
  L.fluid_acc_uniform = Vec<D>{};
  return compute_forces_packed(
      L.prm, L.ps, L.grid, L.cols, capillary ? L.sf.acc_st.data() : nullptr,
      pair_acc ? L.pair_acc.data() : nullptr, mode == Pass1InForces::none ? nullptr : &pass1);
}

template <int D>
void add_capillary(Level<D>& L, ForceStats& s) {
  ParticleSet<D>& ps = L.ps;
  const std::vector<Vec<D>>& a_st = L.sf.acc_st;
  const double max_acc2 =
      exec::max_of(static_cast<std::int64_t>(ps.size()), 1024, 0.0, [&](std::int64_t i) {
        if (ps.kind[i] != Kind::fluid) return 0.0;
        ps.acc[i] += a_st[i];
        return norm2(ps.acc[i]);
      });
  s.max_acc = std::sqrt(max_acc2);
}

// Predictor (dt/2): x+ = x + dt/2 v, v+ = v + dt/2 (a + g), rho+ = rho + dt/2 drho.
// Walls keep position and velocity; their density is clamped at >= rho0 (physics/walls.hpp).
// Buffer particles move with their velocity; their v and rho are imposed (from another level,
// docs/physics.md section 10) and not integrated. v and rho at the step's start are kept for the
// corrector, x only where the level coupling reads it (ps.keeps_pos0).
template <int D>
void predictor(Level<D>& L, double dt) {
  ParticleSet<D>& ps = L.ps;
  const double half = 0.5 * dt;
  const double rho0 = L.prm.eos.rho0;
  const Vec<D> g = L.prm.gravity;
  const bool keep_x = ps.keeps_pos0;
  const bool uniform = L.fluid_acc_uniform != Vec<D>{};
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(ps.size()), [&](std::int64_t i) {
    if (keep_x) ps.pos0[i] = ps.pos[i];
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
    ps.vel[i] += half * (fluid_acceleration(L, i, uniform) + g);
  });
}

// Corrector: v' = v + dt (a+ + g), x' = x + dt (v + v')/2 + dr_shift,
// rho' = rho (2 - eps)/(2 + eps), eps = -(drho+/rho+) dt. Buffer particles: x' = x + dt v +
// dr_shift without its component along L.buffer_shift_normal; v and rho unchanged.
// x' is formed from the half-step position x+ = x + dt/2 v the predictor left:
// x' = x+ + dt/2 v' + dr_shift (fluid), x+ + dt/2 v + dr_shift (buffer), so the step's start
// position need not be kept.
template <int D>
void corrector(Level<D>& L, double dt) {
  ParticleSet<D>& ps = L.ps;
  const SolverParams<D>& prm = L.prm;
  const double rho0 = prm.eos.rho0;
  const bool shifting = prm.shifting.on();
  const bool constrained = !L.buffer_shift_normal.empty();
  const bool uniform = L.fluid_acc_uniform != Vec<D>{};
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(ps.size()), [&](std::int64_t i) {
    if (ps.kind[i] == Kind::wall) {
      const double eps = -(ps.drho[i] / ps.rho[i]) * dt;
      ps.rho[i] = wall_density(ps.rho0[i] * (2.0 - eps) / (2.0 + eps), rho0);
      return;
    }
    Vec<D> dr{};     // the shifting displacement, kept in ps.shift for the outputs
    if (shifting) {  // from the half-step sums and velocity
      dr = shifting_displacement<D>(prm.shifting, L.sf.grad_c[i], L.sf.div_r[i], norm(ps.vel[i]),
                                    dt);
      if (ps.kind[i] == Kind::buffer && constrained) {
        const Vec<D> nf = L.buffer_shift_normal[i];
        dr -= dot(dr, nf) * nf;
      }
      ps.shift[i] = dr;
    }
    if (ps.kind[i] == Kind::buffer) {
      ps.rho[i] = ps.rho0[i];
      ps.vel[i] = ps.vel0[i];
      ps.pos[i] += (0.5 * dt) * ps.vel0[i] + dr;
      return;
    }
    const double eps = -(ps.drho[i] / ps.rho[i]) * dt;
    ps.rho[i] = ps.rho0[i] * (2.0 - eps) / (2.0 + eps);
    ps.vel[i] = ps.vel0[i] + dt * (fluid_acceleration(L, i, uniform) + prm.gravity);
    ps.pos[i] += (0.5 * dt) * ps.vel[i] + dr;
  });
}

template <int D>
void damp_fluid_velocities(Level<D>& L, double factor) {
  if (factor == 1.0) return;
  ParticleSet<D>& ps = L.ps;
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(ps.size()), [&](std::int64_t i) {
    if (ps.kind[i] == Kind::fluid) ps.vel[i] *= factor;
  });
}

template <int D>
DtChoice level_dt(const Level<D>& L, const ForceStats& s, double c0) {
  const double vmax2 = exec::max_of(
      static_cast<std::int64_t>(L.ps.size()), 1024, 0.0,
      [&](std::int64_t i) { return L.ps.kind[i] != Kind::wall ? norm2(L.ps.vel[i]) : 0.0; });
  const DtInputs in{L.prm.h,
                    L.prm.cfl,
                    c0,
                    s.max_acc,
                    std::sqrt(vmax2),
                    s.max_visc_dt,
                    L.prm.viscosity.nu,
                    L.prm.eos.rho0,
                    L.prm.sigma};
  return choose_dt(in);
}

template <int D>
DtChoice level_dt_at_start(const Level<D>& L, double c0) {
  DtInputs in{L.prm.h,        L.prm.cfl,  c0, 0.0, 0.0, 0.0, L.prm.viscosity.nu,
              L.prm.eos.rho0, L.prm.sigma};
  for (const auto& v : L.ps.vel) in.max_speed = std::max(in.max_speed, norm(v));
  return choose_dt(in);
}

template <int D>
std::size_t first_unstable(const Level<D>& L) {
  const ParticleSet<D>& ps = L.ps;
  const double rho0 = L.prm.eos.rho0;
  auto bad = [&](std::int64_t ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (ps.kind[i] == Kind::wall) return false;
    return !state_is_finite(ps, i) || ps.rho[i] < 0.5 * rho0 || ps.rho[i] > 2.0 * rho0;
  };
  return static_cast<std::size_t>(exec::first_index(static_cast<std::int64_t>(ps.size()), bad));
}

template void pack_level<2>(Level<2>&);
template void pack_level<3>(Level<3>&);
template void surface_pass_sums<2>(Level<2>&);
template void surface_pass_sums<3>(Level<3>&);
template void surface_pass_shifting_sums<2>(Level<2>&);
template void surface_pass_shifting_sums<3>(Level<3>&);
template bool surface_pass_sums_in_forces<2>(Level<2>&);
template bool surface_pass_sums_in_forces<3>(Level<3>&);
template void surface_pass_normals<2>(Level<2>&);
template void surface_pass_normals<3>(Level<3>&);
template void surface_pass_curvature<2>(Level<2>&);
template void surface_pass_curvature<3>(Level<3>&);
template ForceStats level_forces<2>(Level<2>&, bool, bool);
template ForceStats level_forces<3>(Level<3>&, bool, bool);
template void add_capillary<2>(Level<2>&, ForceStats&);
template void add_capillary<3>(Level<3>&, ForceStats&);
template void predictor<2>(Level<2>&, double);
template void predictor<3>(Level<3>&, double);
template void corrector<2>(Level<2>&, double);
template void corrector<3>(Level<3>&, double);
template void damp_fluid_velocities<2>(Level<2>&, double);
template void damp_fluid_velocities<3>(Level<3>&, double);
template DtChoice level_dt<2>(const Level<2>&, const ForceStats&, double);
template DtChoice level_dt<3>(const Level<3>&, const ForceStats&, double);
template DtChoice level_dt_at_start<2>(const Level<2>&, double);
template DtChoice level_dt_at_start<3>(const Level<3>&, double);
template std::size_t first_unstable<2>(const Level<2>&);
template std::size_t first_unstable<3>(const Level<3>&);

}  // namespace vrsph
