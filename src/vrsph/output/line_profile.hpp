// Pressure profile along a segment (the poster's diameter plot), two ways:
//  - the particle strip: the fluid particles (walls and buffer particles excluded) within
//    half_width of the segment from -> to, i.e. with perpendicular distance <= half_width and
//    projection s in [0, |to - from|], sorted by s (ties by particle id); file columns
//    s,x,y[,z],p,level (line_<name>_NNNN.csv);
//  - the interpolated line: points every dp/2 along the segment with the kernel-interpolated
//    fluid values there (analysis/shepard.hpp); file columns s,x,y[,z],p,rho,vx,vy[,vz],level,
//    shepard, the values and level empty at points outside the fluid
//    (line_<name>_interp_NNNN.csv).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vrsph/output/fluid_point.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/eos.hpp"

namespace vrsph {

template <int D>
struct LineSample {
  double s = 0.0;  // m, distance along the segment from `from`
  Vec<D> x{};      // m
  double p = 0.0;  // Pa
  int level = 0;
  std::uint64_t id = 0;
};

// The selected particles, sorted by s, each with its pressure from the EOS. `level` empty means
// all level 0. Throws
// std::invalid_argument if from == to or `level` has the wrong size.
template <int D>
std::vector<LineSample<D>> sample_line(const ParticleSet<D>& ps, const TaitEos& eos,
                                       std::span<const std::uint8_t> level, const Vec<D>& from,
                                       const Vec<D>& to, double half_width);

// Writes sample_line(...) as CSV, atomically. Callers pass half_width = dp / 2.
template <int D>
void write_line_profile(const std::filesystem::path& path, const ParticleSet<D>& ps,
                        const TaitEos& eos, std::span<const std::uint8_t> level, const Vec<D>& from,
                        const Vec<D>& to, double half_width);

// Writes already selected samples (e.g. merged from several levels) as CSV, atomically.
template <int D>
void write_line_samples(const std::filesystem::path& path, std::span<const LineSample<D>> samples);

// "line_diameter_0003.csv" for ("diameter", 3).
std::string line_file_name(std::string_view name, int index);

// A point of an interpolated line.
template <int D>
struct LineInterpSample {
  double s = 0.0;  // m, distance along the segment from `from`
  Vec<D> x{};      // m
  FluidPoint<D> f;
};

// The points from + k ds e, k = 0, 1, ... while k ds <= |to - from| (e the unit direction);
// values are left for the caller. Throws std::invalid_argument if from == to or ds <= 0.
template <int D>
std::vector<LineInterpSample<D>> line_points(const Vec<D>& from, const Vec<D>& to, double ds);

// Writes an interpolated line as CSV, atomically.
template <int D>
void write_line_interp(const std::filesystem::path& path,
                       std::span<const LineInterpSample<D>> samples);

// "line_diameter_interp_0003.csv" for ("diameter", 3).
std::string line_interp_file_name(std::string_view name, int index);

}  // namespace vrsph
