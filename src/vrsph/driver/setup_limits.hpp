// The machine's side of the set-up checks (sim/preflight.hpp): the memory it has available.
#pragma once

#include <optional>

#include "vrsph/driver/run.hpp"
#include "vrsph/sim/preflight.hpp"

namespace vrsph {

// MemAvailable of /proc/meminfo in bytes (the kernel's estimate of what a new process can use
// without swapping); nullopt where it cannot be read.
std::optional<double> available_memory_bytes();

// The limits for a command: the user's --max-particles and the memory available.
PreflightLimits machine_limits(const SetupOrigin& origin);

// preflight() with machine_limits(origin).
SetupEstimate preflight_case(const CaseSpec& spec, const SetupOrigin& origin);

}  // namespace vrsph
