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

}  // namespace

template <int D>
void surface_sums(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  SurfaceFields<D>& sf) {
  const auto n = static_cast<std::int64_t>(ps.size());
  sf.resize(ps.size());
  const auto& k = prm.kernel;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (ps.kind[i] == Kind::wall) continue;
    Mat<D> m;
    Vec<D> grad_c{};
    double div_r = 0.0, shep = ps.mass[i] / ps.rho[i] * k.w(0.0);
    for_each_neighbour(ps, grid, k.support2, i, true, [&](std::uint32_t j, const Vec<D>& r_ij, double r2) {
      const double r = std::sqrt(r2);
      const double vol_f = ps.mass[j] / ps.rho[j] * k.f(r);  // V_j F(r)
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) m.a[a][b] -= vol_f * r_ij[a] * r_ij[b];  // V_j (r_j - r_i) (x) grad W
      grad_c += vol_f * r_ij;
      div_r -= vol_f * r2;
      shep += ps.mass[j] / ps.rho[j] * k.w(r);
    });
    const double lambda = min_eigenvalue(m);
    sf.lambda[i] = lambda;
    sf.l_corr[i] = correction_from_m(m, lambda);
    sf.grad_c[i] = grad_c;
    sf.div_r[i] = div_r;
    sf.shepard[i] = shep;
  }
}

template <int D>
void surface_normals(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                     SurfaceFields<D>& sf) {
  const auto n = static_cast<std::int64_t>(ps.size());
  const auto& k = prm.kernel;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (ps.kind[i] == Kind::wall) continue;
    const double lambda_i = sf.lambda[i];
    const bool inner = lambda_i >= prm.lambda_threshold;
    Vec<D> sum{};
    for_each_neighbour(ps, grid, k.support2, i, false, [&](std::uint32_t j, const Vec<D>& r_ij, double r2) {
      const double coef = inner ? sf.lambda[j] - lambda_i : sf.lambda[j];
      sum += (coef * ps.mass[j] / ps.rho[j] * k.f(std::sqrt(r2))) * r_ij;
    });
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
    double kappa = 0.0;
    const Mat<D>& l_i = sf.l_corr[i];
    for_each_neighbour(ps, grid, k.support2, i, false, [&](std::uint32_t j, const Vec<D>& r_ij, double r2) {
      const Vec<D>& n_j = sf.normal[j];
      if (norm2(n_j) == 0.0 || dot(n_i, n_j) < cos_t) return;  // S_ij = 0
      const Vec<D> l_grad_w = l_i * (k.f(std::sqrt(r2)) * r_ij);
      kappa += ps.mass[j] / ps.rho[j] * dot(n_j - n_i, l_grad_w);
    });
    sf.curvature[i] = kappa;
    const double delta = surface_delta(norm(sf.grad_c[i]), sf.shepard[i]);
    sf.acc_st[i] = csf_acceleration<D>(prm.sigma, kappa, n_i, delta, ps.rho[i]);
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
