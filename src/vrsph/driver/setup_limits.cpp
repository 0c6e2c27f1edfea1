#include "vrsph/driver/setup_limits.hpp"

#include <fstream>
#include <string>

namespace vrsph {

std::optional<double> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string name, unit;
  double value = 0.0;
  while (in >> name >> value) {
    std::getline(in, unit);
    if (name == "MemAvailable:") return value * 1024.0;  // the file gives kB (KiB)
  }
  return std::nullopt;
}

PreflightLimits machine_limits(const SetupOrigin& origin) {
  return {origin.max_particles, available_memory_bytes()};
}

SetupEstimate preflight_case(const CaseSpec& spec, const SetupOrigin& origin) {
  return preflight(spec, origin.source, machine_limits(origin));
}

}  // namespace vrsph
