// Wendland C2 kernel (Wendland 1995), support radius 2h, as used by DualSPHysics.
//   W(q) = a_D (1 - q/2)^4 (2q + 1),  q = r/h in [0, 2]
//   a_2 = 7 / (4 pi h^2),  a_3 = 21 / (16 pi h^3)   (exact constants, not DualSPHysics' rounded
//   ones) grad_i W_ij = F(r) r_ij,  F(r) = W'(r)/r = -5 a_D / h^2 (1 - q/2)^3
// Callers test r^2 < 4h^2 before calling; the functions do not check the support.
#pragma once

#include <numbers>

namespace vrsph {

template <int D>
struct WendlandC2 {
  double h = 0.0;
  double inv_h = 0.0;
  double a_d = 0.0;       // normalisation a_D
  double f_coef = 0.0;    // -5 a_D / h^2
  double support2 = 0.0;  // (2h)^2

  WendlandC2() = default;
  explicit WendlandC2(double h_) : h(h_), inv_h(1.0 / h_) {
    constexpr double pi = std::numbers::pi;
    if constexpr (D == 2) {
      a_d = 7.0 / (4.0 * pi * h * h);
    } else {
      a_d = 21.0 / (16.0 * pi * h * h * h);
    }
    f_coef = -5.0 * a_d / (h * h);
    support2 = 4.0 * h * h;
  }

  double support() const { return 2.0 * h; }

  // W(r) for 0 <= r <= 2h.
  // T: the pass's arithmetic type (double, or float in mixed precision).
  template <class T>
  T w(T r) const {
    const T q = r * T(inv_h);
    const T t = T(1) - T(0.5) * q;
    const T t2 = t * t;
    return T(a_d) * t2 * t2 * (T(2) * q + T(1));
  }

  // F(r) = W'(r) / r for 0 <= r <= 2h (finite at r = 0).
  template <class T>
  T f(T r) const {
    const T t = T(1) - T(0.5) * r * T(inv_h);
    return T(f_coef) * t * t * t;
  }
};

}  // namespace vrsph
