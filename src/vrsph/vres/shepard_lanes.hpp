// Shepard averages over a donor level in fixed lanes (variable resolution: the values of buffer
// particles and mass points, vres/interpolation.cpp; the surface fields that buffer particles take
// from the other level, vres/level_coupling.cpp):
//   f(x) = sum_j V_j f_j W(x - x_j) / sum_j V_j W(x - x_j)
// over the fluid donors within 2h of x (Shepard 1968; V_j = m_j / rho_j). The donors are read as
// columns (LaneColumns), and each row of x's stencil is summed in chunks of kShepardLanes
// candidates, candidate j0 + l of a chunk in lane l, every candidate weighed (W set to 0 beyond the
// support or past the row's end), the lanes added in order at the end. No list of the candidates
// within reach and no branch, so a chunk vectorises. Summed donor by donor instead (a branch-free
// list of the candidates within reach, then the sums one donor after the other), a buffer value of
// the shipped VR drop cost some 550 cycles, 40% of a fluid particle's whole force evaluation. The
// order of the sums depends on the grid alone, not on the threads.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "vrsph/core/kernel.hpp"
#include "vrsph/core/vec.hpp"

namespace vrsph {

inline constexpr int kShepardLanes = 8;

// A donor level as columns: positions, the volume of each fluid donor (0 for the others), that of
// each buffer donor (0 for the others; empty where no fill is summed) and up to D + 1 value
// columns (the averaged fields' components). Each column holds kPad entries past the last donor:
// far away, with zero volume and value, so that a chunk may read past the end.
template <int D>
struct LaneColumns {
  static constexpr std::size_t kPad = kShepardLanes;
  std::vector<double> x[D];
  std::vector<double> vol_fluid;
  std::vector<double> vol_buffer;
  std::vector<double> value[D + 1];

  // Sizes x, vol_fluid, the first `values` value columns and (with `buffer`) vol_buffer to
  // n + kPad entries and writes the padding; entries below n are the caller's to fill.
  void size_for(std::size_t n, int values, bool buffer) {
    auto pad = [n](std::vector<double>& col, double v) {
      col.resize(n + kPad);
      std::fill(col.begin() + static_cast<std::ptrdiff_t>(n), col.end(), v);
    };
    for (int k = 0; k < D; ++k) pad(x[k], 1e10);  // far from every point: weighed 0
    pad(vol_fluid, 0.0);
    if (buffer) pad(vol_buffer, 0.0);
    for (int q = 0; q < values; ++q) pad(value[q], 0.0);
  }
};

// The lane sums of the first NV value columns: w = sum V_j W over fluid donors, fw[q] = sum V_j
// f_j^q W over them, and with kBuffer w_buffer = sum V_j W over buffer donors.
template <int D, int NV, bool kBuffer>
struct LaneSums {
  double w[kShepardLanes] = {};
  double w_buffer[kShepardLanes] = {};
  double fw[NV][kShepardLanes] = {};

  // The candidates [begin, end) of one row of the stencil.
  void add_row(const Vec<D>& x, const LaneColumns<D>& col, const WendlandC2<D>& kernel,
               std::size_t begin, std::size_t end) {
    const double support2 = kernel.support2;
    for (std::size_t j0 = begin; j0 < end; j0 += kShepardLanes) {
      const int valid = static_cast<int>(end - j0);
      // The chunk's columns from j0, so that each lane's load is the next element of one vector.
      const double* px[D];
      const double* pv[NV];
      for (int k = 0; k < D; ++k) px[k] = col.x[k].data() + j0;
      for (int q = 0; q < NV; ++q) pv[q] = col.value[q].data() + j0;
      const double* pf = col.vol_fluid.data() + j0;
      const double* pb = kBuffer ? col.vol_buffer.data() + j0 : nullptr;
      for (int l = 0; l < kShepardLanes; ++l) {
        double r2 = 0.0;
        for (int k = 0; k < D; ++k) {
          const double d = x[k] - px[k][l];
          r2 += d * d;
        }
        const bool in = (r2 < support2) & (l < valid);
        const double wr = kernel.w(std::sqrt(r2));  // finite for every candidate, then selected
        const double wj = in ? wr : 0.0;
        const double vw = pf[l] * wj;
        w[l] += vw;
        if constexpr (kBuffer) w_buffer[l] += pb[l] * wj;
        for (int q = 0; q < NV; ++q) fw[q][l] += vw * pv[q][l];
      }
    }
  }

  // The lanes added in order.
  struct Totals {
    double w = 0.0, w_buffer = 0.0, fw[NV] = {};
  };
  Totals totals() const {
    Totals t;
    for (int l = 0; l < kShepardLanes; ++l) {
      t.w += w[l];
      if constexpr (kBuffer) t.w_buffer += w_buffer[l];
      for (int q = 0; q < NV; ++q) t.fw[q] += fw[q][l];
    }
    return t;
  }
};

}  // namespace vrsph
