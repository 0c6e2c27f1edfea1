// Line samples over all levels of a run (the Laplace metric and the line files of a VR run).
#pragma once

#include <algorithm>
#include <vector>

#include "vrsph/analysis/laplace.hpp"
#include "vrsph/core/to_vec.hpp"
#include "vrsph/output/line_profile.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {

// The particles (fluid only) within dp/2 of a line, dp of each level, all levels, sorted by s.
template <int D>
std::vector<LineSample<D>> sample_levels(const Simulation<D>& sim, const OutputLine& line) {
  std::vector<LineSample<D>> all;
  for (std::size_t l = 0; l < sim.level_count(); ++l) {
    const auto& L = sim.level(l);
    auto s = sample_line<D>(L.ps, L.prm.eos, {}, to_vec<D>(line.from), to_vec<D>(line.to),
                            0.5 * L.prm.dp);
    for (auto& q : s) q.level = static_cast<int>(l);
    all.insert(all.end(), s.begin(), s.end());
  }
  std::sort(all.begin(), all.end(), [](const LineSample<D>& a, const LineSample<D>& b) {
    return a.s < b.s || (a.s == b.s && a.id < b.id);
  });
  return all;
}

// The Laplace error (analysis/laplace.hpp) on a line over all levels, leaving out 2h of the level
// found at each end of the line (summary.json's `laplace`; series.csv's laplace columns).
template <int D>
LaplaceError levels_laplace_error(const Simulation<D>& sim, const OutputLine& line,
                                  double expected) {
  const auto samples = sample_levels(sim, line);
  const double h_first = samples.empty() ? 0.0 : sim.level(samples.front().level).prm.h;
  const double h_last = samples.empty() ? 0.0 : sim.level(samples.back().level).prm.h;
  return laplace_error<D>(samples, expected, h_first, h_last);
}

}  // namespace vrsph
