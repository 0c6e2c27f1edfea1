#include "vrsph/solver/surface_pass.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/exec/sweep.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/surface_tension.hpp"
#include "vrsph/solver/forces.hpp"
#include "vrsph/solver/normal_bound.hpp"
#include "vrsph/solver/surface_block.hpp"
#include "vrsph/solver/surface_pass1.hpp"

namespace vrsph {

namespace {

constexpr int kChunk = 256;  // particles handed to a thread at a time
// Passes 2 and 3 sweep only the particles near the free surface (about 30% and 10% of a 2D
// drop's), so their work per chunk varies: smaller chunks even it out between the threads.
constexpr int kSurfaceChunk = 64;

// fluid_rows false: the fluid particles are left as they are (surface_sums_for_shifting).
template <int D, class T>
void sums_pass(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
               const LevelColumns<D>& cols, SurfaceFields<D>& sf, bool fluid_rows) {
  sf.resize(ps.size());
  using S = SurfaceColumns<D, 1, T>;
  const S src(cols, {volume_column<T>(cols)});
  const double w0 = prm.kernel.w(0.0);
  const bool grad_w = prm.sigma > 0.0;  // read by pass 2 only
  sf.grad_w.resize(grad_w ? ps.size() : 0);
  sf.sums_grad_w = grad_w;
  sf.cross_hit.assign(sf.cross.empty() ? 0 : ps.size(), 0);
  const Pass1Out<D> out = sf.pass1_out(true);
  // The fields of particle i from its pass-1 sums; w_self = W(0) of its kernel.
  auto finish = [&](std::size_t i, const double(&s)[12], double w_self) {
    out.store(i, s, shepard_self(ps, cols, i, w_self));
  };
  auto body = [&](std::int64_t ii, StencilSpans<D>& sp) {
    const auto i = static_cast<std::size_t>(ii);
    if (!fluid_rows && ps.kind[i] == Kind::fluid) return;
    if (ps.kind[i] == Kind::wall) {  // no fields of its own: neutral values
      sf.lambda[i] = sf.div_r[i] = sf.shepard[i] = 0.0;
      sf.l_corr[i] = Mat<D>::identity();
      sf.grad_c[i] = Vec<D>{};
      if (grad_w) sf.grad_w[i] = 0.0;
      return;
    }
    double s[12] = {};
    const double h_wide = sf.h_wide.empty() ? 0.0 : sf.h_wide[i];
    if (h_wide > 0.0) {  // the own level too through the wide kernel, not the blocks
      pass1::pass1_across<D, T>(grad_w, sf.wide, WendlandC2<D>(h_wide), ps.pos[i], true, s);
      sf.cross_hit[i] = 1;
      finish(i, s, WendlandC2<D>(h_wide).w(0.0));
      return;
    }
    sp.of(grid, grid.particle_cells()[i], Groups::all);
    T xi[3], xi_lo[3];
    src.self(i, xi, xi_lo);
    if (grad_w)
      pass1::pass1_particle<D, T, true>(prm, src, sp, xi, xi_lo, s);
    else
      pass1::pass1_particle<D, T, false>(prm, src, sp, xi, xi_lo, s);
    if (!sf.cross.empty())
      sf.cross_hit[i] =
          pass1::pass1_across<D, T>(grad_w, sf.cross, prm.kernel, ps.pos[i], false, s) > 0;
    finish(i, s, w0);
  };
  exec::for_each_with<StencilSpans<D>>(static_cast<std::int64_t>(ps.size()), kChunk, body);
}

// Pass 2's pair term: (lambda_j - lambda_ref) V_j F_ij r_ij (physics/surface_tension.hpp).
template <int D, class T, int K>
struct LambdaGradientPair {
  T lambda_ref;
  [[gnu::always_inline]] PairSumsT<T> operator()(const PairGeometryT<T>& g,
                                                 const Neighbour<K, T>& nb) const {
    PairSumsT<T> a;
    const T c = lambda_gradient_pair(nb[D + 1], lambda_ref, nb[D], g.f);
    a.s0 = c * g.rx, a.s1 = c * g.ry;
    if constexpr (D == 3) a.s2 = c * g.rz;
    return a;
  }
};

// Pass 2 of particle i with its wide kernel of h (SurfaceFields::h_wide) over sf.wide.
template <int D, class T, int K>
Vec<D> wide_normal(const SurfaceFields<D>& sf, std::size_t i, const Vec<D>& x, T lambda_ref,
                   double h, double eps) {
  double s[12] = {};
  cross_sums<D, K, D, T>(sf.wide, WendlandC2<D>(h), x, false, &load_lambda<D, K, T>,
                         LambdaGradientPair<D, T, K>{lambda_ref}, s);
  Vec<D> sum;
  for (int d = 0; d < D; ++d) sum[d] = s[d];
  return normal_from_lambda_gradient<D>(sf.l_corr[i] * sum, sf.lambda[i], eps, h);
}

// lambda of the n particles as a column of type T padded like the packed state (the padding
// reads 0), after the coupling has set the buffers' lambda.
template <class T, int D>
const T* padded_lambda(SurfaceFields<D>& sf, std::size_t n) {
  auto& col = [&]() -> auto& {
    if constexpr (std::is_same_v<T, float>)
      return sf.lambda_f;
    else
      return sf.lambda_col;
  }
  ();
  col.resize(n + kBlockPad);
  std::fill(col.begin() + static_cast<std::ptrdiff_t>(n), col.end(), T(0));
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(n),
                 [&](std::int64_t i) { col[i] = static_cast<T>(sf.lambda[i]); });
  return col.data();
}

template <int D, class T>
void normals_pass(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  const LevelColumns<D>& cols, SurfaceFields<D>& sf) {
  sf.normal.resize(ps.size());  // every entry written below (0 for walls and skipped particles)
  const T* lambda_col = padded_lambda<T>(sf, ps.size());
  using S = SurfaceColumns<D, 2, T>;
  using Scratch = NormalsScratch<StencilSpans<D>>;
  const S src(cols, {volume_column<T>(cols), lambda_col});
  if (sf.sums_grad_w) sf.lambda_ranges.build(grid, lambda_col);
  auto body = [&](std::int64_t ii, Scratch& sc) {
    const auto i = static_cast<std::size_t>(ii);
    sf.normal[i] = Vec<D>{};
    if (ps.kind[i] == Kind::wall) return;
    const double lambda_i = sf.lambda[i];
    const bool difference = lambda_i >= prm.surface_tension.lambda_threshold;
    const T lambda_ref = static_cast<T>(difference ? lambda_i : 0.0);  // difference form
    const std::int64_t cell = grid.particle_cells()[i];
    const bool across = !sf.cross_hit.empty() && sf.cross_hit[i] != 0;
    const double h_wide = sf.h_wide.empty() ? 0.0 : sf.h_wide[i];
    if (difference && sf.sums_grad_w && !across) {  // the bound knows this level only
      lambda_range<D>(grid, cell, sf.lambda_ranges, sc);
      const double limit = prm.surface_tension.normal_epsilon * lambda_i / prm.h;
      if (normal_surely_zero<D, T>(sc.lo, sc.hi, lambda_ref, sf.l_corr[i], sf.grad_w[i], limit))
        return;  // the normal stays 0
    }
    const double eps = prm.surface_tension.normal_epsilon;
    if (h_wide > 0.0) {  // the own level too through the wide kernel, not the blocks
      sf.normal[i] = wide_normal<D, T, S::K>(sf, i, ps.pos[i], lambda_ref, h_wide, eps);
      return;
    }
    auto& sp = sc.spans;
    sp.of(grid, cell, Groups::fluid);
    T xi[3], xi_lo[3];
    src.self(i, xi, xi_lo);
    double s[12] = {}, unused = -1e300;
    auto pair = [=](const PairGeometryT<T>& g, const Neighbour<S::K, T>& nb) {
      return LambdaGradientPair<D, T, S::K>{lambda_ref}(g, nb);
    };
    sweep_spans<D, S::K, D, false, S::KL>(prm.kernel, xi, src.base, sp.span, sp.count, pair, s,
                                          unused, xi_lo);
    if (across) {
      cross_sums<D, S::K, D, T>(sf.cross, prm.kernel, ps.pos[i], false, &load_lambda<D, S::K, T>,
                                pair, s);
    }
    Vec<D> sum;
    for (int d = 0; d < D; ++d) sum[d] = s[d];
    sf.normal[i] = normal_from_lambda_gradient<D>(sf.l_corr[i] * sum, lambda_i, eps, prm.h);
  };
  exec::for_each_with<Scratch>(static_cast<std::int64_t>(ps.size()), kSurfaceChunk, body);
}

// Pass 3 of particle i over its block (columns x, V, n): the curvature sums of
// physics/surface_tension.hpp (kappa, a, b in s0..s2) over the neighbours that pass S_ij.
template <int D, class T>
CurvatureSums curvature_particle(const SolverParams<D>& prm, const SurfaceColumns<D, D + 1, T>& src,
                                 const StencilSpans<D>* sp, const T (&xi)[3], const T (&xi_lo)[3],
                                 const Vec<D, T>& n_i, const Mat<D, T>& l_i,
                                 const std::vector<CrossSource<D>>* cross, const Vec<D>& x_i,
                                 const WendlandC2<D>& kernel) {
  using S = SurfaceColumns<D, D + 1, T>;
  auto pair = [=](const PairGeometryT<T>& g, const Neighbour<S::K, T>& nb) {
    PairSumsT<T> s;
    Vec<D, T> n_j, r_ij;
    n_j[0] = nb[D + 1], n_j[1] = nb[D + 2], r_ij[0] = g.rx, r_ij[1] = g.ry;
    if constexpr (D == 3) n_j[2] = nb[2 * D], r_ij[2] = g.rz;
    const T vol_j = nb[D];
    const bool s_ij = curvature_filter<D>(norm2(n_j), dot(n_i, n_j));
    CurvatureSumsT<T> c;
    add_curvature_pair<D>(c, s_ij ? vol_j : T(0), n_i, n_j, T(-1) * r_ij, l_i * (g.f * r_ij));
    s.s0 = c.kappa, s.s1 = c.a, s.s2 = c.b;
    return s;
  };
  double s[12] = {}, unused = -1e300;
  if (sp != nullptr) {  // null: the wide kernel, over `cross` alone (its own level first)
    sweep_spans<D, S::K, 3, false, S::KL>(prm.kernel, xi, src.base, sp->span, sp->count, pair, s,
                                          unused, xi_lo);
  }
  if (cross != nullptr)
    cross_sums<D, S::K, 3, T>(*cross, kernel, x_i, false, &load_normal<D, S::K, T>, pair, s);
  return CurvatureSums{s[0], s[1], s[2]};
}

template <int D, class T>
void curvature_pass(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                    const LevelColumns<D>& cols, SurfaceFields<D>& sf) {
  const auto n = static_cast<std::int64_t>(ps.size());
  sf.curvature.resize(ps.size());  // every entry written below
  sf.acc_st.resize(ps.size());
  auto& normal_col = [&]() -> auto& {
    if constexpr (std::is_same_v<T, float>)
      return sf.normal_f;
    else
      return sf.normal_col;
  }
  ();
  for (int k = 0; k < D; ++k) {  // every entry written below; the padding reads 0
    normal_col[k].resize(ps.size() + kBlockPad);
    std::fill(normal_col[k].begin() + n, normal_col[k].end(), T(0));
  }
  exec::for_each(exec::in_shares, n, [&](std::int64_t i) {
    for (int k = 0; k < D; ++k) normal_col[k][i] = static_cast<T>(sf.normal[i][k]);
  });
  using S = SurfaceColumns<D, D + 1, T>;
  std::array<const T*, D + 1> extra{};
  extra[0] = volume_column<T>(cols);
  for (int k = 0; k < D; ++k) extra[k + 1] = normal_col[k].data();
  const S src(cols, extra);
  auto body = [&](std::int64_t ii, StencilSpans<D>& sp) {
    const auto i = static_cast<std::size_t>(ii);
    sf.curvature[i] = 0.0;
    sf.acc_st[i] = Vec<D>{};
    const Vec<D> n_i = sf.normal[i];
    if (ps.kind[i] == Kind::wall || norm2(n_i) == 0.0) return;
    const bool across = !sf.cross_hit.empty() && sf.cross_hit[i] != 0;
    const double h_wide = sf.h_wide.empty() ? 0.0 : sf.h_wide[i];
    T xi[3] = {}, xi_lo[3] = {};
    if (h_wide == 0.0) {
      sp.of(grid, grid.particle_cells()[i], Groups::fluid);
      src.self(i, xi, xi_lo);
    }
    const auto* sources = h_wide > 0.0 ? &sf.wide : (across ? &sf.cross : nullptr);
    const CurvatureSums sums =
        curvature_particle<D, T>(prm, src, h_wide > 0.0 ? nullptr : &sp, xi, xi_lo,
                                 vec_cast<T>(n_i), mat_cast<T>(sf.l_corr[i]), sources, ps.pos[i],
                                 h_wide > 0.0 ? WendlandC2<D>(h_wide) : prm.kernel);
    const SurfaceTensionParams& st = prm.surface_tension;
    const double kappa = st.curvature_correction ? corrected_curvature<D>(sums) : sums.kappa;
    sf.curvature[i] = kappa;
    const double delta = surface_delta(norm(sf.grad_c[i]), sf.shepard[i]);
    const double k_force = st.surface_offset ? curvature_at_surface<D>(kappa, prm.dp) : kappa;
    sf.acc_st[i] = csf_acceleration<D>(prm.sigma, k_force, n_i, delta, ps.rho[i]);
  };
  exec::for_each_with<StencilSpans<D>>(n, kSurfaceChunk, body);
}

}  // namespace

template <int D>
void surface_sums(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  const LevelColumns<D>& cols, SurfaceFields<D>& sf) {
  with_pair_type(prm.precision,
                 [&](auto t) { sums_pass<D, decltype(t)>(prm, ps, grid, cols, sf, true); });
}

namespace {

// Pass 1 with its fluid rows handed to the level's next force pass as `mode` where `can` and no
// field is summed across levels; otherwise the whole pass. Returns whether it handed them over.
template <int D>
bool sums_handing_over(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                       const CellGrid<D>& grid, const LevelColumns<D>& cols, SurfaceFields<D>& sf,
                       bool can, Pass1InForces mode) {
  const bool in_forces = can && sf.cross.empty() && sf.h_wide.empty();
  with_pair_type(prm.precision,
                 [&](auto t) { sums_pass<D, decltype(t)>(prm, ps, grid, cols, sf, !in_forces); });
  sf.in_forces = in_forces ? mode : Pass1InForces::none;
  return in_forces;
}

}  // namespace

template <int D>
bool surface_sums_for_shifting(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                               const CellGrid<D>& grid, const LevelColumns<D>& cols,
                               SurfaceFields<D>& sf) {
  return sums_handing_over(prm, ps, grid, cols, sf, true, Pass1InForces::shifting);
}

template <int D>
bool surface_sums_in_forces(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                            const CellGrid<D>& grid, const LevelColumns<D>& cols,
                            SurfaceFields<D>& sf) {
  return sums_handing_over(prm, ps, grid, cols, sf, kForcePassSumsPass1<D> && prm.sigma > 0.0,
                           Pass1InForces::full);
}

template <int D>
void surface_sums(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                  SurfaceFields<D>& sf) {
  sf.own.pack_geometry(ps, grid, prm.precision);
  surface_sums(prm, ps, grid, sf.own, sf);
}

template <int D>
void surface_normals(const SolverParams<D>& prm, const ParticleSet<D>& ps, const CellGrid<D>& grid,
                     const LevelColumns<D>& cols, SurfaceFields<D>& sf) {
  with_pair_type(prm.precision,
                 [&](auto t) { normals_pass<D, decltype(t)>(prm, ps, grid, cols, sf); });
}

template <int D>
void surface_curvature_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                             const CellGrid<D>& grid, const LevelColumns<D>& cols,
                             SurfaceFields<D>& sf) {
  with_pair_type(prm.precision,
                 [&](auto t) { curvature_pass<D, decltype(t)>(prm, ps, grid, cols, sf); });
}

template <int D>
void surface_tension_force(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                           const CellGrid<D>& grid, const LevelColumns<D>& cols,
                           SurfaceFields<D>& sf) {
  surface_normals(prm, ps, grid, cols, sf);
  surface_curvature_force(prm, ps, grid, cols, sf);
}

template void surface_sums<2>(const SolverParams<2>&, const ParticleSet<2>&, const CellGrid<2>&,
                              SurfaceFields<2>&);
template void surface_sums<2>(const SolverParams<2>&, const ParticleSet<2>&, const CellGrid<2>&,
                              const LevelColumns<2>&, SurfaceFields<2>&);
template bool surface_sums_for_shifting<2>(const SolverParams<2>&, const ParticleSet<2>&,
                                           const CellGrid<2>&, const LevelColumns<2>&,
                                           SurfaceFields<2>&);
template bool surface_sums_in_forces<2>(const SolverParams<2>&, const ParticleSet<2>&,
                                        const CellGrid<2>&, const LevelColumns<2>&,
                                        SurfaceFields<2>&);
template bool surface_sums_in_forces<3>(const SolverParams<3>&, const ParticleSet<3>&,
                                        const CellGrid<3>&, const LevelColumns<3>&,
                                        SurfaceFields<3>&);
template bool surface_sums_for_shifting<3>(const SolverParams<3>&, const ParticleSet<3>&,
                                           const CellGrid<3>&, const LevelColumns<3>&,
                                           SurfaceFields<3>&);
template void surface_normals<2>(const SolverParams<2>&, const ParticleSet<2>&, const CellGrid<2>&,
                                 const LevelColumns<2>&, SurfaceFields<2>&);
template void surface_curvature_force<2>(const SolverParams<2>&, const ParticleSet<2>&,
                                         const CellGrid<2>&, const LevelColumns<2>&,
                                         SurfaceFields<2>&);
template void surface_tension_force<2>(const SolverParams<2>&, const ParticleSet<2>&,
                                       const CellGrid<2>&, const LevelColumns<2>&,
                                       SurfaceFields<2>&);
template void surface_sums<3>(const SolverParams<3>&, const ParticleSet<3>&, const CellGrid<3>&,
                              SurfaceFields<3>&);
template void surface_sums<3>(const SolverParams<3>&, const ParticleSet<3>&, const CellGrid<3>&,
                              const LevelColumns<3>&, SurfaceFields<3>&);
template void surface_normals<3>(const SolverParams<3>&, const ParticleSet<3>&, const CellGrid<3>&,
                                 const LevelColumns<3>&, SurfaceFields<3>&);
template void surface_curvature_force<3>(const SolverParams<3>&, const ParticleSet<3>&,
                                         const CellGrid<3>&, const LevelColumns<3>&,
                                         SurfaceFields<3>&);
template void surface_tension_force<3>(const SolverParams<3>&, const ParticleSet<3>&,
                                       const CellGrid<3>&, const LevelColumns<3>&,
                                       SurfaceFields<3>&);

}  // namespace vrsph
