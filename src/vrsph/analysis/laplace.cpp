#include "vrsph/analysis/laplace.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "vrsph/output/line_profile.hpp"

namespace vrsph {

LaplaceError laplace_error(std::span<const double> s, std::span<const double> p, double expected,
                           double h) {
  return laplace_error(s, p, expected, h, h);
}

LaplaceError laplace_error(std::span<const double> s, std::span<const double> p, double expected,
                           double h_first, double h_last) {
  if (s.size() != p.size()) throw std::invalid_argument("laplace_error: size mismatch");
  LaplaceError e;
  e.expected = expected;
  if (s.empty()) return e;
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  const double s_min = *lo + 2.0 * h_first, s_max = *hi - 2.0 * h_last;
  double sum_all = 0.0, sum_in = 0.0, sum_p = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double d2 = (p[k] - expected) * (p[k] - expected);
    sum_all += d2;
    if (s[k] >= s_min && s[k] <= s_max) {
      sum_in += d2;
      sum_p += p[k];
      ++e.n_points;
    }
  }
  e.rmse_all = std::sqrt(sum_all / static_cast<double>(s.size()));
  if (e.n_points > 0) {
    e.rmse = std::sqrt(sum_in / static_cast<double>(e.n_points));
    e.mean_interior = sum_p / static_cast<double>(e.n_points);
  }
  e.nrmse = e.rmse / expected;
  return e;
}

template <int D>
LaplaceError laplace_error(std::span<const LineSample<D>> samples, double expected, double h_first,
                           double h_last) {
  std::vector<double> s, p;
  for (const auto& q : samples) {
    s.push_back(q.s);
    p.push_back(q.p);
  }
  return laplace_error(s, p, expected, h_first, h_last);
}

template <int D>
LaplaceError laplace_error(std::span<const LineInterpSample<D>> samples, double expected,
                           double h_first, double h_last) {
  std::vector<double> s, p;
  for (const auto& q : samples) {
    if (!q.f.inside()) continue;
    s.push_back(q.s);
    p.push_back(q.f.p);
  }
  return laplace_error(s, p, expected, h_first, h_last);
}

template LaplaceError laplace_error<2>(std::span<const LineSample<2>>, double, double, double);
template LaplaceError laplace_error<3>(std::span<const LineSample<3>>, double, double, double);
template LaplaceError laplace_error<2>(std::span<const LineInterpSample<2>>, double, double,
                                       double);
template LaplaceError laplace_error<3>(std::span<const LineInterpSample<3>>, double, double,
                                       double);

}  // namespace vrsph
