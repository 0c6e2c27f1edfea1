#include "vrsph/analysis/front.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vrsph {

template <int D>
double surge_front(const ParticleSet<D>& ps, int axis) {
  double x = -1e300;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] == Kind::fluid) x = std::max(x, ps.pos[i][axis]);
  }
  return x;
}

std::vector<FrontPoint> load_front_reference(const std::string& csv_path,
                                             const std::string& source) {
  std::ifstream in(csv_path);
  if (!in) throw std::runtime_error(csv_path + ": cannot open the dam-break reference");
  std::vector<FrontPoint> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("source,", 0) == 0) continue;
    std::stringstream ss(line);
    std::string src, t, z;
    if (!std::getline(ss, src, ',') || !std::getline(ss, t, ',') || !std::getline(ss, z)) continue;
    if (src == source) out.push_back({std::stod(t), std::stod(z)});
  }
  if (out.empty()) throw std::runtime_error(csv_path + ": no rows for source " + source);
  return out;
}

FrontError compare_front(const std::vector<FrontPoint>& sim, const std::vector<FrontPoint>& ref,
                         double time_shift, double t_min) {
  FrontError e;
  double sum2 = 0.0;
  for (const FrontPoint& r : ref) {
    const double T = r.T - time_shift;
    if (r.T < t_min || sim.empty() || T < sim.front().T || T > sim.back().T) continue;
    auto hi = std::lower_bound(sim.begin(), sim.end(), T,
                               [](const FrontPoint& p, double v) { return p.T < v; });
    double z = hi->Z;
    if (hi != sim.begin() && hi->T > T) {
      const auto lo = hi - 1;
      z = lo->Z + (hi->Z - lo->Z) * (T - lo->T) / (hi->T - lo->T);
    }
    const double d = z - r.Z;
    sum2 += d * d;
    e.max_abs = std::max(e.max_abs, std::fabs(d));
    ++e.n;
  }
  if (e.n > 0) e.rms = std::sqrt(sum2 / e.n);
  return e;
}

template double surge_front<2>(const ParticleSet<2>&, int);
template double surge_front<3>(const ParticleSet<3>&, int);

}  // namespace vrsph
