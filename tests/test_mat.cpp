// Small symmetric matrices of the surface-tension model (core/mat.hpp) against Eigen: the smallest
// eigenvalue by cyclic Jacobi rotations in 3D and by the closed form in 2D, on random symmetric
// matrices (fixed seed) of several kinds: generic, nearly diagonal, with repeated eigenvalues,
// badly scaled; and the cofactor inverse (inverse(M) M = I).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

// Eigen with -march=native trips -Wmaybe-uninitialized inside GCC 12 AVX-512 intrinsics headers.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <eigen3/Eigen/Dense>

#include "vrsph/core/mat.hpp"

namespace vrsph {
namespace {

template <int D>
Mat<D> from_eigen(const Eigen::Matrix<double, D, D>& e) {
  Mat<D> m;
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) m(r, c) = e(r, c);
  return m;
}

// Random orthogonal matrix (Q of a QR factorisation of a Gaussian matrix).
template <int D>
Eigen::Matrix<double, D, D> random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Matrix<double, D, D> a;
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) a(r, c) = g(rng);
  Eigen::HouseholderQR<Eigen::Matrix<double, D, D>> qr(a);
  return qr.householderQ();
}

// Symmetric test matrix of kind k (0..4), exactly symmetric.
template <int D>
Eigen::Matrix<double, D, D> random_symmetric(int kind, std::mt19937_64& rng) {
  using M = Eigen::Matrix<double, D, D>;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> e10(-8.0, 8.0);
  M m;
  switch (kind) {
    case 0: {  // generic: entries uniform in [-s, s], random scale s
      const double s = std::pow(10.0, 3.0 * u(rng));
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c) m(r, c) = s * u(rng);
      break;
    }
    case 1: {  // nearly diagonal: off-diagonal entries 1e-14 .. 1e-6 of the diagonal
      m.setZero();
      for (int r = 0; r < D; ++r) m(r, r) = 2.0 * u(rng);
      const double eps = std::pow(10.0, -10.0 + 4.0 * u(rng));
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c)
          if (r != c) m(r, c) = eps * u(rng);
      break;
    }
    case 2: {  // repeated eigenvalues (all D equal, or D - 1 equal), random basis
      Eigen::Matrix<double, D, 1> lam;
      const double a = u(rng), b = u(rng);
      const int pattern = static_cast<int>(rng() % 3);
      for (int k = 0; k < D; ++k) lam(k) = a;
      if (pattern == 1) lam(0) = b;              // smallest may be the single one or the pair
      if (pattern == 2) lam(D - 1) = a + 1e-13;  // nearly repeated
      const M q = random_rotation<D>(rng);
      m = q * lam.asDiagonal() * q.transpose();
      break;
    }
    case 3: {  // badly scaled: eigenvalues spread over 16 decades, random basis
      Eigen::Matrix<double, D, 1> lam;
      for (int k = 0; k < D; ++k) lam(k) = (u(rng) < 0.0 ? -1.0 : 1.0) * std::pow(10.0, e10(rng));
      const M q = random_rotation<D>(rng);
      m = q * lam.asDiagonal() * q.transpose();
      break;
    }
    default: {  // graded: S A S with S = diag(1, 1e-4, 1e4) (rows/columns of very different size)
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c) m(r, c) = u(rng);
      const double s[3] = {1.0, 1e-4, 1e4};
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c) m(r, c) *= s[r] * s[c];
      break;
    }
  }
  return 0.5 * (m + m.transpose());
}

const char* kind_name(int kind) {
  static const char* names[] = {"generic", "nearly diagonal", "repeated", "badly scaled", "graded"};
  return names[kind];
}

constexpr int kKinds = 5;
constexpr int kPerKind = 240;  // 1200 matrices per dimension

TEST(MatEigen, JacobiMinEigenvalueMatchesEigen3D) {
  std::mt19937_64 rng(20240611);
  double worst = 0.0, worst_all = 0.0;
  for (int kind = 0; kind < kKinds; ++kind) {
    double worst_kind = 0.0;
    for (int t = 0; t < kPerKind; ++t) {
      const Eigen::Matrix3d e = random_symmetric<3>(kind, rng);
      const Mat<3> m = from_eigen<3>(e);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(e, Eigen::EigenvaluesOnly);
      ASSERT_EQ(es.info(), Eigen::Success);
      const double scale = e.norm();  // Frobenius norm
      ASSERT_GT(scale, 0.0);
      const double ref_min = es.eigenvalues().minCoeff();
      const double got_min = min_eigenvalue<3>(m);
      const double err = std::abs(got_min - ref_min) / scale;
      worst_kind = std::max(worst_kind, err);
      EXPECT_LT(err, 1e-12) << kind_name(kind) << " #" << t << ": jacobi " << got_min << ", eigen "
                            << ref_min << ", |M| " << scale;
      // All three eigenvalues (sorted) agree as well.
      std::array<double, 3> all = eigenvalues_sym3_jacobi(m);
      std::sort(all.begin(), all.end());
      for (int k = 0; k < 3; ++k) {
        const double ek = std::abs(all[k] - es.eigenvalues()(k)) / scale;
        worst_all = std::max(worst_all, ek);
        EXPECT_LT(ek, 1e-12) << kind_name(kind) << " #" << t << " eigenvalue " << k;
      }
      // The trace is preserved by the rotations.
      EXPECT_NEAR(all[0] + all[1] + all[2], e.trace(), 1e-12 * scale);
    }
    std::printf("[ mat 3D ] %-16s min eigenvalue: max |jacobi - eigen| / |M| = %.2e\n",
                kind_name(kind), worst_kind);
    worst = std::max(worst, worst_kind);
  }
  std::printf("[ mat 3D ] all: min %.2e, all eigenvalues %.2e\n", worst, worst_all);
}

TEST(MatEigen, Jacobi3DSpecialCases) {
  // Already diagonal (no rotation at all), zero, and the lattice-like M = m I.
  Mat<3> d;
  d(0, 0) = 3.0;
  d(1, 1) = -2.0;
  d(2, 2) = 0.5;
  EXPECT_EQ(min_eigenvalue<3>(d), -2.0);
  EXPECT_EQ(min_eigenvalue<3>(Mat<3>{}), 0.0);
  Mat<3> s = Mat<3>::identity();
  for (int k = 0; k < 3; ++k) s(k, k) = 0.979;
  EXPECT_EQ(min_eigenvalue<3>(s), 0.979);
  // A flat-surface-like M: one direction half supported.
  Mat<3> f = Mat<3>::identity();
  f(2, 2) = 0.49;
  f(0, 2) = f(2, 0) = 0.02;
  Eigen::Matrix3d e;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) e(r, c) = f(r, c);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(e);
  EXPECT_NEAR(min_eigenvalue<3>(f), es.eigenvalues().minCoeff(), 1e-15);
}

TEST(MatEigen, ClosedForm2DMatchesEigen) {
  std::mt19937_64 rng(7);
  double worst = 0.0;
  for (int kind = 0; kind < kKinds; ++kind) {
    for (int t = 0; t < kPerKind; ++t) {
      const Eigen::Matrix2d e = random_symmetric<2>(kind, rng);
      const Mat<2> m = from_eigen<2>(e);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(e, Eigen::EigenvaluesOnly);
      const double scale = e.norm();
      const double ref = es.eigenvalues().minCoeff();
      const double got = min_eigenvalue<2>(m);
      const double err = std::abs(got - ref) / scale;
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-12) << kind_name(kind) << " #" << t << ": closed form " << got << ", eigen "
                            << ref;
      EXPECT_NEAR(min_eigenvalue_sym2(e(0, 0), e(0, 1), e(1, 1)), ref, 1e-12 * scale);
    }
  }
  std::printf("[ mat 2D ] closed form: max |closed - eigen| / |M| = %.2e\n", worst);
  // Slightly unsymmetric input: the 2D form uses the mean of the off-diagonal pair.
  Mat<2> u;
  u(0, 0) = 1.0;
  u(1, 1) = 0.5;
  u(0, 1) = 0.1 + 1e-12;
  u(1, 0) = 0.1 - 1e-12;
  EXPECT_NEAR(min_eigenvalue<2>(u), min_eigenvalue_sym2(1.0, 0.1, 0.5), 1e-15);
}

template <int D>
void check_inverse(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  int tested = 0;
  for (int t = 0; t < 1000; ++t) {
    // Symmetric (as M_i is) for half of them, general for the rest; random scale.
    Eigen::Matrix<double, D, D> e;
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) e(r, c) = u(rng);
    if (t % 2 == 0) e = 0.5 * (e + e.transpose()).eval();
    e *= std::pow(10.0, 4.0 * u(rng));
    const double cond = e.norm() * e.inverse().norm();
    if (!(cond < 1e6)) continue;  // the caller guarantees a well-conditioned M (lambda >= 0.1)
    ++tested;
    const Mat<D> m = from_eigen<D>(e);
    const Mat<D> inv = inverse(m);
    // inverse(M) * M = I and M * inverse(M) = I, column by column through operator*(Mat, Vec).
    for (int c = 0; c < D; ++c) {
      Vec<D> col, icol;
      for (int r = 0; r < D; ++r) {
        col[r] = m(r, c);
        icol[r] = inv(r, c);
      }
      const Vec<D> a = inv * col, b = m * icol;
      for (int r = 0; r < D; ++r) {
        const double want = r == c ? 1.0 : 0.0;
        const double err = std::max(std::abs(a[r] - want), std::abs(b[r] - want));
        worst = std::max(worst, err / cond);
        EXPECT_NEAR(a[r], want, 1e-14 * cond) << "trial " << t;
        EXPECT_NEAR(b[r], want, 1e-14 * cond) << "trial " << t;
      }
    }
    // Against Eigen's inverse.
    const Eigen::Matrix<double, D, D> ref = e.inverse();
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c)
        EXPECT_NEAR(inv(r, c), ref(r, c), 1e-13 * cond * ref.norm()) << "trial " << t;
  }
  EXPECT_GT(tested, 900);
  std::printf("[ mat %dD ] inverse: %d matrices, max |inv M - I| / cond = %.2e\n", D, tested,
              worst);
}

TEST(MatInverse, InverseTimesMatrixIsIdentity2D) { check_inverse<2>(11); }
TEST(MatInverse, InverseTimesMatrixIsIdentity3D) { check_inverse<3>(13); }

TEST(MatInverse, DeterminantAndIdentity) {
  EXPECT_EQ(determinant(Mat<2>::identity()), 1.0);
  EXPECT_EQ(determinant(Mat<3>::identity()), 1.0);
  Mat<3> m;
  m(0, 0) = 2.0;
  m(0, 1) = 1.0;
  m(1, 0) = 1.0;
  m(1, 1) = 3.0;
  m(2, 2) = 4.0;
  m(0, 2) = 0.5;
  m(2, 0) = -0.5;
  Eigen::Matrix3d e;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) e(r, c) = m(r, c);
  EXPECT_NEAR(determinant(m), e.determinant(), 1e-14);
  // Unsymmetric 3D inverse: transposition errors in the cofactors would show here.
  const Mat<3> inv = inverse(m);
  const Eigen::Matrix3d ref = e.inverse();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(inv(r, c), ref(r, c), 1e-14);
}

}  // namespace
}  // namespace vrsph
