#include "vrsph/vres/interpolation.hpp"

#include <stdexcept>

namespace vrsph {
namespace {

// Where a point's neighbour stencil lies in a sorted CellGrid's cell table.
//
// CellGrid lays its table over the cells the particles occupy (plus `reach` ghost cells), not
// over the whole domain, and for_each_run does not clip its stencil. A point inside the domain
// but near or beyond the edge of the particle cloud would read outside the table. The table's
// shape is recovered here from the public interface: strides by probing cell_of at cell
// centres, the table coordinates of one cell from the first particle's recorded cell. A point's
// table coordinates t_k are then clamped to [reach, n_k - 1 - reach]: that stencil still
// contains every occupied cell within reach of the point (occupied cells lie in that range), and
// the distance test drops the rest.
template <int D>
struct TableWindow {
  bool valid = false;
  std::array<std::int64_t, D> n{}, stride{}, ref_table{}, ref_abs{};
  int reach = 1;
  Vec<D> min{};
  double inv_cell = 0.0;

  std::int64_t abs_cell(const Vec<D>& x, int k) const {  // the grid's own formula
    return static_cast<std::int64_t>((x[k] - min[k]) * inv_cell);
  }

  TableWindow(const ParticleSet<D>& ps, const CellGrid<D>& grid) {
    const auto& cells = grid.particle_cells();
    if (ps.size() == 0 || cells.size() != ps.size() || grid.cell_count() <= 0) return;
    min = grid.domain_min();
    inv_cell = 1.0 / grid.cell_size();
    reach = grid.reach();
    const Vec<D>& x0 = ps.pos[0];
    if (!grid.inside(x0) || grid.cell_of(x0) != cells[0]) {
      throw std::logic_error(
          "vres interpolation: the donor grid is out of date (sort it after moving particles)");
    }
    const double cs = grid.cell_size();
    Vec<D> centre{};
    for (int k = 0; k < D; ++k) {
      ref_abs[k] = abs_cell(x0, k);
      centre[k] = min[k] + (static_cast<double>(ref_abs[k]) + 0.5) * cs;
    }
    const std::int64_t base = grid.cell_of(centre);
    stride[0] = 1;
    for (int k = 1; k < D; ++k) {
      Vec<D> next = centre;
      next[k] += cs;
      stride[k] = grid.cell_of(next) - base;
    }
    n[0] = stride[1];
    if constexpr (D == 2) {
      n[1] = grid.cell_count() / n[0];
    } else {
      n[1] = stride[2] / n[0];
      n[2] = grid.cell_count() / stride[2];
    }
    std::int64_t rest = cells[0];
    for (int k = 0; k < D; ++k) {
      ref_table[k] = (k + 1 < D) ? rest % n[k] : rest;
      rest /= n[k];
    }
    std::int64_t total = 1;
    bool shape_ok = true;
    for (int k = 0; k < D; ++k) {
      total *= n[k];
      shape_ok = shape_ok && n[k] >= 2 * reach + 1 && ref_table[k] >= reach &&
                 ref_table[k] < n[k] - reach;
    }
    valid = shape_ok && total == grid.cell_count() && base == cells[0];
  }

  // Stencil centre cell for x (linear index), or false when no particle can be within reach.
  bool stencil_cell(const Vec<D>& x, std::int64_t& c) const {
    c = 0;
    for (int k = 0; k < D; ++k) {
      const std::int64_t t = ref_table[k] + abs_cell(x, k) - ref_abs[k];
      if (t < 0 || t >= n[k]) return false;  // more than `reach` cells from any particle
      c += std::clamp<std::int64_t>(t, reach, n[k] - 1 - reach) * stride[k];
    }
    return true;
  }
};

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

template <int D>
InterpolatedState<D> interpolate_at(const Vec<D>& x, const ParticleSet<D>& donors,
                                    const CellGrid<D>& grid, const TableWindow<D>& win,
                                    const WendlandC2<D>& kernel, double cond_limit) {
  InterpolatedState<D> out;
  std::int64_t c = 0;
  if (!win.valid || !grid.inside(x) || !win.stencil_cell(x, c)) return out;
  DonorSums<D> s;
  grid.for_each_run(c, Group::fluid, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t j = begin; j < end; ++j) {
      if (donors.kind[j] != Kind::fluid) continue;
      const Vec<D> r = x - donors.pos[j];
      const double r2 = norm2(r);
      if (r2 >= kernel.support2) continue;
      s.add(r, r2, donors.mass[j] / donors.rho[j], donors.rho[j], donors.vel[j], kernel);
    }
  });
  out.shepard = s.a[0][0];
  out.div_r = s.div_r;
  if (!(out.shepard >= kVresShepardMin)) return out;  // no fluid here
  const SmallLu<D + 1> lu(s.a);
  out.cond = lu.cond_inf();
  if (out.cond <= cond_limit) {
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

}  // namespace

template <int D>
InterpolatedState<D> interpolate_from_level(const Vec<D>& x, const ParticleSet<D>& donors,
                                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                                            double cond_limit) {
  return interpolate_at(x, donors, grid, TableWindow<D>(donors, grid), kernel, cond_limit);
}

template <int D>
void interpolate_from_level(const std::vector<Vec<D>>& points, const ParticleSet<D>& donors,
                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                            std::vector<InterpolatedState<D>>& out, double cond_limit) {
  out.resize(points.size());
  const TableWindow<D> win(donors, grid);
  const auto n = static_cast<std::int64_t>(points.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    out[i] = interpolate_at(points[i], donors, grid, win, kernel, cond_limit);
  }
}

template InterpolatedState<2> interpolate_from_level(const Vec<2>&, const ParticleSet<2>&,
                                                     const CellGrid<2>&, const WendlandC2<2>&,
                                                     double);
template InterpolatedState<3> interpolate_from_level(const Vec<3>&, const ParticleSet<3>&,
                                                     const CellGrid<3>&, const WendlandC2<3>&,
                                                     double);
template void interpolate_from_level(const std::vector<Vec<2>>&, const ParticleSet<2>&,
                                     const CellGrid<2>&, const WendlandC2<2>&,
                                     std::vector<InterpolatedState<2>>&, double);
template void interpolate_from_level(const std::vector<Vec<3>>&, const ParticleSet<3>&,
                                     const CellGrid<3>&, const WendlandC2<3>&,
                                     std::vector<InterpolatedState<3>>&, double);

}  // namespace vrsph
