// SurfaceFields' own bookkeeping: sizing, and the held fields that follow their particles through
// sorts, compactions and appends (solver/surface_pass.hpp).
#include "vrsph/exec/parallel.hpp"
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
  if (held_geometry) {
    keep_entries(lambda, keep);
    keep_entries(normal, keep);
    keep_entries(curvature, keep);
  }
  keep_entries(acc_st, keep);
  keep_entries(acc_ref, keep);
  keep_entries(acc_rate, keep);
}

template <int D>
void SurfaceFields<D>::fit_held(std::size_t n) {
  if (!held) return;
  lambda.resize(n, 0.0);
  normal.resize(n, Vec<D>{});
  curvature.resize(n, 0.0);
  acc_st.resize(n, Vec<D>{});
  if (!acc_ref.empty()) {  // a created particle: nothing held, no rate
    acc_ref.resize(n, Vec<D>{});
    acc_rate.resize(n, Vec<D>{});
  }
}

template <int D>
void SurfaceFields<D>::take_refresh(double since_last) {
  const std::size_t n = acc_st.size();
  const bool rate = since_last > 0.0 && acc_ref.size() == n;
  acc_rate.resize(n);
  acc_ref.resize(n);
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(n), [&](std::int64_t i) {
    const bool both = norm2(acc_st[i]) > 0.0 && norm2(acc_ref[i]) > 0.0;
    acc_rate[i] = rate && both ? (acc_st[i] - acc_ref[i]) * (1.0 / since_last) : Vec<D>{};
    acc_ref[i] = acc_st[i];
  });
}

template <int D>
void SurfaceFields<D>::extrapolate(double tau) {
  if (acc_ref.empty()) return;  // nothing refreshed yet: acc_st as held
  acc_st.resize(acc_ref.size());
  exec::for_each(exec::in_shares, static_cast<std::int64_t>(acc_st.size()),
                 [&](std::int64_t i) { acc_st[i] = acc_ref[i] + acc_rate[i] * tau; });
}

template struct SurfaceFields<2>;
template struct SurfaceFields<3>;

}  // namespace vrsph
