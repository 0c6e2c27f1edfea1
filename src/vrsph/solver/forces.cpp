#include "vrsph/solver/forces.hpp"

#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/particles/run_columns.hpp"
#include "vrsph/physics/continuity.hpp"
#include "vrsph/physics/density_diffusion.hpp"
#include "vrsph/physics/pressure.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/viscosity.hpp"

namespace vrsph {
namespace {

template <int D>
using ForceCol = StateCol<D>;
static_assert(kBlockPad % kSweepLanes == 0, "spans must fill whole sweep lanes");

// What one particle i reads of itself, from the state columns of type T: its position in their
// frame (hi + lo), the rest as stored.
template <class T>
struct Self {
  T x[3] = {0, 0, 0}, x_lo[3] = {0, 0, 0};
  T v[3] = {0, 0, 0};
  T rho_dev = 0, p = 0;
  template <int D>
  Self(const StateRuns<D, T>& st, std::uint32_t i) {
    using C = ForceCol<D>;
    st.self(i, x, x_lo);
    for (int k = 0; k < D; ++k) v[k] = st.col[C::v + k][i];
    rho_dev = st.col[C::rho][i], p = st.col[C::p][i];
  }
};

// Sums of one particle over its spans: drho/dt (s0), pairs (s1), acceleration (s2..s1+D; a 2D
// sweep sums no zero z component), with kShift shifting's grad C (s2+D..s1+2D) and div r
// (s2+2D), and the viscous time-step measure (max).
struct ForceSums {
  double s[12] = {};
  double max_visc_dt = -1e300;
};

// Shifting's pair terms (physics/shifting.hpp) in the slots after the acceleration: grad C, div r.
template <int D, class T>
[[gnu::always_inline]] inline void add_shifting_pair(const PairGeometryT<T>& g, T vol_j,
                                                     PairSumsT<T>& s) {
  const T vf = vol_j * g.f;
  if constexpr (D == 2) {
    s.s4 = colour_gradient_pair(vf, g.rx);
    s.s5 = colour_gradient_pair(vf, g.ry);
    s.s6 = position_divergence_pair(vf, g.r2);
  } else {
    s.s5 = colour_gradient_pair(vf, g.rx);
    s.s6 = colour_gradient_pair(vf, g.ry);
    s.s7 = colour_gradient_pair(vf, g.rz);
    s.s8 = position_divergence_pair(vf, g.r2);
  }
}

// The fluid particle i against one block: pressure, viscosity, continuity and (kWall: not with
// wall neighbours) density diffusion; kShift: also shifting's grad C and div r, the terms of
// surface pass 1 (solver/surface_pass.cpp) on the same geometry. Everything the body reads is a
// value (exec/sweep.hpp).
// T: the arithmetic of the pair terms (core/precision.hpp). Densities arrive as deviations
// rho - rho0 (LevelColumns): rho = rho0 + deviation, exact in double.
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall, bool kShift, class T>
inline auto fluid_pair(const SolverParams<D>& prm, const Self<T>& me) {
  using C = ForceCol<D>;
  const T rho0 = static_cast<T>(prm.eos.rho0);
  const T rho_dev_i = me.rho_dev, rho_i = rho0 + rho_dev_i, p_i = me.p;
  const T inv_rho_i = T(1) / rho_i, eta2 = static_cast<T>(prm.eta2);
  const T vi0 = me.v[0], vi1 = me.v[1], vi2 = me.v[2];
  const T nu = static_cast<T>(prm.viscosity.nu);
  const T alpha_c0_h = static_cast<T>(prm.viscosity.alpha_c0_h);
  const T two_delta_h_c0 = static_cast<T>(prm.density_diffusion.two_delta_h_c0);
  const T rho0_g_over_b = static_cast<T>(prm.density_diffusion.rho0_g_over_b);
  const T inv_gamma = static_cast<T>(prm.density_diffusion.inv_gamma);
  const T up0 = static_cast<T>(prm.up[0]), up1 = static_cast<T>(prm.up[1]);
  const T up2 = static_cast<T>(prm.up[D - 1]);
  auto pair = [=](const PairGeometryT<T>& g, const Neighbour<kStateCols<D, T>, T>& nb) {
    const T rho_dev_j = nb[C::rho], rho_j = rho0 + rho_dev_j, vol_j = nb[C::vol];
    // the weighted mass omega_j m_j = V_j rho_j (solver/columns.hpp): no column of its own
    const T m_j = vol_j * rho_j, rho_i_minus_j = rho_dev_i - rho_dev_j;
    const T ux = vi0 - nb[C::v], uy = vi1 - nb[C::v + 1];
    const T uz = D == 3 ? vi2 - nb[C::v + D - 1] : T(0);
    const T rij_dot_gradw = g.f * g.r2;
    const T vij_dot_rij = ux * g.rx + uy * g.ry + uz * g.rz;
    const PairReciprocals<T> rec = pair_reciprocals(g.r2, eta2, rho_i, rho_j);
    const T inv_r2eta = rec.inv_r2eta;
    T c = pressure_pair(p_i, nb[C::p], vol_j, inv_rho_i);
    if constexpr (VM == ViscosityModel::artificial) {
      c += artificial_viscosity_pair(m_j, alpha_c0_h, vij_dot_rij, inv_r2eta, rec.inv_rho_sum);
    }
    c *= g.f;
    T ax = c * g.rx, ay = c * g.ry, az = c * g.rz;
    if constexpr (VM == ViscosityModel::laminar) {
      const T lv = laminar_viscosity_pair(m_j, nu, rij_dot_gradw, inv_r2eta, rec.inv_rho_sum);
      ax += lv * ux;
      ay += lv * uy;
      az += lv * uz;
    }
    T dr = continuity_pair(rho_i, vol_j, g.f, vij_dot_rij);
    if constexpr (!kWall && DM == DiffusionModel::molteni) {
      dr += molteni_diffusion_pair(two_delta_h_c0, vol_j, rho_i_minus_j, rij_dot_gradw, inv_r2eta);
    } else if constexpr (!kWall && DM == DiffusionModel::fourtakas) {
      // Selected to 0 outside the support: the series of a dummy's z (1e15 m) overflows float.
      const T z = g.rx * up0 + g.ry * up1 + (D == 3 ? g.rz * up2 : T(0));
      const T z_ij = g.in != T(0) ? z : T(0);
      const T rho_h = hydrostatic_density_difference(rho0, rho0_g_over_b, inv_gamma, z_ij);
      dr += fourtakas_diffusion_pair(two_delta_h_c0, vol_j, rho_i_minus_j, rho_h, rij_dot_gradw,
                                     inv_r2eta);
    }
    PairSumsT<T> s;  // drho/dt, pair count, acceleration, viscous dt measure
    s.s0 = dr, s.s1 = g.in, s.s2 = ax, s.s3 = ay;
    if constexpr (D == 3) s.s4 = az;
    if constexpr (kShift) add_shifting_pair<D>(g, vol_j, s);
    s.max = g.in != T(0) ? viscous_dt_measure(vij_dot_rij, inv_r2eta) : PairSumsT<T>::lowest();
    return s;
  };
  return pair;
}
template <int D, bool kShift>
inline constexpr int kForceSums = 2 + D + (kShift ? D + 1 : 0);
// The fluid particle i against the spans of its stencil in the state columns st.
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall, bool kShift, class T>
inline void fluid_sweep(const SolverParams<D>& prm, const Self<T>& me, const StateRuns<D, T>& st,
                        const Span* spans, int count, ForceSums& out) {
  constexpr int K = kStateCols<D, T>;
  sweep_spans<D, K, kForceSums<D, kShift>, true, StateRuns<D, T>::kLo>(
      prm.kernel, me.x, st.base, spans, count, fluid_pair<D, VM, DM, kWall, kShift>(prm, me), out.s,
      out.max_visc_dt, me.x_lo);
}

// Continuity of wall particle i over its fluid block (dynamic boundary, physics/walls.hpp).
// kVol: the block column of the neighbours' volume, ForceCol::wall_vol where buffer particles
// are present (their volume is 0 there), else ForceCol::vol.
template <int D, int kVol, class T>
inline auto wall_pair(const SolverParams<D>& prm, const Self<T>& me) {
  using C = ForceCol<D>;
  const T rho_i = static_cast<T>(prm.eos.rho0) + me.rho_dev, eta2 = static_cast<T>(prm.eta2);
  const T vi0 = me.v[0], vi1 = me.v[1], vi2 = me.v[2];
  auto pair = [=](const PairGeometryT<T>& g, const Neighbour<kStateCols<D, T>, T>& nb) {
    const T ux = vi0 - nb[C::v], uy = vi1 - nb[C::v + 1];
    const T uz = D == 3 ? vi2 - nb[C::v + D - 1] : T(0);
    const T vij_dot_rij = ux * g.rx + uy * g.ry + uz * g.rz;
    const T inv_r2eta = T(1) / (g.r2 + eta2);
    PairSumsT<T> s;
    s.s0 = continuity_pair(rho_i, nb[kVol], g.f, vij_dot_rij);
    s.s1 = g.in;
    s.max = g.in != T(0) ? viscous_dt_measure(vij_dot_rij, inv_r2eta) : PairSumsT<T>::lowest();
    return s;
  };
  return pair;
}
template <int D, int kVol, class T>
inline void wall_sweep(const SolverParams<D>& prm, const Self<T>& me, const StateRuns<D, T>& st,
                       const Span* spans, int count, ForceSums& out) {
  constexpr int K = kStateCols<D, T>;
  sweep_spans<D, K, 2, true, StateRuns<D, T>::kLo>(prm.kernel, me.x, st.base, spans, count,
                                                   wall_pair<D, kVol>(prm, me), out.s,
                                                   out.max_visc_dt, me.x_lo);
}

// Per-thread scratch of the force pass: the spans of the cell last asked for (particles are
// sorted by cell, so consecutive particles share them).
template <int D>
struct ForceScratch {
  StencilSpans<D> fluid, wall;
  void spans_of(const CellGrid<D>& grid, std::int64_t c) {
    fluid.of(grid, c, Groups::fluid);
    wall.of(grid, c, Groups::wall);
  }
};
// Statistics of the pass (ForceStats::merge across threads).
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

template <int D, ViscosityModel VM, DiffusionModel DM, class T, bool kShift>
ForceStats force_pass(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                      const LevelColumns<D>& cols, const Vec<D>* extra_acc, bool buffer_reaction,
                      const ShiftingSums<D>& shift) {
  if (grid.reach() > 4) throw std::invalid_argument("force pass: more than 4 cells per support");
  const auto& cells = grid.particle_cells();
  const StateRuns<D, T>& st = cols.template state_of<T>();
  auto body = [&](std::int64_t ii, ForceScratch<D>& sc, ForceAcc& acc) {
    const auto i = static_cast<std::uint32_t>(ii);
    const Self<T> me(st, i);
    ForceSums s;
    if (ps.kind[i] == Kind::buffer) {
      // v and rho come from another level: acc is only the reaction of this level's fluid and
      // buffer neighbours (walls left out), from which the coupling measures the net force the
      // buffer exerts on the fluid. Buffer-buffer pairs cancel in that sum. Without it
      // (buffer_reaction false) a buffer particle needs no neighbour at all.
      if (buffer_reaction) {
        sc.spans_of(grid, cells[i]);
        fluid_sweep<D, VM, DM, false, false>(prm, me, st, sc.fluid.span, sc.fluid.count, s);
      }
      ps.acc[i] = acceleration<D>(s);
      ps.drho[i] = 0.0;
      return;
    }
    sc.spans_of(grid, cells[i]);
    if (ps.kind[i] == Kind::wall) {
      if (cols.has_wall_vol)
        wall_sweep<D, ForceCol<D>::wall_vol>(prm, me, st, sc.fluid.span, sc.fluid.count, s);
      else
        wall_sweep<D, ForceCol<D>::vol>(prm, me, st, sc.fluid.span, sc.fluid.count, s);
    } else {
      fluid_sweep<D, VM, DM, false, kShift>(prm, me, st, sc.fluid.span, sc.fluid.count, s);
      fluid_sweep<D, VM, DM, true, kShift>(prm, me, st, sc.wall.span, sc.wall.count, s);
      if constexpr (kShift) {
        for (int k = 0; k < D; ++k) shift.grad_c[i][k] = s.s[2 + D + k];
        shift.div_r[i] = s.s[2 + 2 * D];
      }
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

template <int D, ViscosityModel VM, class T, bool kShift>
ForceStats dispatch_diffusion(const SolverParams<D>& prm, ParticleSet<D>& ps,
                              const CellGrid<D>& grid, const LevelColumns<D>& cols,
                              const Vec<D>* extra, bool br, const ShiftingSums<D>& sh) {
  switch (prm.density_diffusion.model) {
    case DiffusionModel::none:
      return force_pass<D, VM, DiffusionModel::none, T, kShift>(prm, ps, grid, cols, extra, br, sh);
    case DiffusionModel::molteni:
      return force_pass<D, VM, DiffusionModel::molteni, T, kShift>(prm, ps, grid, cols, extra, br,
                                                                   sh);
    case DiffusionModel::fourtakas:
      return force_pass<D, VM, DiffusionModel::fourtakas, T, kShift>(prm, ps, grid, cols, extra, br,
                                                                     sh);
  }
  return {};
}

template <int D, class T, bool kShift>
ForceStats dispatch_viscosity(const SolverParams<D>& prm, ParticleSet<D>& ps,
                              const CellGrid<D>& grid, const LevelColumns<D>& cols,
                              const Vec<D>* extra, bool br, const ShiftingSums<D>& sh) {
  if (prm.viscosity.model == ViscosityModel::laminar)
    return dispatch_diffusion<D, ViscosityModel::laminar, T, kShift>(prm, ps, grid, cols, extra, br,
                                                                     sh);
  return dispatch_diffusion<D, ViscosityModel::artificial, T, kShift>(prm, ps, grid, cols, extra,
                                                                      br, sh);
}

}  // namespace

template <int D>
ForceStats compute_forces_packed(const SolverParams<D>& prm, ParticleSet<D>& ps,
                                 const CellGrid<D>& grid, const LevelColumns<D>& cols,
                                 const Vec<D>* extra_acc, bool buffer_reaction,
                                 const ShiftingSums<D>* shift) {
  ps.acc.resize(ps.size());
  ps.drho.resize(ps.size());
  return with_pair_type(prm.precision, [&](auto t) {
    using T = decltype(t);
    if (shift != nullptr)
      return dispatch_viscosity<D, T, true>(prm, ps, grid, cols, extra_acc, buffer_reaction,
                                            *shift);
    return dispatch_viscosity<D, T, false>(prm, ps, grid, cols, extra_acc, buffer_reaction,
                                           ShiftingSums<D>{});
  });
}

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                          ForceWorkspace<D>& ws, const Vec<D>* extra_acc, bool buffer_reaction) {
  ws.pack(ps, grid, prm.eos, prm.precision);
  return compute_forces_packed(prm, ps, grid, ws, extra_acc, buffer_reaction);
}

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid) {
  ForceWorkspace<D> ws;
  return compute_forces(prm, ps, grid, ws);
}

template ForceStats compute_forces_packed<2>(const SolverParams<2>&, ParticleSet<2>&,
                                             const CellGrid<2>&, const LevelColumns<2>&,
                                             const Vec<2>*, bool, const ShiftingSums<2>*);
template ForceStats compute_forces_packed<3>(const SolverParams<3>&, ParticleSet<3>&,
                                             const CellGrid<3>&, const LevelColumns<3>&,
                                             const Vec<3>*, bool, const ShiftingSums<3>*);
template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&);
template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&,
                                      ForceWorkspace<2>&, const Vec<2>*, bool);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&,
                                      ForceWorkspace<3>&, const Vec<3>*, bool);

}  // namespace vrsph
