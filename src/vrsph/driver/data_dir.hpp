// Where the shipped data (cases/, reference/, scripts/) is found at run time, so that an
// installed `vrsph` needs no source tree. In order:
//   1. the environment variable VRSPH_DATA_DIR, when set and not empty;
//   2. next to the executable: <folder of the executable>/VRSPH_DATA_RELATIVE (../share/vrsph for
//      an installed bin/vrsph), when that folder holds cases/;
//   3. the source tree the program was built from (a binary run from its build folder).
#pragma once

#include <filesystem>

namespace vrsph {

// The rule above for given inputs: `env` is the value of VRSPH_DATA_DIR (nullptr when unset),
// `exe` the executable's path (empty when unknown).
std::filesystem::path data_dir_for(const char* env, const std::filesystem::path& exe);

// The rule above for this process (the executable read from /proc/self/exe).
std::filesystem::path data_dir();

// The case file to read for a path given on the command line: the path itself when it exists,
// is absolute or is found nowhere else (its error then names it); otherwise, for a relative path,
// the same path under data_dir() when that file exists there, so that
// `vrsph check cases/droplet_2d.toml` finds the shipped case from any folder.
std::filesystem::path find_case_file(const std::filesystem::path& given);

}  // namespace vrsph
