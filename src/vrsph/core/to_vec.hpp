// Case-file vectors to the solver's Vec<D>. The case stores every vector with 3 components
// (setup/case_spec.hpp, Vec3d); only the first D are meaningful.
#pragma once

#include <array>
#include <cstddef>

#include "vrsph/core/vec.hpp"

namespace vrsph {

template <int D>
Vec<D> to_vec(const std::array<double, 3>& a) {
  Vec<D> v;
  for (int k = 0; k < D; ++k) v[k] = a[static_cast<std::size_t>(k)];
  return v;
}

}  // namespace vrsph
