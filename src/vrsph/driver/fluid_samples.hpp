// The fluid's values at points of a run, over all its levels: the probes ([[output.probe]]) and
// the interpolated lines of [[output.line]] (docs/outputs.md). At each point the Shepard
// interpolation of analysis/shepard.hpp runs on the finest level whose fluid covers the point
// (Shepard sum >= kShepardInside); where no level covers it alone but their sums together do (at
// a resolution interface, where each level's fluid ends about half-way through the support) the
// levels' sums are added, and the point is attributed to the level with the largest sum. A point
// that no fluid covers is outside (FluidPoint::level = -1). The grids must be sorted.
#pragma once

#include <span>
#include <vector>

#include "vrsph/analysis/laplace.hpp"
#include "vrsph/output/fluid_point.hpp"
#include "vrsph/output/line_profile.hpp"
#include "vrsph/setup/case_spec.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {

template <int D>
FluidPoint<D> sample_fluid(const Simulation<D>& sim, const Vec<D>& x);

// The points every dp/2 (dp of the finest level) along the line, with their values.
template <int D>
std::vector<LineInterpSample<D>> interpolate_line(const Simulation<D>& sim, const OutputLine& line);

// The Laplace error on an interpolated line, the 2h margins with h of the level of the first and
// last point inside the fluid.
template <int D>
LaplaceError interp_laplace_error(const Simulation<D>& sim,
                                  std::span<const LineInterpSample<D>> samples, double expected);

}  // namespace vrsph
