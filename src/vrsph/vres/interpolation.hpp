// Buffer-particle values of variable resolution (docs/physics.md section 10; Ricci, Vacondio &
// Tafuni 2024): the density and velocity at a point, taken from the fluid particles of the other
// ("donor") level by first-order consistent corrected SPH (Liu & Liu 2006, "Restoring particle
// consistency in smoothed particle hydrodynamics", Appl. Numer. Math. 56:19-36).
//
// Idea: a first-order Taylor expansion about the point x, f_j = f + grad f . (x_j - x), is
// multiplied by V_j W and by V_j grad W and summed over the donors j. This gives D+1 linear
// equations in the D+1 unknowns (f, grad f):
//     A [f, grad f]^T = b,
//     A = sum_j V_j [W, grad W](x - x_j) (outer) [1, (x_j - x)],   b = sum_j V_j f_j [W, grad W],
// with V_j = m_j / rho_j and grad W(x - x_j) = F(r) (x - x_j). Linear fields are reproduced
// exactly, whatever the particle disorder and however truncated the support (near a free
// surface or the edge of the donor region), as long as A is well conditioned.
// The same matrix serves f = rho and every velocity component: one LU factorisation (partial
// pivoting), D+1 right-hand sides.
//
// Safeguards, as in DualSPHysics' VRes (same first-order Liu method, threshold 100):
//  - the system is written in dimensionless form (rows [W, h grad W], columns [1, (x_j - x)/h],
//    unknowns [f, h grad f]); when its condition number ||A||inf ||A^-1||inf exceeds cond_limit
//    (default 100) the result falls back to the Shepard average f = sum V f W / sum V W, which
//    keeps constants exact and never overshoots the donor values;
//  - when the Shepard sum sum V W is below 0.05 there is no fluid at the point: rho = vel = 0,
//    corrected = false, and the caller deletes the buffer particle.
// The dimensionless form matters: written in metres, A has entries of order 1, h and 1/h, and a
// plain ||A|| ||A^-1|| would be about 1 in the bulk but grow like 1/h^2 near an edge
// (DualSPHysics rescales its estimate by a power of h instead). With the diagonal scaling the
// number does not depend on the units: it is of order 1 in the bulk, larger on a free surface,
// and passes the limit a little beyond it (values: docs/validation.md, "Figures formerly in code
// comments"; tests/test_vres_interpolation.cpp).
//
// Only Kind::fluid donors count: buffer particles (themselves interpolated) and walls are skipped.
// The donor grid must have been sorted since the donor particles last moved, as for every pass.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "vrsph/core/kernel.hpp"
#include "vrsph/core/vec.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/vres/shepard_lanes.hpp"

namespace vrsph {

template <int D>
struct InterpolatedState {
  double rho = 0.0;             // kg/m^3
  Vec<D> vel{};                 // m/s
  double shepard = 0.0;         // sum_j V_j W(x - x_j): donor support; < 0.05 means no fluid here
  double shepard_walls = 0.0;   // sum_j V_j W(x - x_j) over the donor level's wall particles
  double shepard_buffer = 0.0;  // the same over the donor level's buffer particles
  bool corrected = false;  // true: first-order corrected; false: Shepard fallback (or no support)
  // Dimensionless cond_inf(A): infinity where singular; 0 where there is no support, or where
  // the Shepard average was taken without forming A (shepard_fill above 1).
  double cond = 0.0;
};

inline constexpr double kVresShepardMin = 0.05;  // below: no fluid at the point
inline constexpr double kVresCondLimit = 100.0;  // above: Shepard fallback

// Smoothed fill of the donor level at a point: sum_j V_j W over all its particles (fluid, buffer
// and walls; next to the interface the donor's buffer completes the support, where its fluid alone
// sums to about 1/2). About 1 inside the fluid, it falls through 1/2 at a free surface (on a flat
// lattice face, near the plane dp/2 beyond the outer row). Below 1/2 a point lies outside the
// donor's fluid.
// With numerics.vres_buffer_fill_min > 0, buffer particles are deleted below that fill (0.4 in
// cases/droplet_vr_2d.toml, a little outside the surface): the outer buffer row of a finer level
// sits not far above 1/2 and its fill moves with the particle disorder, and deleting at 1/2 (with
// creation also restricted to fill >= 1/2) stirred the VR droplet. Values: docs/validation.md,
// "Figures formerly in code comments".

template <int D>
inline double donor_fill(const InterpolatedState<D>& s) {
  return s.shepard + s.shepard_buffer + s.shepard_walls;
}

// Values at point x from the Kind::fluid particles of a donor level (particle set, its cell grid
// after a sort, its kernel). Points with no donor in reach (also beyond the particle cloud or
// the domain) return shepard = 0. Forms the donor state (DonorState) for this one point: a batch
// of points forms it once and calls interpolate_from_donor.
// Local time stepping: `a` in [0, 1] is the time within the donor's last step, as a fraction of
// it, and each donor's position, velocity and density are interpolated linearly between the
// step's start (pos0, vel0, rho0) and its end; a = 1 (the default) reads the current state. The
// neighbours are found with the grid of the current positions: a donor moves a small fraction
// of h in one step, so the only ones missed sit at the edge of the support, where W vanishes
// to fourth order.
template <int D>
// shepard_fill (numerics.vres_shepard_fill; not part of Ricci et al. 2024): where the donor's
// fill (donor_fill) is below it, the Shepard average instead of the first-order values (0: never).
InterpolatedState<D> interpolate_from_level(const Vec<D>& x, const ParticleSet<D>& donors,
                                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                                            double cond_limit = kVresCondLimit, double a = 1.0,
                                            double shepard_fill = 0.0);

// The donors as columns for the Shepard sums in lanes (vres/shepard_lanes.hpp): value[0] = rho,
// value[1 + k] = vel_k.
template <int D>
using ShepardColumns = LaneColumns<D>;

// The arrays a DonorState fills, kept by its owner from one batch to the next: formed anew for
// every batch, they were some 200 kB allocated and freed per level step, and the page faults of
// the heap growing and shrinking cost more than the sums they served.
template <int D>
struct DonorStorage {
  std::vector<Vec<D>> pos_a, vel_a;
  std::vector<double> rho_a, vol;
  ShepardColumns<D> columns;
};

// A donor level as a batch of interpolations reads it: the positions, velocities and densities of
// its particles at the fraction a of its last step (as interpolate_from_level forms them), formed
// once for all the points of the batch (for a = 1 the particle set's own arrays), and their
// volumes m_j / rho_j (each point's support holds some 20 donors, and every donor serves several
// points: one division per donor and batch instead of one per donor and point, the same bits).
// With `lanes`, the state also holds the donors as columns (ShepardColumns): a batch whose points
// take the Shepard average first (shepard_fill above 1) sums them in fixed lanes, vectorised,
// instead of donor by donor (interpolate_values).
template <int D>
class DonorState {
 public:
  DonorState(const ParticleSet<D>& ps, const CellGrid<D>& grid, const WendlandC2<D>& kernel,
             double a, DonorStorage<D>& store, bool lanes = false);
  DonorState(const DonorState&) = delete;
  DonorState& operator=(const DonorState&) = delete;

  const ParticleSet<D>& ps;
  const CellGrid<D>& grid;
  const WendlandC2<D>& kernel;
  const Vec<D>* pos = nullptr;
  const Vec<D>* vel = nullptr;
  const double* rho = nullptr;
  const double* vol = nullptr;                 // m_j / rho_j
  const ShepardColumns<D>* columns = nullptr;  // the donors as columns; null without `lanes`

 private:
  void fill_columns(ShepardColumns<D>& c) const;
};

// interpolate_from_level from a donor state, donor by donor whether or not the state holds columns
// (the reference the sums in lanes are tested against).
template <int D>
InterpolatedState<D> interpolate_from_donor(const Vec<D>& x, const DonorState<D>& donor,
                                            double cond_limit, double shepard_fill);

// As interpolate_from_donor, except that with a donor state holding columns and shepard_fill above
// 1 the Shepard average comes from the sums in lanes: the same values but for the order of the
// sums (round-off), at a third of the cost. Where the fill reaches shepard_fill, the first-order
// values of interpolate_from_donor.
template <int D>
InterpolatedState<D> interpolate_values(const Vec<D>& x, const DonorState<D>& donor,
                                        double cond_limit, double shepard_fill);

// The same for many points, in parallel (OpenMP, static schedule): out[i] for points[i]. out is
// resized to points.size() (no allocation once it is large enough).
template <int D>
void interpolate_from_level(const std::vector<Vec<D>>& points, const ParticleSet<D>& donors,
                            const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                            std::vector<InterpolatedState<D>>& out,
                            double cond_limit = kVresCondLimit);

// Shepard average of a per-particle field of the donor level's fluid at x:
// sum_j V_j f_j W / sum_j V_j W over Kind::fluid donors; `fallback` where the donor support is
// below kVresShepardMin. T is double or Vec<D>. Used to give buffer particles the surface-tension
// quantities (lambda, normals) of the other level where their own support reaches beyond the
// buffer shell and would see a free surface that is not there.
template <int D, class T>
T shepard_field(const Vec<D>& x, const ParticleSet<D>& donors, const CellGrid<D>& grid,
                const WendlandC2<D>& kernel, const std::vector<T>& field, T fallback);

// The number of components of a field of type T (double or Vec<D>).
template <int D, class T>
inline constexpr int kComponents = std::is_same_v<T, double> ? 1 : D;

// The donor level's fluid and a field of it as columns for shepard_field in lanes: x, V_j of
// fluid donors (0 for buffer donors), the field's components.
template <int D, class T>
void fill_field_columns(const ParticleSet<D>& donors, const std::vector<T>& field,
                        LaneColumns<D>& cols);

// shepard_field from those columns, summed in lanes: the same average but for the order of the
// sums (round-off), a third of the cost.
template <int D, class T>
T shepard_field(const Vec<D>& x, const CellGrid<D>& grid, const WendlandC2<D>& kernel,
                const LaneColumns<D>& cols, T fallback);

// Small dense N x N LU factorisation with partial pivoting (Golub & Van Loan, algorithm 3.4.1):
// P A = L U with L unit lower triangular, both stored in lu. A pivot below 1e-14 ||A||inf marks
// the matrix singular (solve() must not be called then).
template <int N>
struct SmallLu {
  using Matrix = std::array<std::array<double, N>, N>;  // m[row][col]
  using Vector = std::array<double, N>;

  Matrix lu{};
  std::array<int, N> perm{};  // row perm[i] of A is row i of P A
  double norm_inf = 0.0;      // ||A||inf (largest absolute row sum)
  bool singular = false;

  explicit SmallLu(const Matrix& a);

  // x with A x = b.
  Vector solve(const Vector& b) const;

  // ||A||inf ||A^-1||inf, the columns of A^-1 solved one by one; infinity when singular.
  double cond_inf() const;

 private:
  // Partial pivoting at step k: the row p >= k with the largest |lu[p][k]| (the first of equals).
  int pivot_row(int k) const;
  // Gaussian elimination below the pivot lu[k][k]: the multipliers l_ik = lu[i][k] / lu[k][k]
  // are stored in column k of L, and row k times l_ik is subtracted from each row i > k.
  void eliminate_below(int k);
};

template <int N>
inline SmallLu<N>::SmallLu(const Matrix& a) : lu(a) {
  for (int i = 0; i < N; ++i) {
    perm[i] = i;
    double s = 0.0;
    for (int j = 0; j < N; ++j) s += std::fabs(a[i][j]);
    norm_inf = std::max(norm_inf, s);
  }
  const double tiny = 1e-14 * norm_inf;
  for (int k = 0; k < N; ++k) {
    const int p = pivot_row(k);
    if (!(std::fabs(lu[p][k]) > tiny)) {  // also catches NaN
      singular = true;
      return;
    }
    std::swap(lu[p], lu[k]);
    std::swap(perm[p], perm[k]);
    eliminate_below(k);
  }
}

template <int N>
inline int SmallLu<N>::pivot_row(int k) const {
  int p = k;
  for (int i = k + 1; i < N; ++i)
    if (std::fabs(lu[i][k]) > std::fabs(lu[p][k])) p = i;
  return p;
}

template <int N>
inline void SmallLu<N>::eliminate_below(int k) {
  const double inv_pivot = 1.0 / lu[k][k];
  for (int i = k + 1; i < N; ++i) {
    const double l = lu[i][k] * inv_pivot;
    lu[i][k] = l;
    for (int j = k + 1; j < N; ++j) lu[i][j] -= l * lu[k][j];
  }
}

// The two substitutions stay in one body, and the row sums in the constructor's first loop:
// as separate functions (-march=native) GCC vectorised and FMA-contracted the solves of
// interpolation.cpp differently, which changed results in the last bits.
template <int N>
inline typename SmallLu<N>::Vector SmallLu<N>::solve(const Vector& b) const {
  Vector y{};
  for (int i = 0; i < N; ++i) {  // L y = P b
    double s = b[perm[i]];
    for (int j = 0; j < i; ++j) s -= lu[i][j] * y[j];
    y[i] = s;
  }
  for (int i = N - 1; i >= 0; --i) {  // U x = y
    double s = y[i];
    for (int j = i + 1; j < N; ++j) s -= lu[i][j] * y[j];
    y[i] = s / lu[i][i];
  }
  return y;
}

template <int N>
inline double SmallLu<N>::cond_inf() const {
  if (singular) return std::numeric_limits<double>::infinity();
  std::array<double, N> row_sum{};
  for (int c = 0; c < N; ++c) {
    Vector e{};
    e[c] = 1.0;
    const Vector col = solve(e);
    for (int r = 0; r < N; ++r) row_sum[r] += std::fabs(col[r]);
  }
  double inv_norm = 0.0;
  for (int r = 0; r < N; ++r) inv_norm = std::max(inv_norm, row_sum[r]);
  return norm_inf * inv_norm;
}

}  // namespace vrsph
