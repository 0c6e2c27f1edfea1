#include "vrsph/vres/interpolation.hpp"

#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/within.hpp"

namespace vrsph {
namespace {

// The sums over the donors of the dimensionless system (see the header):
//   a = sum_j [V_j W, V_j h grad W] (outer) [1, (x_j - x)/h],  grad W = F(r) (x - x_j);
//   rhs[q] = sum_j f_j^q [V_j W, V_j h grad W] for f^0 = rho, f^(1+k) = vel_k;
//   div_r = -sum_j V_j F(r) r^2.
template <int D>
struct DonorSums {
  static constexpr int N = D + 1;
  typename SmallLu<N>::Matrix a{};
  std::array<typename SmallLu<N>::Vector, N> rhs{};
  double div_r = 0.0;

  void add(const Vec<D>& r, double r2, double vol, double rho, const Vec<D>& vel,
           const WendlandC2<D>& kernel) {
    const double dist = std::sqrt(r2);
    const double vw = vol * kernel.w(dist);
    const double vf = vol * kernel.f(dist);
    std::array<double, N> row{}, col{};  // row: test functions; col: Taylor terms
    row[0] = vw;
    col[0] = 1.0;
    for (int k = 0; k < D; ++k) {
      row[k + 1] = vf * kernel.h * r[k];
      col[k + 1] = -r[k] * kernel.inv_h;
    }
    for (int i = 0; i < N; ++i) {
      for (int j = 0; j < N; ++j) a[i][j] += row[i] * col[j];
      rhs[0][i] += row[i] * rho;
      for (int k = 0; k < D; ++k) rhs[k + 1][i] += row[i] * vel[k];
    }
    div_r -= vf * r2;
  }
};

}  // namespace

template <int D>
InterpolatedState<D> interpolate_from_donor(const Vec<D>& x, const DonorState<D>& dn,
                                            double cond_limit, double shepard_fill) {
  InterpolatedState<D> out;
  std::int64_t c = 0;
  const ParticleSet<D>& donors = dn.ps;
  const WendlandC2<D>& kernel = dn.kernel;
  if (donors.size() == 0 || !dn.grid.stencil_cell(x, c)) return out;
  DonorSums<D> s;
  const Vec<D>* pos = dn.pos;
  auto at = [pos](std::uint32_t j) { return pos[j]; };
  for_each_within(dn.grid, c, Group::fluid, x, kernel.support2, at,
                  [&](std::uint32_t j, const Vec<D>& r, double r2) {
                    const double rho_j = dn.rho[j];
                    if (donors.kind[j] != Kind::fluid) {  // buffer: counted in the fill only
                      out.shepard_buffer += donors.mass_of(j) / rho_j * kernel.w(std::sqrt(r2));
                      return;
                    }
                    s.add(r, r2, donors.mass_of(j) / rho_j, rho_j, dn.vel[j], kernel);
                  });
  out.shepard = s.a[0][0];
  out.div_r = s.div_r;
  auto now = [&](std::uint32_t j) { return donors.pos[j]; };
  for_each_within(dn.grid, c, Group::wall, x, kernel.support2, now,
                  [&](std::uint32_t j, const Vec<D>&, double r2) {
                    const double v = donors.mass_of(j) / donors.rho[j];
                    out.shepard_walls += v * kernel.w(std::sqrt(r2));
                  });
  if (!(out.shepard >= kVresShepardMin)) return out;  // no fluid here
  const SmallLu<D + 1> lu(s.a);
  out.cond = lu.cond_inf();
  if (out.cond <= cond_limit && !(donor_fill(out) < shepard_fill)) {
    out.rho = lu.solve(s.rhs[0])[0];
    for (int k = 0; k < D; ++k) out.vel[k] = lu.solve(s.rhs[k + 1])[0];
    out.corrected = std::isfinite(out.rho) && std::isfinite(norm2(out.vel));
    if (out.corrected) return out;
  }
  // Shepard: the first component of each right-hand side over the Shepard sum.
  const double inv_shep = 1.0 / out.shepard;
  out.rho = s.rhs[0][0] * inv_shep;
  for (int k = 0; k < D; ++k) out.vel[k] = s.rhs[k + 1][0] * inv_shep;
  return out;
}

// Donor j at the fraction a of its last step: the states at the step's start (pos0, vel0, rho0)
// and end, linearly interpolated; a = 1 is the current state itself.
template <int D>
DonorState<D>::DonorState(const ParticleSet<D>& p, const CellGrid<D>& g, const WendlandC2<D>& k,
                          double a)
    : ps(p), grid(g), kernel(k), pos(p.pos.data()), vel(p.vel.data()), rho(p.rho.data()) {
  if (a == 1.0 || p.size() == 0) return;
  const std::size_t n = p.size();
  pos_a_.resize(n);
  vel_a_.resize(n);
  rho_a_.resize(n);
  exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t j) {
    pos_a_[j] = p.pos0[j] + a * (p.pos[j] - p.pos0[j]);
    vel_a_[j] = p.vel0[j] + a * (p.vel[j] - p.vel0[j]);
    rho_a_[j] = p.rho0[j] + a * (p.rho[j] - p.rho0[j]);
  });
  pos = pos_a_.data(), vel = vel_a_.data(), rho = rho_a_.data();
}

template <int D>
InterpolatedState<D> interpolate_from_level(const Vec<D>& x, const ParticleSet<D>& donors,
                                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                                            double cond_limit, double a, double shepard_fill) {
  const DonorState<D> donor(donors, grid, kernel, a);
  return interpolate_from_donor(x, donor, cond_limit, shepard_fill);
}

template <int D, class T>
T shepard_field(const Vec<D>& x, const ParticleSet<D>& donors, const CellGrid<D>& grid,
                const WendlandC2<D>& kernel, const std::vector<T>& field, T fallback) {
  std::int64_t c = 0;
  if (donors.size() == 0 || !grid.stencil_cell(x, c)) return fallback;
  double sw = 0.0;
  T sfw{};
  auto now = [&](std::uint32_t j) { return donors.pos[j]; };
  for_each_within(grid, c, Group::fluid, x, kernel.support2, now,
                  [&](std::uint32_t j, const Vec<D>&, double r2) {
                    if (donors.kind[j] != Kind::fluid) return;
                    const double vw = donors.mass_of(j) / donors.rho[j] * kernel.w(std::sqrt(r2));
                    sw += vw;
                    sfw += field[j] * vw;
                  });
  return sw >= kVresShepardMin ? sfw * (1.0 / sw) : fallback;
}

template <int D>
void interpolate_from_level(const std::vector<Vec<D>>& points, const ParticleSet<D>& donors,
                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                            std::vector<InterpolatedState<D>>& out, double cond_limit) {
  out.resize(points.size());
  const DonorState<D> donor(donors, grid, kernel, 1.0);
  exec::for_each(static_cast<std::int64_t>(points.size()), [&](std::int64_t i) {
    out[i] = interpolate_from_donor(points[i], donor, cond_limit, 0.0);
  });
}

template class DonorState<2>;
template class DonorState<3>;
template InterpolatedState<2> interpolate_from_donor(const Vec<2>&, const DonorState<2>&, double,
                                                     double);
template InterpolatedState<3> interpolate_from_donor(const Vec<3>&, const DonorState<3>&, double,
                                                     double);
template InterpolatedState<2> interpolate_from_level(const Vec<2>&, const ParticleSet<2>&,
                                                     const CellGrid<2>&, const WendlandC2<2>&,
                                                     double, double, double);
template InterpolatedState<3> interpolate_from_level(const Vec<3>&, const ParticleSet<3>&,
                                                     const CellGrid<3>&, const WendlandC2<3>&,
                                                     double, double, double);
template void interpolate_from_level(const std::vector<Vec<2>>&, const ParticleSet<2>&,
                                     const CellGrid<2>&, const WendlandC2<2>&,
                                     std::vector<InterpolatedState<2>>&, double);
template void interpolate_from_level(const std::vector<Vec<3>>&, const ParticleSet<3>&,
                                     const CellGrid<3>&, const WendlandC2<3>&,
                                     std::vector<InterpolatedState<3>>&, double);

template double shepard_field<2, double>(const Vec<2>&, const ParticleSet<2>&, const CellGrid<2>&,
                                         const WendlandC2<2>&, const std::vector<double>&, double);
template double shepard_field<3, double>(const Vec<3>&, const ParticleSet<3>&, const CellGrid<3>&,
                                         const WendlandC2<3>&, const std::vector<double>&, double);
template Vec<2> shepard_field<2, Vec<2>>(const Vec<2>&, const ParticleSet<2>&, const CellGrid<2>&,
                                         const WendlandC2<2>&, const std::vector<Vec<2>>&, Vec<2>);
template Vec<3> shepard_field<3, Vec<3>>(const Vec<3>&, const ParticleSet<3>&, const CellGrid<3>&,
                                         const WendlandC2<3>&, const std::vector<Vec<3>>&, Vec<3>);

}  // namespace vrsph
