// SurfaceFields' own bookkeeping: sizing, and the held fields that follow their particles through
// sorts, compactions and appends (solver/surface_pass.hpp).
#include "vrsph/solver/surface_pass.hpp"

namespace vrsph {

template <int D>
void SurfaceFields<D>::resize(std::size_t n) {
  // sized only: pass 1 writes every entry, in parallel (walls their neutral values)
  lambda.resize(n);
  l_corr.resize(n);
  grad_c.resize(n);
  div_r.resize(n);
  shepard.resize(n);
  normal.resize(n);  // sized only: held values stay, and passes 2 and 3 write every entry
  curvature.resize(n);
  acc_st.resize(n);
}

namespace {
template <class T>
void keep_entries(std::vector<T>& a, const std::vector<std::uint8_t>& keep) {
  if (a.size() != keep.size()) return;  // not sized to this level's particles: nothing held
  std::size_t w = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (keep[i]) a[w++] = a[i];
  a.resize(w);
}
}  // namespace

template <int D>
void SurfaceFields<D>::compact_held(const std::vector<std::uint8_t>& keep) {
  if (!held) return;
  keep_entries(lambda, keep);
  keep_entries(normal, keep);
  keep_entries(curvature, keep);
  keep_entries(acc_st, keep);
}

template <int D>
void SurfaceFields<D>::fit_held(std::size_t n) {
  if (!held) return;
  lambda.resize(n, 0.0);
  normal.resize(n, Vec<D>{});
  curvature.resize(n, 0.0);
  acc_st.resize(n, Vec<D>{});
}

template struct SurfaceFields<2>;
template struct SurfaceFields<3>;

}  // namespace vrsph
