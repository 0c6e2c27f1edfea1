// Small fixed-size vector and matrix maths for the numeric core (D = 2 or 3).
// Plain aggregates so that arrays of them are contiguous and trivially copyable.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace vrsph {

template <int D>
struct Vec {
  static_assert(D == 2 || D == 3, "vrsph supports 2D and 3D");
  std::array<double, D> c{};

  constexpr double& operator[](int k) { return c[static_cast<std::size_t>(k)]; }
  constexpr double operator[](int k) const { return c[static_cast<std::size_t>(k)]; }

  constexpr Vec& operator+=(const Vec& o) {
    for (int k = 0; k < D; ++k) (*this)[k] += o[k];
    return *this;
  }
  constexpr Vec& operator-=(const Vec& o) {
    for (int k = 0; k < D; ++k) (*this)[k] -= o[k];
    return *this;
  }
  constexpr Vec& operator*=(double s) {
    for (int k = 0; k < D; ++k) (*this)[k] *= s;
    return *this;
  }
  friend constexpr Vec operator+(Vec a, const Vec& b) { return a += b; }
  friend constexpr Vec operator-(Vec a, const Vec& b) { return a -= b; }
  friend constexpr Vec operator*(Vec a, double s) { return a *= s; }
  friend constexpr Vec operator*(double s, Vec a) { return a *= s; }
  friend constexpr Vec operator-(Vec a) { return a *= -1.0; }
  friend constexpr bool operator==(const Vec&, const Vec&) = default;
};

template <int D>
constexpr double dot(const Vec<D>& a, const Vec<D>& b) {
  double s = 0.0;
  for (int k = 0; k < D; ++k) s += a[k] * b[k];
  return s;
}

template <int D>
constexpr double norm2(const Vec<D>& a) {
  return dot(a, a);
}

template <int D>
inline double norm(const Vec<D>& a) {
  return std::sqrt(norm2(a));
}

// Index of the vertical axis (the one gravity usually points along): y in 2D, z in 3D.
template <int D>
constexpr int vertical_axis() {
  return D - 1;
}

}  // namespace vrsph
