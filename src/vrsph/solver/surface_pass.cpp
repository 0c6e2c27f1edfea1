#include "vrsph/solver/surface_pass.hpp"

#include <cmath>

#include "vrsph/physics/surface_tension.hpp"

namespace vrsph {

template <int D>
void SurfaceFields<D>::resize(std::size_t n) {
  lambda.assign(n, 0.0);
  l_corr.assign(n, Mat<D>::identity());
  grad_c.assign(n, Vec<D>{});
  div_r.assign(n, 0.0);
  shepard.assign(n, 0.0);
  normal.assign(n, Vec<D>{});
  curvature.assign(n, 0.0);
  acc_st.assign(n, Vec<D>{});
}

template <int D>
void SurfaceFields<D>::pack(const ParticleSet<D>& ps) {
  const std::size_t n = ps.size();
  for (int k = 0; k < D; ++k) x[k].resize(n);
  vol.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < D; ++k) x[k][i] = ps.pos[i][k];
    vol[i] = ps.mass[i] / ps.rho[i];
  }
}

namespace {

// Calls fn(j, r_ij, r2) for every neighbour j != i within 2h in the given groups.
template <int D, class Fn>
inline void for_each_neighbour(const ParticleSet<D>& ps, const CellGrid<D>& grid, double support2,
                               std::size_t i, bool with_walls, Fn&& fn) {
  const Vec<D> xi = ps.pos[i];
  auto run = [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t j = b; j < e; ++j) {
      const Vec<D> r_ij = xi - ps.pos[j];
      const double r2 = norm2(r_ij);
      if (r2 < support2 && j != i) fn(j, r_ij, r2);
    }
  };
  const std::int64_t c = grid.particle_cells()[i];
  grid.for_each_run(c, Group::fluid, run);
  if (with_walls) grid.for_each_run(c, Group::wall, run);
}

// Kernel constants as plain values, so vector loops keep them in registers.
struct KernelConsts {
  double support2, inv_h, f_coef, a_d;
  template <int D>
  explicit KernelConsts(const WendlandC2<D>& k)
      : support2(k.support2), inv_h(k.inv_h), f_coef(k.f_coef), a_d(k.a_d) {}
};

// Pass-1 sums of one particle: M (xx, xy, yy, xz, yz, zz), grad C, div r, Shepard.
struct Pass1Sums {
  double m[6] = {0, 0, 0, 0, 0, 0};
  double g[3] = {0, 0, 0};
  double div_r = 0.0, shep = 0.0;
};

// Pass 1 over one run of candidates (unit-stride pointers from the run start). Candidates outside
// the support, and i itself, get zero kernel values instead of a branch, so the loop vectorises.
template <int D>
inline void pass1_run(const KernelConsts kc, const double xi[3], const double* px,
                      const double* py, const double* pz, const double* pv, std::ptrdiff_t len,
                      Pass1Sums& out) {
  double mxx = 0, mxy = 0, myy = 0, mxz = 0, myz = 0, mzz = 0;
  double gx = 0, gy = 0, gz = 0, div_r = 0, shep = 0;
#pragma omp simd reduction(+ : mxx, mxy, myy, mxz, myz, mzz, gx, gy, gz, div_r, shep)
  for (std::ptrdiff_t j = 0; j < len; ++j) {
    const double rx = xi[0] - px[j], ry = xi[1] - py[j], rz = D == 3 ? xi[2] - pz[j] : 0.0;
    const double r2 = rx * rx + ry * ry + rz * rz;
    const bool in = r2 < kc.support2 && r2 > 0.0;
    const double q = std::sqrt(r2) * kc.inv_h;
    const double t = 1.0 - 0.5 * q;
    const double vf = in ? pv[j] * kc.f_coef * t * t * t : 0.0;                   // V_j F(r)
    const double vw = in ? pv[j] * kc.a_d * t * t * t * t * (2.0 * q + 1.0) : 0.0;  // V_j W
    mxx -= vf * rx * rx, mxy -= vf * rx * ry, myy -= vf * ry * ry;  // V_j (r_j - r_i) (x) grad W
    mxz -= vf * rx * rz, myz -= vf * ry * rz, mzz -= vf * rz * rz;
    gx += vf * rx, gy += vf * ry, gz += vf * rz;
    div_r -= vf * r2;
    shep += vw;
  }
  out.m[0] += mxx, out.m[1] += mxy, out.m[2] += myy, out.m[3] += mxz, out.m[4] += myz,
      out.m[5] += mzz;
  out.g[0] += gx, out.g[1] += gy, out.g[2] += gz;
  out.div_r += div_r;
  out.shep += shep;
}

// Pass 2 over one run: sum_j (lambda_j - lambda_ref) V_j F(r) r_ij.
template <int D>
inline void pass2_run(const KernelConsts kc, const double xi[3], double lambda_ref,
                      const double* px, const double* py, const double* pz, const double* pv,
                      const double* pl, std::ptrdiff_t len, double sum[3]) {
  double sx = 0, sy = 0, sz = 0;
#pragma omp simd reduction(+ : sx, sy, sz)
  for (std::ptrdiff_t j = 0; j < len; ++j) {
    const double rx = xi[0] - px[j], ry = xi[1] - py[j], rz = D == 3 ? xi[2] - pz[j] : 0.0;
    const double r2 = rx * rx + ry * ry + rz * rz;
    const bool in = r2 < kc.support2 && r2 > 0.0;
    const double t = 1.0 - 0.5 * std::sqrt(r2) * kc.inv_h;
    const double c = in ? (pl[j] - lambda_ref) * pv[j] * kc.f_coef * t * t * t : 0.0;
    sx += c * rx, sy += c * ry, sz += c * rz;
  }
  sum[0] += sx, sum[1] += sy, sum[2] += sz;
}

}  // namespace

template <int D>
void surface_sums(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  SurfaceFields<D>& sf) {
  const auto n = static_cast<std::int64_t>(ps.size());
  sf.resize(ps.size());
  sf.pack(ps);
  const KernelConsts kc(prm.kernel);
  const double w0 = prm.kernel.w(0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (ps.kind[i] == Kind::wall) continue;
    double xi[3] = {0, 0, 0};
    for (int d = 0; d < D; ++d) xi[d] = sf.x[d][i];
    Pass1Sums acc;
    acc.shep = sf.vol[i] * w0;  // self term
    auto run = [&](std::uint32_t b, std::uint32_t e) {
      pass1_run<D>(kc, xi, sf.x[0].data() + b, sf.x[1].data() + b, sf.x[D - 1].data() + b,
                   sf.vol.data() + b, static_cast<std::ptrdiff_t>(e - b), acc);
    };
    const std::int64_t c = grid.particle_cells()[i];
    grid.for_each_run(c, Group::fluid, run);
    grid.for_each_run(c, Group::wall, run);
    Mat<D> m;
    Vec<D> grad_c;
    m(0, 0) = acc.m[0], m(0, 1) = m(1, 0) = acc.m[1], m(1, 1) = acc.m[2];
    grad_c[0] = acc.g[0], grad_c[1] = acc.g[1];
    if constexpr (D == 3) {
      m(0, 2) = m(2, 0) = acc.m[3], m(1, 2) = m(2, 1) = acc.m[4], m(2, 2) = acc.m[5];
      grad_c[2] = acc.g[2];
    }
    const double lambda = min_eigenvalue(m);
    sf.lambda[i] = lambda;
    sf.l_corr[i] = correction_from_m(m, lambda);
    sf.grad_c[i] = grad_c;
    sf.div_r[i] = acc.div_r;
    sf.shepard[i] = acc.shep;
  }
}

template <int D>
void surface_normals(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                     SurfaceFields<D>& sf) {
  const auto n = static_cast<std::int64_t>(ps.size());
  const KernelConsts kc(prm.kernel);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (ps.kind[i] == Kind::wall) continue;
    const double lambda_i = sf.lambda[i];
    const double lambda_ref = lambda_i >= prm.lambda_threshold ? lambda_i : 0.0;  // difference form
    double xi[3] = {0, 0, 0};
    for (int d = 0; d < D; ++d) xi[d] = sf.x[d][i];
    double s3[3] = {0, 0, 0};
    grid.for_each_run(grid.particle_cells()[i], Group::fluid, [&](std::uint32_t b, std::uint32_t e) {
      pass2_run<D>(kc, xi, lambda_ref, sf.x[0].data() + b, sf.x[1].data() + b,
                   sf.x[D - 1].data() + b, sf.vol.data() + b, sf.lambda.data() + b,
                   static_cast<std::ptrdiff_t>(e - b), s3);
    });
    Vec<D> sum;
    for (int d = 0; d < D; ++d) sum[d] = s3[d];
    sf.normal[i] = normal_from_lambda_gradient<D>(sf.l_corr[i] * sum, lambda_i,
                                                  prm.normal_epsilon, prm.h);
  }
}

template <int D>
void surface_curvature_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                             const CellGrid<D>& grid, SurfaceFields<D>& sf) {
  const auto n = static_cast<std::int64_t>(ps.size());
  const auto& k = prm.kernel;
  constexpr double cos_t = curvature_filter_cos<D>();
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    sf.curvature[i] = 0.0;
    sf.acc_st[i] = Vec<D>{};
    const Vec<D> n_i = sf.normal[i];
    if (ps.kind[i] == Kind::wall || norm2(n_i) == 0.0) continue;
    CurvatureSums sums;
    const Mat<D>& l_i = sf.l_corr[i];
    for_each_neighbour(ps, grid, k.support2, i, false, [&](std::uint32_t j, const Vec<D>& r_ij, double r2) {
      const Vec<D>& n_j = sf.normal[j];
      if (norm2(n_j) == 0.0 || dot(n_i, n_j) < cos_t) return;  // S_ij = 0
      const Vec<D> l_grad_w = l_i * (k.f(std::sqrt(r2)) * r_ij);
      add_curvature_pair<D>(sums, ps.mass[j] / ps.rho[j], n_i, n_j, -1.0 * r_ij, l_grad_w);
    });
    const double kappa = prm.curvature_correction ? corrected_curvature<D>(sums) : sums.kappa;
    sf.curvature[i] = kappa;
    const double delta = surface_delta(norm(sf.grad_c[i]), sf.shepard[i]);
    const double k_force = prm.surface_offset ? curvature_at_surface<D>(kappa, prm.dp) : kappa;
    sf.acc_st[i] = csf_acceleration<D>(prm.sigma, k_force, n_i, delta, ps.rho[i]);
  }
}

template struct SurfaceFields<2>;
template struct SurfaceFields<3>;
template void surface_sums<2>(const SolverParams<2>&, const ParticleSet<2>&, const CellGrid<2>&, SurfaceFields<2>&);
template void surface_sums<3>(const SolverParams<3>&, const ParticleSet<3>&, const CellGrid<3>&, SurfaceFields<3>&);
template <int D>
void surface_tension_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                           const CellGrid<D>& grid, SurfaceFields<D>& sf) {
  surface_normals(prm, ps, grid, sf);
  surface_curvature_force(prm, ps, grid, sf);
}

template void surface_normals<2>(const SolverParams<2>&, const ParticleSet<2>&, const CellGrid<2>&, SurfaceFields<2>&);
template void surface_normals<3>(const SolverParams<3>&, const ParticleSet<3>&, const CellGrid<3>&, SurfaceFields<3>&);
template void surface_curvature_force<2>(const SolverParams<2>&, const ParticleSet<2>&, const CellGrid<2>&, SurfaceFields<2>&);
template void surface_curvature_force<3>(const SolverParams<3>&, const ParticleSet<3>&, const CellGrid<3>&, SurfaceFields<3>&);
template void surface_tension_force<2>(const SolverParams<2>&, const ParticleSet<2>&, const CellGrid<2>&, SurfaceFields<2>&);
template void surface_tension_force<3>(const SolverParams<3>&, const ParticleSet<3>&, const CellGrid<3>&, SurfaceFields<3>&);

}  // namespace vrsph
