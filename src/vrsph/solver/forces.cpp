#include "vrsph/solver/forces.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "vrsph/physics/pair_terms.hpp"

namespace vrsph {
namespace {

// Candidates of one cell's particles, copied from the runs of the cell stencil into one
// contiguous block padded to a multiple of kPad with inert dummies (far away, zero volume and
// mass), so that every particle of the cell sweeps a single vector loop with no remainder.
// All particles of a cell share the block: the copy is amortised over them.
constexpr std::size_t kPad = 8;

template <int D>
struct Candidates {
  NeighbourArrays<D> a;
  std::size_t len = 0;          // padded length
  std::int64_t cell = -1;       // cell the block was gathered for
  Group group = Group::fluid;

  void gather(const NeighbourArrays<D>& nb, const CellGrid<D>& grid, std::int64_t c, Group g) {
    if (c == cell && g == group) return;
    cell = c;
    group = g;
    std::size_t n = 0;
    grid.for_each_run(c, g, [&](std::uint32_t b, std::uint32_t e) { n += e - b; });
    len = (n + kPad - 1) / kPad * kPad;
    if (a.rho.size() < len) grow(len);
    std::size_t k = 0;
    grid.for_each_run(c, g, [&](std::uint32_t b, std::uint32_t e) {
      for (int d = 0; d < D; ++d) {
        std::copy(nb.x[d].begin() + b, nb.x[d].begin() + e, a.x[d].begin() + k);
        std::copy(nb.v[d].begin() + b, nb.v[d].begin() + e, a.v[d].begin() + k);
      }
      std::copy(nb.rho.begin() + b, nb.rho.begin() + e, a.rho.begin() + k);
      std::copy(nb.p.begin() + b, nb.p.begin() + e, a.p.begin() + k);
      std::copy(nb.vol.begin() + b, nb.vol.begin() + e, a.vol.begin() + k);
      std::copy(nb.mass.begin() + b, nb.mass.begin() + e, a.mass.begin() + k);
      std::copy(nb.wall_vol.begin() + b, nb.wall_vol.begin() + e, a.wall_vol.begin() + k);
      k += e - b;
    });
    for (; k < len; ++k) {  // dummies: outside every support, and zero in every term
      for (int d = 0; d < D; ++d) {
        a.x[d][k] = 1e15;
        a.v[d][k] = 0.0;
      }
      a.rho[k] = 1.0;
      a.p[k] = 0.0;
      a.vol[k] = 0.0;
      a.mass[k] = 0.0;
      a.wall_vol[k] = 0.0;
    }
  }

  void grow(std::size_t n) {
    for (int d = 0; d < D; ++d) {
      a.x[d].resize(n);
      a.v[d].resize(n);
    }
    a.rho.resize(n);
    a.p.resize(n);
    a.vol.resize(n);
    a.mass.resize(n);
    a.wall_vol.resize(n);
  }
};

// Raw pointers into a candidate block, read by the vector loops.
template <int D>
struct BlockView {
  const double *x0, *x1, *x2, *v0, *v1, *v2, *rho, *p, *vol, *mass, *wall_vol;
  std::ptrdiff_t len;
  explicit BlockView(const Candidates<D>& cand)
      : x0(cand.a.x[0].data()), x1(cand.a.x[1].data()), x2(cand.a.x[D - 1].data()),
        v0(cand.a.v[0].data()), v1(cand.a.v[1].data()), v2(cand.a.v[D - 1].data()),
        rho(cand.a.rho.data()), p(cand.a.p.data()), vol(cand.a.vol.data()),
        mass(cand.a.mass.data()), wall_vol(cand.a.wall_vol.data()),
        len(static_cast<std::ptrdiff_t>(cand.len)) {}
};

// Position and velocity of particle i, padded to 3 components.
template <int D>
struct SelfState {
  double x[3] = {0.0, 0.0, 0.0};
  double v[3] = {0.0, 0.0, 0.0};
  SelfState(const NeighbourArrays<D>& nb, std::uint32_t i) {
    for (int k = 0; k < D; ++k) {
      x[k] = nb.x[k][i];
      v[k] = nb.v[k][i];
    }
  }
};

// Running sums of one particle i (scalars, so `omp simd` can reduce them).
struct Accum {
  double acc[3] = {0.0, 0.0, 0.0};
  double drho = 0.0;
  double max_visc_dt = -1e300;
  std::uint64_t pairs = 0;
};

// Sums the pair terms of fluid particle i over its candidate block. Candidates outside the support
// (and i itself, r = 0) get a zero kernel factor instead of a branch, so the loop vectorises.
// kWall: the run holds wall particles, which take no part in density diffusion (as DualSPHysics'
// Fourtakas "full" variant). kSeries: the Fourtakas hydrostatic term may use its series form.
template <int D, ViscosityModel VM, DiffusionModel DM, bool kWall>
inline void fluid_run(const SolverParams<D>& prm, const NeighbourArrays<D>& nb, std::uint32_t i,
                      const Candidates<D>& cand, Accum& a) {
  const SelfState<D> self(nb, i);
  const double *xi = self.x, *vi = self.v;
  const double rho_i = nb.rho[i], p_i = nb.p[i];
  const double inv_rho_i = 1.0 / rho_i;
  const double support2 = prm.kernel.support2, inv_h = prm.kernel.inv_h;
  const double f_coef = prm.kernel.f_coef, eta2 = prm.eta2;
  const BlockView<D> c(cand);
  const double *xj0 = c.x0, *xj1 = c.x1, *xj2 = c.x2, *vj0 = c.v0, *vj1 = c.v1, *vj2 = c.v2;
  const double *rho = c.rho, *p = c.p, *vol = c.vol, *mass = c.mass;
  const std::ptrdiff_t len = c.len;
  double ax = 0.0, ay = 0.0, az = 0.0, drho = 0.0, vdt = -1e300, npair = 0.0;
#pragma omp simd reduction(+ : ax, ay, az, drho, npair) reduction(max : vdt)
  for (std::ptrdiff_t j = 0; j < len; ++j) {
    const double rx = xi[0] - xj0[j], ry = xi[1] - xj1[j];
    const double rz = D == 3 ? xi[2] - xj2[j] : 0.0;
    const double r2 = rx * rx + ry * ry + rz * rz;
    const bool in = r2 < support2 && r2 > 0.0;
    const double t = 1.0 - 0.5 * std::sqrt(r2) * inv_h;
    const double f = in ? f_coef * t * t * t : 0.0;  // F(r) = W'(r)/r, zero outside
    const double ux = vi[0] - vj0[j], uy = vi[1] - vj1[j];
    const double uz = D == 3 ? vi[2] - vj2[j] : 0.0;
    const double rij_dot_gradw = f * r2;
    const double vij_dot_rij = ux * rx + uy * ry + uz * rz;
    const double inv_r2eta = 1.0 / (r2 + eta2);
    // pressure: -m_j (p_i + p_j)/(rho_i rho_j) = -(p_i + p_j) V_j / rho_i
    double g = -(p_i + p[j]) * vol[j] * inv_rho_i;
    if constexpr (VM == ViscosityModel::artificial) {
      g += artificial_visc_coef(mass[j], prm.alpha_c0_h, vij_dot_rij, rho_i, rho[j], r2, eta2);
    }
    g *= f;
    ax += g * rx;
    ay += g * ry;
    az += g * rz;
    if constexpr (VM == ViscosityModel::laminar) {
      const double lv = mass[j] * 4.0 * prm.nu * rij_dot_gradw * inv_r2eta / (rho_i + rho[j]);
      ax += lv * ux;
      ay += lv * uy;
      az += lv * uz;
    }
    double dr = rho_i * vol[j] * f * vij_dot_rij;  // continuity: rho_i V_j v_ij . grad W
    if constexpr (!kWall && DM == DiffusionModel::molteni) {
      dr += prm.two_delta_h_c0 * vol[j] * (rho_i - rho[j]) * rij_dot_gradw * inv_r2eta;
    } else if constexpr (!kWall && DM == DiffusionModel::fourtakas) {
      const double z_ij = rx * prm.up[0] + ry * prm.up[1] + (D == 3 ? rz * prm.up[D - 1] : 0.0);
      const double rho_h = prm.eos.rho0 * binomial_series_minus_one(prm.rho0_g_over_b * z_ij,
                                                                      prm.inv_gamma);
      dr += prm.two_delta_h_c0 * vol[j] * ((rho_i - rho[j]) + rho_h) * rij_dot_gradw * inv_r2eta;
    }
    drho += dr;
    vdt = std::max(vdt, in ? vij_dot_rij * inv_r2eta : -1e300);
    npair += in ? 1.0 : 0.0;
  }
  a.acc[0] += ax;
  a.acc[1] += ay;
  a.acc[2] += az;
  a.drho += drho;
  a.max_visc_dt = std::max(a.max_visc_dt, vdt);
  a.pairs += static_cast<std::uint64_t>(npair);
}

// Continuity of wall particle i over its fluid candidates (dynamic boundary).
template <int D>
inline void wall_run(const SolverParams<D>& prm, const NeighbourArrays<D>& nb, std::uint32_t i,
                     const Candidates<D>& cand, Accum& a) {
  const SelfState<D> self(nb, i);
  const double *xi = self.x, *vi = self.v;
  const double rho_i = nb.rho[i];
  const double support2 = prm.kernel.support2, inv_h = prm.kernel.inv_h;
  const double f_coef = prm.kernel.f_coef, eta2 = prm.eta2;
  const BlockView<D> c(cand);
  const double *xj0 = c.x0, *xj1 = c.x1, *xj2 = c.x2, *vj0 = c.v0, *vj1 = c.v1, *vj2 = c.v2;
  const double* vol = c.wall_vol;  // buffers excluded: see NeighbourArrays::wall_vol
  const std::ptrdiff_t len = c.len;
  double drho = 0.0, vdt = -1e300, npair = 0.0;
#pragma omp simd reduction(+ : drho, npair) reduction(max : vdt)
  for (std::ptrdiff_t j = 0; j < len; ++j) {
    const double rx = xi[0] - xj0[j], ry = xi[1] - xj1[j];
    const double rz = D == 3 ? xi[2] - xj2[j] : 0.0;
    const double r2 = rx * rx + ry * ry + rz * rz;
    const bool in = r2 < support2 && r2 > 0.0;
    const double t = 1.0 - 0.5 * std::sqrt(r2) * inv_h;
    const double f = in ? f_coef * t * t * t : 0.0;
    const double ux = vi[0] - vj0[j], uy = vi[1] - vj1[j];
    const double uz = D == 3 ? vi[2] - vj2[j] : 0.0;
    const double vij_dot_rij = ux * rx + uy * ry + uz * rz;
    drho += rho_i * vol[j] * f * vij_dot_rij;
    vdt = std::max(vdt, in ? vij_dot_rij / (r2 + eta2) : -1e300);
    npair += in ? 1.0 : 0.0;
  }
  a.drho += drho;
  a.max_visc_dt = std::max(a.max_visc_dt, vdt);
  a.pairs += static_cast<std::uint64_t>(npair);
}

template <int D, ViscosityModel VM, DiffusionModel DM>
ForceStats force_loop(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                      const NeighbourArrays<D>& nb, const Vec<D>* extra_acc,
                      bool buffer_reaction) {
  const auto& cells = grid.particle_cells();
  const auto n = static_cast<std::int64_t>(ps.size());
  double max_visc_dt = -1e300, max_acc2 = 0.0;
  std::uint64_t pairs = 0;
#pragma omp parallel reduction(max : max_visc_dt, max_acc2) reduction(+ : pairs)
  {
    Candidates<D> fluid_cand, wall_cand;  // per thread
#pragma omp for schedule(dynamic, 512)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::uint32_t>(ii);
    Accum a;
    fluid_cand.gather(nb, grid, cells[i], Group::fluid);
    if (ps.kind[i] == Kind::buffer) {
      // v and rho come from another level: acc is only the reaction of this level's fluid and
      // buffer neighbours (walls left out), from which the simulation measures the net force the
      // buffer exerts on the fluid. Buffer-buffer pairs cancel in that sum.
      if (buffer_reaction) fluid_run<D, VM, DM, false>(prm, nb, i, fluid_cand, a);
      for (int k = 0; k < D; ++k) ps.acc[i][k] = a.acc[k];
      ps.drho[i] = 0.0;
      continue;
    }
    if (ps.kind[i] == Kind::wall) {
      wall_run(prm, nb, i, fluid_cand, a);
    } else {
      fluid_run<D, VM, DM, false>(prm, nb, i, fluid_cand, a);
      wall_cand.gather(nb, grid, cells[i], Group::wall);
      fluid_run<D, VM, DM, true>(prm, nb, i, wall_cand, a);
    }
    Vec<D> acc;
    for (int k = 0; k < D; ++k) acc[k] = a.acc[k];
    if (extra_acc != nullptr && ps.kind[i] != Kind::wall) acc += extra_acc[i];
    ps.acc[i] = acc;
    ps.drho[i] = a.drho;
    if (ps.kind[i] != Kind::wall) max_acc2 = std::max(max_acc2, norm2(acc));
    max_visc_dt = std::max(max_visc_dt, a.max_visc_dt);
    pairs += a.pairs;
  }
  }
  return {max_visc_dt, std::sqrt(max_acc2), pairs};
}

template <int D, ViscosityModel VM>
ForceStats dispatch_diffusion(const SolverParams<D>& prm, ParticleSet<D>& ps,
                              const CellGrid<D>& grid, const NeighbourArrays<D>& nb,
                              const Vec<D>* extra, bool br) {
  switch (prm.diffusion) {
    case DiffusionModel::none:
      return force_loop<D, VM, DiffusionModel::none>(prm, ps, grid, nb, extra, br);
    case DiffusionModel::molteni:
      return force_loop<D, VM, DiffusionModel::molteni>(prm, ps, grid, nb, extra, br);
    case DiffusionModel::fourtakas:
      return force_loop<D, VM, DiffusionModel::fourtakas>(prm, ps, grid, nb, extra, br);
  }
  return {};
}

}  // namespace

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid) {
  ForceWorkspace<D> ws;
  return compute_forces(prm, ps, grid, ws);
}

template <int D>
ForceStats compute_forces(const SolverParams<D>& prm, ParticleSet<D>& ps, const CellGrid<D>& grid,
                          ForceWorkspace<D>& ws, const Vec<D>* extra_acc,
                          bool buffer_reaction) {
  const std::size_t n = ps.size();
  ps.p.resize(n);
  ps.acc.resize(n);
  ps.drho.resize(n);
  NeighbourArrays<D>& nb = ws.packed;
  nb.pack(ps, prm.eos);
  if (prm.viscosity == ViscosityModel::laminar) {
    return dispatch_diffusion<D, ViscosityModel::laminar>(prm, ps, grid, nb, extra_acc,
                                                          buffer_reaction);
  }
  return dispatch_diffusion<D, ViscosityModel::artificial>(prm, ps, grid, nb, extra_acc,
                                                           buffer_reaction);
}

template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&);
template ForceStats compute_forces<2>(const SolverParams<2>&, ParticleSet<2>&, const CellGrid<2>&,
                                      ForceWorkspace<2>&, const Vec<2>*, bool);
template ForceStats compute_forces<3>(const SolverParams<3>&, ParticleSet<3>&, const CellGrid<3>&,
                                      ForceWorkspace<3>&, const Vec<3>*, bool);

}  // namespace vrsph
