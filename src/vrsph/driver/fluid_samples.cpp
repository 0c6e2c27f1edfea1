#include "vrsph/driver/fluid_samples.hpp"

#include <algorithm>
#include <numeric>

#include "vrsph/analysis/shepard.hpp"
#include "vrsph/core/to_vec.hpp"

namespace vrsph {
namespace {

// Level indices from the finest (smallest dp) to the coarsest.
template <int D>
std::vector<std::size_t> finest_first(const Simulation<D>& sim) {
  std::vector<std::size_t> order(sim.level_count());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return sim.level(a).prm.dp < sim.level(b).prm.dp;
  });
  return order;
}

double finest_dp(const auto& sim) {
  double dp = sim.level(0).prm.dp;
  for (std::size_t l = 1; l < sim.level_count(); ++l) dp = std::min(dp, sim.level(l).prm.dp);
  return dp;
}

}  // namespace

template <int D>
FluidPoint<D> sample_fluid(const Simulation<D>& sim, const Vec<D>& x) {
  ShepardSums<D> total;
  int best = -1;
  double best_s = 0.0;
  for (std::size_t l : finest_first(sim)) {
    const auto& L = sim.level(l);
    const ShepardSums<D> s = shepard_sums<D>(x, L.ps, L.grid, L.prm.kernel, L.prm.eos);
    if (s.s >= kShepardInside) return shepard_point<D>(s, static_cast<int>(l));
    total.add(s);
    if (s.s > best_s) {
      best_s = s.s;
      best = static_cast<int>(l);
    }
  }
  return shepard_point<D>(total, best);
}

template <int D>
std::vector<LineInterpSample<D>> interpolate_line(const Simulation<D>& sim,
                                                  const OutputLine& line) {
  auto points = line_points<D>(to_vec<D>(line.from), to_vec<D>(line.to), 0.5 * finest_dp(sim));
  for (LineInterpSample<D>& q : points) q.f = sample_fluid(sim, q.x);
  return points;
}

template <int D>
LaplaceError interp_laplace_error(const Simulation<D>& sim,
                                  std::span<const LineInterpSample<D>> samples, double expected) {
  auto first =
      std::find_if(samples.begin(), samples.end(), [](const auto& q) { return q.f.inside(); });
  auto last =
      std::find_if(samples.rbegin(), samples.rend(), [](const auto& q) { return q.f.inside(); });
  const double h_first = first == samples.end() ? 0.0 : sim.level(first->f.level).prm.h;
  const double h_last = last == samples.rend() ? 0.0 : sim.level(last->f.level).prm.h;
  return laplace_error<D>(samples, expected, h_first, h_last);
}

template FluidPoint<2> sample_fluid<2>(const Simulation<2>&, const Vec<2>&);
template FluidPoint<3> sample_fluid<3>(const Simulation<3>&, const Vec<3>&);
template std::vector<LineInterpSample<2>> interpolate_line<2>(const Simulation<2>&,
                                                              const OutputLine&);
template std::vector<LineInterpSample<3>> interpolate_line<3>(const Simulation<3>&,
                                                              const OutputLine&);
template LaplaceError interp_laplace_error<2>(const Simulation<2>&,
                                              std::span<const LineInterpSample<2>>, double);
template LaplaceError interp_laplace_error<3>(const Simulation<3>&,
                                              std::span<const LineInterpSample<3>>, double);

}  // namespace vrsph
