// Line profiles: particle selection near a segment and the line_<name>_NNNN.csv writer.
#include "vrsph/output/line_profile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vrsph/output/atomic_file.hpp"

namespace vrsph {

template <int D>
std::vector<LineSample<D>> sample_line(const ParticleSet<D>& ps, const TaitEos& eos,
                                       std::span<const std::uint8_t> level, const Vec<D>& from,
                                       const Vec<D>& to, double half_width) {
  if (!level.empty() && level.size() != ps.size())
    throw std::invalid_argument("sample_line: level has the wrong size");
  const Vec<D> d = to - from;
  const double length = norm(d);
  if (!(length > 0.0)) throw std::invalid_argument("sample_line: from and to coincide");
  const Vec<D> e = d * (1.0 / length);  // unit direction
  std::vector<LineSample<D>> out;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] != Kind::fluid) continue;  // walls, and buffers (they mirror another level)
    const Vec<D> r = ps.pos[i] - from;
    const double s = dot(r, e);
    if (s < 0.0 || s > length) continue;
    if (norm2(r - s * e) > half_width * half_width) continue;
    out.push_back({s, ps.pos[i], eos.pressure(ps.rho[i]), level.empty() ? 0 : level[i], ps.id[i]});
  }
  std::sort(out.begin(), out.end(), [](const LineSample<D>& a, const LineSample<D>& b) {
    return a.s < b.s || (a.s == b.s && a.id < b.id);
  });
  return out;
}

template <int D>
void write_line_samples(const std::filesystem::path& path, std::span<const LineSample<D>> samples) {
  fmt::memory_buffer buf;
  auto out = fmt::appender(buf);
  fmt::format_to(out, "{}", D == 2 ? "s,x,y,p,level\n" : "s,x,y,z,p,level\n");
  for (const LineSample<D>& q : samples) {
    fmt::format_to(out, "{}", q.s);
    for (int k = 0; k < D; ++k) fmt::format_to(out, ",{}", q.x[k]);
    fmt::format_to(out, ",{},{}\n", q.p, q.level);
  }
  write_file_atomic(path, std::string_view(buf.data(), buf.size()));
}

template <int D>
void write_line_profile(const std::filesystem::path& path, const ParticleSet<D>& ps,
                        const TaitEos& eos, std::span<const std::uint8_t> level, const Vec<D>& from,
                        const Vec<D>& to, double half_width) {
  const std::vector<LineSample<D>> samples = sample_line(ps, eos, level, from, to, half_width);
  write_line_samples<D>(path, samples);
}

std::string line_file_name(std::string_view name, int index) {
  return fmt::format("line_{}_{:04d}.csv", name, index);
}

template <int D>
std::vector<LineInterpSample<D>> line_points(const Vec<D>& from, const Vec<D>& to, double ds) {
  const double length = norm(to - from);
  if (!(length > 0.0)) throw std::invalid_argument("line_points: from and to coincide");
  if (!(ds > 0.0)) throw std::invalid_argument("line_points: spacing must be positive");
  const Vec<D> e = (to - from) * (1.0 / length);
  const auto n = static_cast<long>(std::floor(length / ds * (1.0 + 1e-12)));
  std::vector<LineInterpSample<D>> out(static_cast<std::size_t>(n + 1));
  for (long k = 0; k <= n; ++k) {
    LineInterpSample<D>& q = out[static_cast<std::size_t>(k)];
    q.s = static_cast<double>(k) * ds;
    q.x = from + q.s * e;
  }
  return out;
}

template <int D>
void write_line_interp(const std::filesystem::path& path,
                       std::span<const LineInterpSample<D>> samples) {
  fmt::memory_buffer buf;
  auto out = fmt::appender(buf);
  fmt::format_to(
      out, "{}",
      D == 2 ? "s,x,y,p,rho,vx,vy,level,shepard\n" : "s,x,y,z,p,rho,vx,vy,vz,level,shepard\n");
  for (const LineInterpSample<D>& q : samples) {
    fmt::format_to(out, "{}", q.s);
    for (int k = 0; k < D; ++k) fmt::format_to(out, ",{}", q.x[k]);
    append_fluid_values<D>(buf, q.f);
    if (q.f.inside())
      fmt::format_to(out, ",{},{}\n", q.f.level, q.f.shepard);
    else
      fmt::format_to(out, ",,{}\n", q.f.shepard);
  }
  write_file_atomic(path, std::string_view(buf.data(), buf.size()));
}

std::string line_interp_file_name(std::string_view name, int index) {
  return fmt::format("line_{}_interp_{:04d}.csv", name, index);
}

template std::vector<LineSample<2>> sample_line<2>(const ParticleSet<2>&, const TaitEos&,
                                                   std::span<const std::uint8_t>, const Vec<2>&,
                                                   const Vec<2>&, double);
template void write_line_samples<2>(const std::filesystem::path&, std::span<const LineSample<2>>);
template void write_line_profile<2>(const std::filesystem::path&, const ParticleSet<2>&,
                                    const TaitEos&, std::span<const std::uint8_t>, const Vec<2>&,
                                    const Vec<2>&, double);
template std::vector<LineInterpSample<2>> line_points<2>(const Vec<2>&, const Vec<2>&, double);
template std::vector<LineInterpSample<3>> line_points<3>(const Vec<3>&, const Vec<3>&, double);
template void write_line_interp<2>(const std::filesystem::path&,
                                   std::span<const LineInterpSample<2>>);
template void write_line_interp<3>(const std::filesystem::path&,
                                   std::span<const LineInterpSample<3>>);
template std::vector<LineSample<3>> sample_line<3>(const ParticleSet<3>&, const TaitEos&,
                                                   std::span<const std::uint8_t>, const Vec<3>&,
                                                   const Vec<3>&, double);
template void write_line_samples<3>(const std::filesystem::path&, std::span<const LineSample<3>>);
template void write_line_profile<3>(const std::filesystem::path&, const ParticleSet<3>&,
                                    const TaitEos&, std::span<const std::uint8_t>, const Vec<3>&,
                                    const Vec<3>&, double);

}  // namespace vrsph
