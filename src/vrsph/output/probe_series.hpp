// probe_<name>.csv: the fluid's values at one fixed point ([[output.probe]]) at every output time,
//   t,p,rho,vx,vy[,vz]
// interpolated as analysis/shepard.hpp describes; while the point lies outside the fluid the
// values are empty ("0.01,,,,"). Rows are appended as series.csv's are (one write and an fsync
// each), and a resumed run cuts the file back to the checkpoint's time first.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "vrsph/output/fluid_point.hpp"

namespace vrsph {

template <int D>
class ProbeWriter {
 public:
  // Starts a new file at `path` (replacing any existing one) with the header.
  explicit ProbeWriter(std::filesystem::path path);

  // Continues the file of a run resumed at `up_to_time`: keeps the header and the complete rows
  // with t <= up_to_time. A missing or empty file starts anew; a file with another header throws
  // std::runtime_error.
  static ProbeWriter resume(const std::filesystem::path& path, double up_to_time);

  void append(double t, const FluidPoint<D>& f);

  static std::string header();
  const std::filesystem::path& path() const { return path_; }

 private:
  struct NoInit {};
  ProbeWriter(NoInit, std::filesystem::path path) : path_(std::move(path)) {}
  std::filesystem::path path_;
};

// "probe_gauge.csv" for "gauge".
std::string probe_file_name(std::string_view name);

}  // namespace vrsph
