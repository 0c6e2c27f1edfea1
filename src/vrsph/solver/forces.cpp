#include "vrsph/solver/forces.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/particles/run_columns.hpp"
#include "vrsph/physics/continuity.hpp"
#include "vrsph/physics/density_diffusion.hpp"
#include "vrsph/physics/pressure.hpp"
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
// sweep sums no zero z component), then the first kSurf terms of surface pass 1
// (solver/pass1_terms.hpp) from s2+D, and the viscous time-step measure (max).
struct ForceSums {
  double s[12] = {};
  double max_visc_dt = -1e300;
};

// The fluid particle i against one block: pressure, viscosity, continuity and (kWall: not with
// wall neighbours) density diffusion; also the first kSurf terms of surface pass 1 on the same
// geometry (solver/pass1_terms.hpp). Everything the body reads is a value (exec/sweep.hpp).
// T: the arithmetic of the pair terms (core/precision.hpp). Densities arrive as deviations
// rho - rho0 (LevelColumns): rho = rho0 + deviation, exact in double.
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall, int kSurf, class T>
inline auto fluid_pair(const SolverParams<D>& prm, const Self<T>& me) {
  using C = ForceCol<D>;
  const T rho0 = static_cast<T>(prm.eos.rho0);
  const T rho_dev_i = me.rho_dev, rho_i = rho0 + rho_dev_i, p_i = me.p;
  const T inv_rho_i = T(1) / rho_i, eta2 = static_cast<T>(prm.eta2);
  const T vi0 = me.v[0], vi1 = me.v[1], vi2 = me.v[2];
  const T nu = static_cast<T>(prm.viscosity.nu);
  const T alpha_c0_h = static_cast<T>(prm.viscosity.alpha_c0_h);
  const T two_delta_h_c0 = static_cast<T>(prm.density_diffusion.two_delta_h_c0);
  const HydrostaticSeries<T> rho_h_of(prm.density_diffusion.hydrostatic);
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
      const T rho_h = rho_h_of(z_ij);
      dr += fourtakas_diffusion_pair(two_delta_h_c0, vol_j, rho_i_minus_j, rho_h, rij_dot_gradw,
                                     inv_r2eta);
    }
    PairSumsT<T> s;  // drho/dt, pair count, acceleration, viscous dt measure
    s.s0 = dr, s.s1 = g.in, s.s2 = ax, s.s3 = ay;
    if constexpr (D == 3) s.s4 = az;
    if constexpr (kSurf > 0) set_pass1_terms<D, kSurf, 2 + D>(g, vol_j, s);
    s.max = g.in != T(0) ? viscous_dt_measure(vij_dot_rij, inv_r2eta) : PairSumsT<T>::lowest();
    return s;
  };
  return pair;
}
template <int D, int kSurf>
inline constexpr int kForceSums = 2 + D + kSurf;
// The fluid particle i against the spans of its stencil in the state columns st.
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall, int kSurf, class T>
inline void fluid_sweep(const SolverParams<D>& prm, const Self<T>& me, const StateRuns<D, T>& st,
                        const Span* spans, int count, ForceSums& out) {
  constexpr int K = kStateCols<D, T>;
  sweep_spans<D, K, kForceSums<D, kSurf>, true, StateRuns<D, T>::kLo>(
      prm.kernel, me.x, st.base, spans, count, fluid_pair<D, VM, DM, kWall, kSurf>(prm, me), out.s,
      out.max_visc_dt, me.x_lo);
}
// The same as a function of its own, for the sweeps that carry all of pass 1: inlined into the
// pass's body, the 12 sums of the fluid and the wall sweeps spilled to the stack (the joined sweep
// took 1.24x the samples of two separate passes in float; apart, 0.9x: docs/validation.md).
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall, int kSurf, class T>
[[gnu::noinline]] void fluid_sweep_apart(const SolverParams<D>& prm, const Self<T>& me,
                                         const StateRuns<D, T>& st, const Span* spans, int count,
                                         ForceSums& out) {
  fluid_sweep<D, VM, DM, kWall, kSurf>(prm, me, st, spans, count, out);
}
// fluid_sweep, apart where it carries more than shifting's terms.
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall, int kSurf, class T>
inline void fluid_sweep_for(const SolverParams<D>& prm, const Self<T>& me,
                            const StateRuns<D, T>& st, const Span* spans, int count,
                            ForceSums& out) {
  if constexpr (kSurf > kShiftingTerms<D>)
    fluid_sweep_apart<D, VM, DM, kWall, kSurf>(prm, me, st, spans, count, out);
  else
    fluid_sweep<D, VM, DM, kWall, kSurf>(prm, me, st, spans, count, out);
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

// The arguments of one force pass (compute_forces_packed).
template <int D>
struct ForceCall {
  const SolverParams<D>& prm;
  ParticleSet<D>& ps;
  const CellGrid<D>& grid;
  const LevelColumns<D>& cols;
  const Vec<D>* extra_acc;
  Vec<D>* pair_acc;
  const Pass1Out<D>* pass1;
};

template <int D, ViscosityModel VM, DiffusionModel DM, class T, int kSurf>
ForceStats force_pass(const ForceCall<D>& call) {
  const auto& [prm, ps, grid, cols, extra_acc, pair_acc, pass1] = call;
  if (grid.reach() > 4) throw std::invalid_argument("force pass: more than 4 cells per support");
  const auto& cells = grid.particle_cells();
  const StateRuns<D, T>& st = cols.template state_of<T>();
  const double w0 = prm.kernel.w(0.0);
  auto body = [&](std::int64_t ii, ForceScratch<D>& sc, ForceAcc& acc) {
    const auto i = static_cast<std::uint32_t>(ii);
    const Self<T> me(st, i);
    ForceSums s;
    if (ps.kind[i] == Kind::buffer) {  // v and rho come from another level: nothing to sum
      ps.acc[i] = Vec<D>{};
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
      fluid_sweep_for<D, VM, DM, false, kSurf>(prm, me, st, sc.fluid.span, sc.fluid.count, s);
      if (pair_acc != nullptr) pair_acc[i] = acceleration<D>(s);  // fluid and buffer neighbours
      fluid_sweep_for<D, VM, DM, true, kSurf>(prm, me, st, sc.wall.span, sc.wall.count, s);
      if constexpr (kSurf > 0) pass1->store(i, s.s + 2 + D, shepard_self(ps, cols, i, w0));
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

// The models and the pass-1 terms as template parameters, chosen once per call.
template <int D, ViscosityModel VM, class T, int kSurf>
ForceStats dispatch_diffusion(const ForceCall<D>& call) {
  switch (call.prm.density_diffusion.model) {
    case DiffusionModel::none:
      return force_pass<D, VM, DiffusionModel::none, T, kSurf>(call);
    case DiffusionModel::molteni:
      return force_pass<D, VM, DiffusionModel::molteni, T, kSurf>(call);
    case DiffusionModel::fourtakas:
      return force_pass<D, VM, DiffusionModel::fourtakas, T, kSurf>(call);
  }
  return {};
}

template <int D, class T, int kSurf>
ForceStats dispatch_viscosity(const ForceCall<D>& call) {
  if (call.prm.viscosity.model == ViscosityModel::laminar)
    return dispatch_diffusion<D, ViscosityModel::laminar, T, kSurf>(call);
  return dispatch_diffusion<D, ViscosityModel::artificial, T, kSurf>(call);
}

template <int D, class T>
ForceStats dispatch_pass1(const ForceCall<D>& call) {
  const int terms = call.pass1 == nullptr ? 0 : call.pass1->terms;
  if (terms == 0) return dispatch_viscosity<D, T, 0>(call);
  if (terms == kShiftingTerms<D>) return dispatch_viscosity<D, T, kShiftingTerms<D>>(call);
  if constexpr (kForcePassSumsPass1<D>) {
    if (terms == kPass1Terms<D, true>) return dispatch_viscosity<D, T, kPass1Terms<D, true>>(call);
  }
  throw std::invalid_argument("force pass: cannot sum " + std::to_string(terms) +
                              " terms of surface pass 1");
}

}  // namespace

template <int D>
ForceStats compute_forces_packed(const SolverParams<D>& prm, ParticleSet<D>& ps,
                                 const CellGrid<D>& grid, const LevelColumns<D>& cols,
                                 const Vec<D>* extra_acc, Vec<D>* pair_acc,
                                 const Pass1Out<D>* pass1) {
  ps.acc.resize(ps.size());
  ps.drho.resize(ps.size());
  const ForceCall<D> call{prm, ps, grid, cols, extra_acc, pair_acc, pass1};
  return with_pair_type(prm.precision,
                        [&](auto t) { return dispatch_pass1<D, decltype(t)>(call); });
}

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                          ForceWorkspace<D>& ws, const Vec<D>* extra_acc, Vec<D>* pair_acc) {
  ws.pack(ps, grid, prm.eos, prm.precision);
  return compute_forces_packed(prm, ps, grid, ws, extra_acc, pair_acc);
}

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid) {
  ForceWorkspace<D> ws;
  return compute_forces(prm, ps, grid, ws);
}

template ForceStats compute_forces_packed<2>(const SolverParams<2>&, ParticleSet<2>&,
                                             const CellGrid<2>&, const LevelColumns<2>&,
                                             const Vec<2>*, Vec<2>*, const Pass1Out<2>*);
template ForceStats compute_forces_packed<3>(const SolverParams<3>&, ParticleSet<3>&,
                                             const CellGrid<3>&, const LevelColumns<3>&,
                                             const Vec<3>*, Vec<3>*, const Pass1Out<3>*);
template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&);
template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&,
                                      ForceWorkspace<2>&, const Vec<2>*, Vec<2>*);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&,
                                      ForceWorkspace<3>&, const Vec<3>*, Vec<3>*);

}  // namespace vrsph
