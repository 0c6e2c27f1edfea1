// Small fixed-size vector and matrix maths for the numeric core (D = 2 or 3).
// Plain aggregates so that arrays of them are contiguous and trivially copyable.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace vrsph {

// T: the element type, double for the state; float for the pair terms of the mixed precision's
// surface passes (core/precision.hpp).
template <int D, class T = double>
struct Vec {
  static_assert(D == 2 || D == 3, "vrsph supports 2D and 3D");
  std::array<T, D> c{};

  constexpr T& operator[](int k) { return c[static_cast<std::size_t>(k)]; }
  constexpr T operator[](int k) const { return c[static_cast<std::size_t>(k)]; }

  constexpr Vec& operator+=(const Vec& o) {
    for (int k = 0; k < D; ++k) (*this)[k] += o[k];
    return *this;
  }
  constexpr Vec& operator-=(const Vec& o) {
    for (int k = 0; k < D; ++k) (*this)[k] -= o[k];
    return *this;
  }
  constexpr Vec& operator*=(T s) {
    for (int k = 0; k < D; ++k) (*this)[k] *= s;
    return *this;
  }
  friend constexpr Vec operator+(Vec a, const Vec& b) { return a += b; }
  friend constexpr Vec operator-(Vec a, const Vec& b) { return a -= b; }
  friend constexpr Vec operator*(Vec a, T s) { return a *= s; }
  friend constexpr Vec operator*(T s, Vec a) { return a *= s; }
  friend constexpr Vec operator-(Vec a) { return a *= T(-1); }
  friend constexpr bool operator==(const Vec&, const Vec&) = default;
};

template <int D, class T>
constexpr T dot(const Vec<D, T>& a, const Vec<D, T>& b) {
  T s = 0;
  for (int k = 0; k < D; ++k) s += a[k] * b[k];
  return s;
}

template <int D, class T>
constexpr T norm2(const Vec<D, T>& a) {
  return dot(a, a);
}

template <int D, class T>
inline T norm(const Vec<D, T>& a) {
  return std::sqrt(norm2(a));
}

// The same vector in element type U.
template <class U, int D, class T>
constexpr Vec<D, U> vec_cast(const Vec<D, T>& a) {
  Vec<D, U> r;
  for (int k = 0; k < D; ++k) r[k] = static_cast<U>(a[k]);
  return r;
}

// Index of the vertical axis (the one gravity usually points along): y in 2D, z in 3D.
template <int D>
constexpr int vertical_axis() {
  return D - 1;
}

}  // namespace vrsph
