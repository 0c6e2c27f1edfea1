// Pressure-profile error against the Laplace pressure (docs/physics.md section 11, the poster's
// table): RMSE of the pressures along a line (the droplet diameter) against p = sigma / R,
// NRMSE = RMSE / p_expected, on the line's particle strip or on its interpolated points.
// `rmse_all` uses every sample of the line; `rmse` and `mean_interior` only those at least 2h
// from both ends of the line's sample set, away from the free-surface rows where the pressure
// falls to zero.
#pragma once

#include <cstddef>
#include <span>

#include "vrsph/output/line_profile.hpp"
#include "vrsph/particles/particles.hpp"

namespace vrsph {

struct LaplaceError {
  double expected = 0.0;
  double mean_interior = 0.0;
  double rmse = 0.0;
  double nrmse = 0.0;
  double rmse_all = 0.0;
  std::size_t n_points = 0;  // interior points used for rmse
};

// s: distance along the line of each sample, p: its pressure (same length).
LaplaceError laplace_error(std::span<const double> s, std::span<const double> p, double expected,
                           double h);
// The same with the 2h margin taken with a different h at each end (variable resolution: the
// line's ends may lie in different levels).
LaplaceError laplace_error(std::span<const double> s, std::span<const double> p, double expected,
                           double h_first, double h_last);

// The same for line samples (sorted by s, as sample_line gives them), with the 2h margin taken
// with h_first at the start and h_last at the end.
template <int D>
LaplaceError laplace_error(std::span<const LineSample<D>> samples, double expected, double h_first,
                           double h_last);

// The same for the points of an interpolated line that lie inside the fluid (those outside are
// left out, and the 2h margins are taken from the first and last point inside).
template <int D>
LaplaceError laplace_error(std::span<const LineInterpSample<D>> samples, double expected,
                           double h_first, double h_last);

}  // namespace vrsph
