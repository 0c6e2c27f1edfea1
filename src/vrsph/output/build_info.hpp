// What built this program: its version and the git commit of its source, for summary.json and
// run.log. The commit is read when CMake configures the build (`git rev-parse HEAD`, rerun when
// HEAD moves); "unknown" when the source is not a git checkout.
#pragma once

#include <string_view>

namespace vrsph {

std::string_view program_version();
std::string_view git_commit();

}  // namespace vrsph
