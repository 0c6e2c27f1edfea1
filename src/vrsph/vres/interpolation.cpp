#include "vrsph/vres/interpolation.hpp"

#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/within.hpp"

namespace vrsph {
namespace {

// The sums over the donors of the dimensionless system (see the header):
//   a = sum_j [V_j W, V_j h grad W] (outer) [1, (x_j - x)/h],  grad W = F(r) (x - x_j);
//   rhs[q] = sum_j f_j^q [V_j W, V_j h grad W] for f^0 = rho, f^(1+k) = vel_k;
//   shepard_buffer = sum over the donor's buffer particles of V_j W.
template <int D>
struct DonorSums {
  static constexpr int N = D + 1;
  typename SmallLu<N>::Matrix a{};
  std::array<typename SmallLu<N>::Vector, N> rhs{};
  double shepard_buffer = 0.0;

  double shepard() const { return a[0][0]; }
  // rho, then the velocity components: the first entry of each right-hand side.
  double value_sum(int q) const { return rhs[q][0]; }

  // Adds a piece of donors (within reach of x, in index order). First what each donor gives on
  // its own (r, V W, V F: independent, so the compiler vectorises it), then the sums in donor
  // order with the accumulators in registers. Summed donor by donor with the kernel inside the
  // loop, the accumulators lived in memory (the compiler could not rule out that they alias the
  // donors' arrays) and each sqrt's latency sat in the chain (the interpolation: 14.7% of a
  // one-thread VR drop's samples, 12.0% this way).
  void add_piece(const Vec<D>& x, const std::uint32_t* kept, std::uint32_t n,
                 const DonorState<D>& dn) {
    const WendlandC2<D>& kernel = dn.kernel;
    double r[D][kWithinPiece], vw[kWithinPiece], vf[kWithinPiece];
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t j = kept[k];
      const Vec<D> d = x - dn.pos[j];
      for (int q = 0; q < D; ++q) r[q][k] = d[q];
      const double dist = std::sqrt(norm2(d));
      vw[k] = dn.vol[j] * kernel.w(dist);
      vf[k] = dn.vol[j] * kernel.f(dist);
    }
    DonorSums t = *this;
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t j = kept[k];
      if (dn.ps.kind[j] != Kind::fluid) {  // buffer: counted in the fill only
        t.shepard_buffer += vw[k];
        continue;
      }
      std::array<double, N> row{}, col{};  // row: test functions; col: Taylor terms
      row[0] = vw[k];
      col[0] = 1.0;
      for (int q = 0; q < D; ++q) {
        row[q + 1] = vf[k] * kernel.h * r[q][k];
        col[q + 1] = -r[q][k] * kernel.inv_h;
      }
      const double rho = dn.rho[j];
      const Vec<D> vel = dn.vel[j];
      for (int i = 0; i < N; ++i) {
        for (int c = 0; c < N; ++c) t.a[i][c] += row[i] * col[c];
        t.rhs[0][i] += row[i] * rho;
        for (int q = 0; q < D; ++q) t.rhs[q + 1][i] += row[i] * vel[q];
      }
    }
    *this = t;
  }
};

// What the Shepard average reads of DonorSums, and nothing else: sum_j V_j W, sum_j V_j f_j W for
// f = rho and each velocity component, and the buffer's share of the fill. Each sum is formed by
// the same operations in the same order as DonorSums forms a[0][0] and rhs[q][0] (a product with
// col[0] = 1 is exact), so the Shepard values have the same bits either way. Without the
// gradient rows it needs no F(r), and its six accumulators stay in registers (DonorSums, copied
// in and out of each piece, was a tenth of the interpolation's samples on the shipped VR drop).
template <int D>
struct ShepardValueSums {
  double w = 0.0;
  double fw[D + 1] = {};
  double shepard_buffer = 0.0;

  double shepard() const { return w; }
  double value_sum(int q) const { return fw[q]; }

  void add_piece(const Vec<D>& x, const std::uint32_t* kept, std::uint32_t n,
                 const DonorState<D>& dn) {
    const WendlandC2<D>& kernel = dn.kernel;
    double vw[kWithinPiece];
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t j = kept[k];
      vw[k] = dn.vol[j] * kernel.w(std::sqrt(norm2(x - dn.pos[j])));
    }
    double sw = w, sb = shepard_buffer, s[D + 1];
    for (int q = 0; q <= D; ++q) s[q] = fw[q];
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t j = kept[k];
      if (dn.ps.kind[j] != Kind::fluid) {  // buffer: counted in the fill only
        sb += vw[k];
        continue;
      }
      sw += vw[k];
      s[0] += vw[k] * dn.rho[j];
      const Vec<D> vel = dn.vel[j];
      for (int q = 0; q < D; ++q) s[q + 1] += vw[k] * vel[q];
    }
    w = sw, shepard_buffer = sb;
    for (int q = 0; q <= D; ++q) fw[q] = s[q];
  }
};

// The walls' share of the fill at x (c: its stencil cell): out.shepard_walls += sum_j V_j W over
// the donor level's wall particles within reach.
template <int D>
void add_wall_fill(const Vec<D>& x, std::int64_t c, const DonorState<D>& dn,
                   InterpolatedState<D>& out) {
  const ParticleSet<D>& donors = dn.ps;
  const WendlandC2<D>& kernel = dn.kernel;
  auto now = [&](std::uint32_t j) { return donors.pos[j]; };
  for_each_within(dn.grid, c, Group::wall, x, kernel.support2, now,
                  [&](std::uint32_t j, const Vec<D>&, double r2) {
                    const double v = donors.mass_of(j) / donors.rho[j];
                    out.shepard_walls += v * kernel.w(std::sqrt(r2));
                  });
}

// The lane sums over the fluid group of x's stencil (cell c), into `out`'s Shepard sums and, where
// there is fluid, its Shepard values.
template <int D>
void shepard_in_lanes(const Vec<D>& x, std::int64_t c, const DonorState<D>& dn,
                      InterpolatedState<D>& out) {
  LaneSums<D, D + 1, true> s;
  dn.grid.for_each_run(c, Group::fluid, [&](std::uint32_t begin, std::uint32_t end) {
    s.add_row(x, *dn.columns, dn.kernel, begin, end);
  });
  const auto t = s.totals();
  out.shepard = t.w;
  out.shepard_buffer = t.w_buffer;
  if (!(t.w >= kVresShepardMin)) return;
  const double inv_shep = 1.0 / t.w;
  out.rho = t.fw[0] * inv_shep;
  for (int k = 0; k < D; ++k) out.vel[k] = t.fw[k + 1] * inv_shep;
}

// The sums over the fluid donors in reach of x (c: its stencil cell), and the fields of `out` they
// give: the Shepard sum and the buffer's share of the fill. Sums: DonorSums or ShepardValueSums.
template <class Sums, int D>
Sums donor_sums(const Vec<D>& x, std::int64_t c, const DonorState<D>& dn,
                InterpolatedState<D>& out) {
  Sums s;
  const Vec<D>* pos = dn.pos;
  auto at = [pos](std::uint32_t j) { return pos[j]; };
  for_each_within_piece(
      dn.grid, c, Group::fluid, x, dn.kernel.support2, at,
      [&](const std::uint32_t* kept, std::uint32_t n) { s.add_piece(x, kept, n, dn); });
  out.shepard = s.shepard();
  out.shepard_buffer = s.shepard_buffer;
  return s;
}

// The Shepard average: each value sum over the Shepard sum.
template <class Sums, int D>
void shepard_values(const Sums& s, InterpolatedState<D>& out) {
  const double inv_shep = 1.0 / out.shepard;
  out.rho = s.value_sum(0) * inv_shep;
  for (int k = 0; k < D; ++k) out.vel[k] = s.value_sum(k + 1) * inv_shep;
}

}  // namespace

// Out of line, also where interpolate_values calls it: inlined there, GCC contracted its sums into
// multiply-adds differently, and every run through the first-order path changed in its last bits.
template <int D>
[[gnu::noinline]] InterpolatedState<D> interpolate_from_donor(const Vec<D>& x,
                                                              const DonorState<D>& dn,
                                                              double cond_limit,
                                                              double shepard_fill) {
  InterpolatedState<D> out;
  std::int64_t c = 0;
  if (dn.ps.size() == 0 || !dn.grid.stencil_cell(x, c)) return out;
  add_wall_fill(x, c, dn, out);  // independent of the fluid sums below
  // Above a fill of 1 (the fluid's inside) nearly every point takes the Shepard average, so its
  // sums come first and the first-order system is summed only where the fill reaches
  // shepard_fill (cond stays 0 where it is not formed). The shipped VR drop (2: everywhere)
  // spends half the interpolation's time on sums that the old order formed and never read.
  if (shepard_fill > 1.0) {
    const ShepardValueSums<D> s = donor_sums<ShepardValueSums<D>>(x, c, dn, out);
    if (!(out.shepard >= kVresShepardMin)) return out;  // no fluid here
    if (donor_fill(out) < shepard_fill) {
      shepard_values(s, out);
      return out;
    }
  }
  const DonorSums<D> s = donor_sums<DonorSums<D>>(x, c, dn, out);
  if (!(out.shepard >= kVresShepardMin)) return out;  // no fluid here
  const SmallLu<D + 1> lu(s.a);
  out.cond = lu.cond_inf();
  if (out.cond <= cond_limit && !(donor_fill(out) < shepard_fill)) {
    out.rho = lu.solve(s.rhs[0])[0];
    for (int k = 0; k < D; ++k) out.vel[k] = lu.solve(s.rhs[k + 1])[0];
    out.corrected = std::isfinite(out.rho) && std::isfinite(norm2(out.vel));
    if (out.corrected) return out;
  }
  shepard_values(s, out);
  return out;
}

template <int D>
InterpolatedState<D> interpolate_values(const Vec<D>& x, const DonorState<D>& dn, double cond_limit,
                                        double shepard_fill) {
  if (!(shepard_fill > 1.0) || dn.columns == nullptr)
    return interpolate_from_donor(x, dn, cond_limit, shepard_fill);
  InterpolatedState<D> out;
  std::int64_t c = 0;
  const ParticleSet<D>& donors = dn.ps;
  if (donors.size() == 0 || !dn.grid.stencil_cell(x, c)) return out;
  add_wall_fill(x, c, dn, out);
  shepard_in_lanes(x, c, dn, out);
  if (!(out.shepard >= kVresShepardMin) || donor_fill(out) < shepard_fill) return out;
  return interpolate_from_donor(x, dn, cond_limit, shepard_fill);  // the fill reaches shepard_fill
}

// Donor j at the fraction a of its last step: the states at the step's start (pos0, vel0, rho0)
// and end, linearly interpolated; a = 1 is the current state itself.
template <int D>
DonorState<D>::DonorState(const ParticleSet<D>& p, const CellGrid<D>& g, const WendlandC2<D>& k,
                          double a, DonorStorage<D>& store, bool lanes)
    : ps(p), grid(g), kernel(k), pos(p.pos.data()), vel(p.vel.data()), rho(p.rho.data()) {
  const std::size_t n = p.size();
  if (a != 1.0 && n > 0) {
    store.pos_a.resize(n);
    store.vel_a.resize(n);
    store.rho_a.resize(n);
    Vec<D>* pa = store.pos_a.data();
    Vec<D>* va = store.vel_a.data();
    double* ra = store.rho_a.data();
    exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t j) {
      pa[j] = p.pos0[j] + a * (p.pos[j] - p.pos0[j]);
      va[j] = p.vel0[j] + a * (p.vel[j] - p.vel0[j]);
      ra[j] = p.rho0[j] + a * (p.rho[j] - p.rho0[j]);
    });
    pos = pa, vel = va, rho = ra;
  }
  store.vol.resize(n);
  double* v = store.vol.data();
  const double* r = rho;
  exec::for_each(static_cast<std::int64_t>(n),
                 [&](std::int64_t j) { v[j] = p.mass_of(static_cast<std::size_t>(j)) / r[j]; });
  vol = v;
  if (lanes) {
    fill_columns(store.columns);
    columns = &store.columns;
  }
}

template <int D>
void DonorState<D>::fill_columns(ShepardColumns<D>& c) const {
  const std::size_t n = ps.size();
  c.size_for(n, D + 1, true);
  exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t jj) {
    const auto j = static_cast<std::size_t>(jj);
    for (int k = 0; k < D; ++k) c.x[k][j] = pos[j][k], c.value[k + 1][j] = vel[j][k];
    const bool fluid = ps.kind[j] == Kind::fluid;
    c.vol_fluid[j] = fluid ? vol[j] : 0.0;
    c.vol_buffer[j] = fluid ? 0.0 : vol[j];
    c.value[0][j] = rho[j];
  });
}

template <int D>
InterpolatedState<D> interpolate_from_level(const Vec<D>& x, const ParticleSet<D>& donors,
                                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                                            double cond_limit, double a, double shepard_fill) {
  DonorStorage<D> store;
  const DonorState<D> donor(donors, grid, kernel, a, store, shepard_fill > 1.0);
  return interpolate_values(x, donor, cond_limit, shepard_fill);
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

template <int D, class T>
void fill_field_columns(const ParticleSet<D>& donors, const std::vector<T>& field,
                        LaneColumns<D>& cols) {
  constexpr int K = kComponents<D, T>;
  const std::size_t n = donors.size();
  cols.size_for(n, K, false);
  exec::for_each(static_cast<std::int64_t>(n), [&](std::int64_t jj) {
    const auto j = static_cast<std::size_t>(jj);
    for (int k = 0; k < D; ++k) cols.x[k][j] = donors.pos[j][k];
    cols.vol_fluid[j] = donors.kind[j] == Kind::fluid ? donors.mass_of(j) / donors.rho[j] : 0.0;
    if constexpr (K == 1) {
      cols.value[0][j] = field[j];
    } else {
      for (int k = 0; k < K; ++k) cols.value[k][j] = field[j][k];
    }
  });
}

template <int D, class T>
T shepard_field(const Vec<D>& x, const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                const LaneColumns<D>& cols, T fallback) {
  constexpr int K = kComponents<D, T>;
  std::int64_t c = 0;
  if (cols.vol_fluid.size() <= LaneColumns<D>::kPad || !grid.stencil_cell(x, c)) return fallback;
  LaneSums<D, K, false> s;
  grid.for_each_run(c, Group::fluid, [&](std::uint32_t begin, std::uint32_t end) {
    s.add_row(x, cols, kernel, begin, end);
  });
  const auto t = s.totals();
  if (!(t.w >= kVresShepardMin)) return fallback;
  const double inv = 1.0 / t.w;
  if constexpr (K == 1) {
    return t.fw[0] * inv;
  } else {
    T v;
    for (int k = 0; k < K; ++k) v[k] = t.fw[k] * inv;
    return v;
  }
}

template <int D>
void interpolate_from_level(const std::vector<Vec<D>>& points, const ParticleSet<D>& donors,
                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                            std::vector<InterpolatedState<D>>& out, double cond_limit) {
  out.resize(points.size());
  DonorStorage<D> store;
  const DonorState<D> donor(donors, grid, kernel, 1.0, store);
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
template InterpolatedState<2> interpolate_values(const Vec<2>&, const DonorState<2>&, double,
                                                 double);
template InterpolatedState<3> interpolate_values(const Vec<3>&, const DonorState<3>&, double,
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

template void fill_field_columns<2, double>(const ParticleSet<2>&, const std::vector<double>&,
                                            LaneColumns<2>&);
template double shepard_field<2, double>(const Vec<2>&, const CellGrid<2>&, const WendlandC2<2>&,
                                         const LaneColumns<2>&, double);
template void fill_field_columns<3, double>(const ParticleSet<3>&, const std::vector<double>&,
                                            LaneColumns<3>&);
template double shepard_field<3, double>(const Vec<3>&, const CellGrid<3>&, const WendlandC2<3>&,
                                         const LaneColumns<3>&, double);
template void fill_field_columns<2, Vec<2>>(const ParticleSet<2>&, const std::vector<Vec<2>>&,
                                            LaneColumns<2>&);
template Vec<2> shepard_field<2, Vec<2>>(const Vec<2>&, const CellGrid<2>&, const WendlandC2<2>&,
                                         const LaneColumns<2>&, Vec<2>);
template void fill_field_columns<3, Vec<3>>(const ParticleSet<3>&, const std::vector<Vec<3>>&,
                                            LaneColumns<3>&);
template Vec<3> shepard_field<3, Vec<3>>(const Vec<3>&, const CellGrid<3>&, const WendlandC2<3>&,
                                         const LaneColumns<3>&, Vec<3>);

}  // namespace vrsph
