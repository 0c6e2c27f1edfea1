#include "vrsph/solver/forces.hpp"

#include <cmath>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/particles/candidate_block.hpp"
#include "vrsph/physics/continuity.hpp"
#include "vrsph/physics/density_diffusion.hpp"
#include "vrsph/physics/pressure.hpp"
#include "vrsph/physics/viscosity.hpp"

namespace vrsph {
namespace {

// Columns of the force pass's candidate blocks: positions, velocities, then the scalars.
template <int D>
struct ForceCol {
  static constexpr int v = D, rho = 2 * D, p = rho + 1, vol = rho + 2, mass = rho + 3,
                       wall_vol = rho + 4, count = rho + 5;
};
template <int D>
using ForceBlock = CandidateBlock<ForceCol<D>::count>;
static_assert(kBlockPad % kSweepLanes == 0, "blocks must fill whole sweep lanes");

template <int D>
std::array<const double*, ForceCol<D>::count> force_sources(const LevelColumns<D>& c) {
  std::array<const double*, ForceCol<D>::count> s{};
  for (int k = 0; k < D; ++k) {
    s[k] = c.x[k].data();
    s[ForceCol<D>::v + k] = c.v[k].data();
  }
  s[ForceCol<D>::rho] = c.rho.data();
  s[ForceCol<D>::p] = c.p.data();
  s[ForceCol<D>::vol] = c.vol.data();
  s[ForceCol<D>::mass] = c.mass.data();
  s[ForceCol<D>::wall_vol] = c.wall_vol.data();
  return s;
}

// Dummies: far away, at rest, unit density (no division by zero), no volume, mass or pressure.
template <int D>
std::array<double, ForceCol<D>::count> force_pad() {
  auto pad = position_pad<ForceCol<D>::count, D>(0.0);
  pad[ForceCol<D>::rho] = 1.0;
  return pad;
}

// What one particle i reads of itself.
struct Self {
  double x[3] = {0.0, 0.0, 0.0};
  double v[3] = {0.0, 0.0, 0.0};
  double rho = 1.0, p = 0.0;
  template <int D>
  Self(const LevelColumns<D>& c, std::uint32_t i) : rho(c.rho[i]), p(c.p[i]) {
    for (int k = 0; k < D; ++k) {
      x[k] = c.x[k][i];
      v[k] = c.v[k][i];
    }
  }
};

// Sums of one particle over its blocks: drho/dt (s0), pairs (s1), acceleration (s2..s1+D; a 2D
// sweep sums no zero z component), and the viscous time-step measure (max).
struct ForceSums {
  double s[12] = {};
  double max_visc_dt = -1e300;
};

// The fluid particle i against one block: pressure, viscosity, continuity and (kWall: not with
// wall neighbours) density diffusion. Everything the body reads is a value (exec/sweep.hpp).
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall>
inline void fluid_sweep(const SolverParams<D>& prm, const Self& me, const ForceBlock<D>& blk,
                        ForceSums& out) {
  using C = ForceCol<D>;
  const double rho_i = me.rho, p_i = me.p, inv_rho_i = 1.0 / rho_i, eta2 = prm.eta2;
  const double vi0 = me.v[0], vi1 = me.v[1], vi2 = me.v[2];
  const double nu = prm.viscosity.nu, alpha_c0_h = prm.viscosity.alpha_c0_h;
  const double two_delta_h_c0 = prm.density_diffusion.two_delta_h_c0;
  const double rho0_g_over_b = prm.density_diffusion.rho0_g_over_b;
  const double inv_gamma = prm.density_diffusion.inv_gamma;
  const double up0 = prm.up[0], up1 = prm.up[1], up2 = prm.up[D - 1], rho0 = prm.eos.rho0;
  auto pair = [=](const PairGeometry& g, const Neighbour<C::count>& nb) {
    const double rho_j = nb[C::rho], vol_j = nb[C::vol], m_j = nb[C::mass];
    const double ux = vi0 - nb[C::v], uy = vi1 - nb[C::v + 1];
    const double uz = D == 3 ? vi2 - nb[C::v + D - 1] : 0.0;
    const double rij_dot_gradw = g.f * g.r2;
    const double vij_dot_rij = ux * g.rx + uy * g.ry + uz * g.rz;
    const PairReciprocals rec = pair_reciprocals(g.r2, eta2, rho_i, rho_j);
    const double inv_r2eta = rec.inv_r2eta;
    double c = pressure_pair(p_i, nb[C::p], vol_j, inv_rho_i);
    if constexpr (VM == ViscosityModel::artificial) {
      c += artificial_viscosity_pair(m_j, alpha_c0_h, vij_dot_rij, inv_r2eta, rec.inv_rho_sum);
    }
    c *= g.f;
    double ax = c * g.rx, ay = c * g.ry, az = c * g.rz;
    if constexpr (VM == ViscosityModel::laminar) {
      const double lv = laminar_viscosity_pair(m_j, nu, rij_dot_gradw, inv_r2eta, rec.inv_rho_sum);
      ax += lv * ux;
      ay += lv * uy;
      az += lv * uz;
    }
    double dr = continuity_pair(rho_i, vol_j, g.f, vij_dot_rij);
    if constexpr (!kWall && DM == DiffusionModel::molteni) {
      dr += molteni_diffusion_pair(two_delta_h_c0, vol_j, rho_i, rho_j, rij_dot_gradw, inv_r2eta);
    } else if constexpr (!kWall && DM == DiffusionModel::fourtakas) {
      const double z_ij = g.rx * up0 + g.ry * up1 + (D == 3 ? g.rz * up2 : 0.0);
      const double rho_h = hydrostatic_density_difference(rho0, rho0_g_over_b, inv_gamma, z_ij);
      dr += fourtakas_diffusion_pair(two_delta_h_c0, vol_j, rho_i, rho_j, rho_h, rij_dot_gradw,
                                     inv_r2eta);
    }
    PairSums s;  // drho/dt, pair count, acceleration, viscous dt measure
    s.s0 = dr, s.s1 = g.in, s.s2 = ax, s.s3 = ay;
    if constexpr (D == 3) s.s4 = az;
    s.max = g.in != 0.0 ? viscous_dt_measure(vij_dot_rij, inv_r2eta) : -1e300;
    return s;
  };
  sweep_pairs<D, C::count, 2 + D, true>(prm.kernel, me.x, blk.col,
                                        static_cast<std::ptrdiff_t>(blk.len), pair, out.s,
                                        out.max_visc_dt);
}

// Continuity of wall particle i over its fluid block (dynamic boundary, physics/walls.hpp).
template <int D>
inline void wall_sweep(const SolverParams<D>& prm, const Self& me, const ForceBlock<D>& blk,
                       ForceSums& out) {
  using C = ForceCol<D>;
  const double rho_i = me.rho, eta2 = prm.eta2;
  const double vi0 = me.v[0], vi1 = me.v[1], vi2 = me.v[2];
  auto pair = [=](const PairGeometry& g, const Neighbour<C::count>& nb) {
    const double ux = vi0 - nb[C::v], uy = vi1 - nb[C::v + 1];
    const double uz = D == 3 ? vi2 - nb[C::v + D - 1] : 0.0;
    const double vij_dot_rij = ux * g.rx + uy * g.ry + uz * g.rz;
    const double inv_r2eta = 1.0 / (g.r2 + eta2);
    PairSums s;
    s.s0 = continuity_pair(rho_i, nb[C::wall_vol], g.f, vij_dot_rij);
    s.s1 = g.in;
    s.max = g.in != 0.0 ? viscous_dt_measure(vij_dot_rij, inv_r2eta) : -1e300;
    return s;
  };
  sweep_pairs<D, C::count, 2, true>(prm.kernel, me.x, blk.col, static_cast<std::ptrdiff_t>(blk.len),
                                    pair, out.s, out.max_visc_dt);
}

// Per-thread scratch of the force pass and its statistics (ForceStats::merge across threads).
template <int D>
struct ForceScratch {
  ForceBlock<D> fluid, wall;
};
struct ForceAcc {
  double max_visc_dt = -1e300, max_acc2 = 0.0;
  std::uint64_t pairs = 0;
  void merge(const ForceAcc& o) {
    max_visc_dt = std::max(max_visc_dt, o.max_visc_dt);
    max_acc2 = std::max(max_acc2, o.max_acc2);
    pairs += o.pairs;
  }
};

template <int D>
Vec<D> acceleration(const ForceSums& s) {
  Vec<D> a;
  for (int k = 0; k < D; ++k) a[k] = s.s[2 + k];
  return a;
}

template <int D, ViscosityModel VM, DiffusionModel DM>
ForceStats force_pass(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                      const LevelColumns<D>& cols, const Vec<D>* extra_acc, bool buffer_reaction) {
  const auto& cells = grid.particle_cells();
  const auto src = force_sources(cols);
  const auto pad = force_pad<D>();
  auto body = [&](std::int64_t ii, ForceScratch<D>& scratch, ForceAcc& acc) {
    const auto i = static_cast<std::uint32_t>(ii);
    const Self me(cols, i);
    ForceSums s;
    scratch.fluid.gather(src, pad, grid, cells[i], Groups::fluid);
    if (ps.kind[i] == Kind::buffer) {
      // v and rho come from another level: acc is only the reaction of this level's fluid and
      // buffer neighbours (walls left out), from which the coupling measures the net force the
      // buffer exerts on the fluid. Buffer-buffer pairs cancel in that sum.
      if (buffer_reaction) fluid_sweep<D, VM, DM, false>(prm, me, scratch.fluid, s);
      ps.acc[i] = acceleration<D>(s);
      ps.drho[i] = 0.0;
      return;
    }
    if (ps.kind[i] == Kind::wall) {
      wall_sweep(prm, me, scratch.fluid, s);
    } else {
      fluid_sweep<D, VM, DM, false>(prm, me, scratch.fluid, s);
      scratch.wall.gather(src, pad, grid, cells[i], Groups::wall);
      fluid_sweep<D, VM, DM, true>(prm, me, scratch.wall, s);
    }
    Vec<D> a = acceleration<D>(s);
    if (extra_acc != nullptr && ps.kind[i] != Kind::wall) a += extra_acc[i];
    ps.acc[i] = a;
    ps.drho[i] = s.s[0];
    if (ps.kind[i] != Kind::wall) acc.max_acc2 = std::max(acc.max_acc2, norm2(a));
    acc.max_visc_dt = std::max(acc.max_visc_dt, s.max_visc_dt);
    acc.pairs += static_cast<std::uint64_t>(s.s[1]);
  };
  const ForceAcc total = exec::for_each_gather<ForceScratch<D>, ForceAcc>(
      static_cast<std::int64_t>(ps.size()), 512, body);
  return {total.max_visc_dt, std::sqrt(total.max_acc2), total.pairs};
}

template <int D, ViscosityModel VM>
ForceStats dispatch_diffusion(const SolverParams<D>& prm, ParticleSet<D>& ps,
                              const CellGrid<D>& grid, const LevelColumns<D>& cols,
                              const Vec<D>* extra, bool br) {
  switch (prm.density_diffusion.model) {
    case DiffusionModel::none:
      return force_pass<D, VM, DiffusionModel::none>(prm, ps, grid, cols, extra, br);
    case DiffusionModel::molteni:
      return force_pass<D, VM, DiffusionModel::molteni>(prm, ps, grid, cols, extra, br);
    case DiffusionModel::fourtakas:
      return force_pass<D, VM, DiffusionModel::fourtakas>(prm, ps, grid, cols, extra, br);
  }
  return {};
}

}  // namespace

template <int D>
ForceStats compute_forces_packed(const SolverParams<D>& prm, ParticleSet<D>& ps,
                                 const CellGrid<D>& grid, const LevelColumns<D>& cols,
                                 const Vec<D>* extra_acc, bool buffer_reaction) {
  ps.acc.resize(ps.size());
  ps.drho.resize(ps.size());
  if (prm.viscosity.model == ViscosityModel::laminar) {
    return dispatch_diffusion<D, ViscosityModel::laminar>(prm, ps, grid, cols, extra_acc,
                                                          buffer_reaction);
  }
  return dispatch_diffusion<D, ViscosityModel::artificial>(prm, ps, grid, cols, extra_acc,
                                                           buffer_reaction);
}

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                          ForceWorkspace<D>& ws, const Vec<D>* extra_acc, bool buffer_reaction) {
  ws.pack(ps, prm.eos);
  return compute_forces_packed(prm, ps, grid, ws, extra_acc, buffer_reaction);
}

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid) {
  ForceWorkspace<D> ws;
  return compute_forces(prm, ps, grid, ws);
}

template ForceStats compute_forces_packed<2>(const SolverParams<2>&, ParticleSet<2>&,
                                             const CellGrid<2>&, const LevelColumns<2>&,
                                             const Vec<2>*, bool);
template ForceStats compute_forces_packed<3>(const SolverParams<3>&, ParticleSet<3>&,
                                             const CellGrid<3>&, const LevelColumns<3>&,
                                             const Vec<3>*, bool);
template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&);
template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&,
                                      ForceWorkspace<2>&, const Vec<2>*, bool);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&,
                                      ForceWorkspace<3>&, const Vec<3>*, bool);

}  // namespace vrsph
