// Small symmetric D x D matrices (D = 2, 3) for the correction matrix of the surface-tension
// model: product with a vector, inverse, and the smallest eigenvalue (closed form in 2D, cyclic
// Jacobi rotations in 3D).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "vrsph/core/vec.hpp"

namespace vrsph {

// T: the element type (float for the mixed precision's pair terms; the rest is double).
template <int D, class T = double>
struct Mat {
  std::array<std::array<T, D>, D> a{};  // a[row][col]

  static Mat identity() {
    Mat m;
    for (int k = 0; k < D; ++k) m.a[k][k] = T(1);
    return m;
  }
  T operator()(int r, int c) const { return a[r][c]; }
  T& operator()(int r, int c) { return a[r][c]; }
};

template <int D, class T>
inline Vec<D, T> operator*(const Mat<D, T>& m, const Vec<D, T>& v) {
  Vec<D, T> out;
  for (int r = 0; r < D; ++r) {
    T s = 0;
    for (int c = 0; c < D; ++c) s += m.a[r][c] * v[c];
    out[r] = s;
  }
  return out;
}

// The same matrix in element type U.
template <class U, int D, class T>
inline Mat<D, U> mat_cast(const Mat<D, T>& m) {
  Mat<D, U> r;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) r.a[i][j] = static_cast<U>(m.a[i][j]);
  return r;
}

template <int D>
inline double determinant(const Mat<D>& m) {
  if constexpr (D == 2) {
    return m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
  } else {
    return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
           m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
           m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
  }
}

// Inverse by cofactors; the caller guarantees det != 0.
template <int D>
inline Mat<D> inverse(const Mat<D>& m) {
  const double inv_det = 1.0 / determinant(m);
  Mat<D> r;
  if constexpr (D == 2) {
    r(0, 0) = m(1, 1) * inv_det;
    r(0, 1) = -m(0, 1) * inv_det;
    r(1, 0) = -m(1, 0) * inv_det;
    r(1, 1) = m(0, 0) * inv_det;
  } else {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        r(i, j) = (m(i1, j1) * m(i2, j2) - m(i1, j2) * m(i2, j1)) * inv_det;
      }
  }
  return r;
}

// Smallest eigenvalue of a symmetric 2 x 2 matrix: (a + d)/2 - sqrt(((a - d)/2)^2 + b^2).
inline double min_eigenvalue_sym2(double a, double b, double d) {
  const double mean = 0.5 * (a + d), half = 0.5 * (a - d);
  return mean - std::sqrt(half * half + b * b);
}

// Eigenvalues of a symmetric 3 x 3 matrix by cyclic Jacobi rotations (Golub & Van Loan,
// algorithm 8.4.3): sweeps over the off-diagonal pairs until they vanish to round-off.
inline std::array<double, 3> eigenvalues_sym3_jacobi(Mat<3> m, int max_sweeps = 12) {
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    const double off = m(0, 1) * m(0, 1) + m(0, 2) * m(0, 2) + m(1, 2) * m(1, 2);
    const double diag = m(0, 0) * m(0, 0) + m(1, 1) * m(1, 1) + m(2, 2) * m(2, 2);
    if (off <= 1e-30 * diag || off == 0.0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (m(p, q) == 0.0) continue;
        // Rotation angle that zeroes m(p, q): tan(2 theta) = 2 m_pq / (m_qq - m_pp).
        const double tau = (m(q, q) - m(p, p)) / (2.0 * m(p, q));
        const double t = (tau >= 0.0 ? 1.0 : -1.0) / (std::fabs(tau) + std::sqrt(1.0 + tau * tau));
        const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
        for (int k = 0; k < 3; ++k) {  // columns p, q of m G
          const double mkp = m(k, p), mkq = m(k, q);
          m(k, p) = c * mkp - s * mkq;
          m(k, q) = s * mkp + c * mkq;
        }
        for (int k = 0; k < 3; ++k) {  // rows p, q of G^T (m G)
          const double mpk = m(p, k), mqk = m(q, k);
          m(p, k) = c * mpk - s * mqk;
          m(q, k) = s * mpk + c * mqk;
        }
      }
  }
  return {m(0, 0), m(1, 1), m(2, 2)};
}

template <int D>
inline double min_eigenvalue(const Mat<D>& m) {
  if constexpr (D == 2) {
    return min_eigenvalue_sym2(m(0, 0), 0.5 * (m(0, 1) + m(1, 0)), m(1, 1));
  } else {
    const auto e = eigenvalues_sym3_jacobi(m);
    return std::min({e[0], e[1], e[2]});
  }
}

}  // namespace vrsph
