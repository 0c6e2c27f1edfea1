// Arithmetic precision of the neighbour passes (case key numerics.precision).
//  - double: every value and every pair term in double.
//  - mixed: positions, the integrated state (x, v, rho) and every per-particle sum stay double;
//    the candidate blocks of the force pass and of the three surface passes hold float copies
//    (positions relative to the block's origin as two floats hi + lo, so that r_ij keeps double
//    accuracy until its last rounding; density as rho - rho0; volume, lambda, normal) and their
//    pair terms are formed and summed per lane in float, which doubles the pairs per vector
//    instruction and halves the bytes a block copies. What a pass derives from its sums per
//    particle (lambda, M^-1, the normal, the curvature, the accelerations) is double.
//    DualSPHysics' CPU code runs its whole pair loop in float, with double positions as an option.
#pragma once

namespace vrsph {

enum class Precision { double_precision, mixed };

// Calls fn(T{}) with T the arithmetic of the pair terms: float in mixed precision, else double.
// The one place where a pass's runtime precision picks its template instance.
template <class Fn>
decltype(auto) with_pair_type(Precision precision, Fn&& fn) {
  if (precision == Precision::mixed) return fn(float{});
  return fn(double{});
}

}  // namespace vrsph
