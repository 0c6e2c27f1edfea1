// The shipped data folder (see data_dir.hpp).
#include "vrsph/driver/data_dir.hpp"

#include <cstdlib>
#include <system_error>

#ifndef VRSPH_DATA_RELATIVE
#define VRSPH_DATA_RELATIVE "../share/vrsph"
#endif

namespace vrsph {

namespace fs = std::filesystem;

fs::path data_dir_for(const char* env, const fs::path& exe) {
  if (env != nullptr && *env != '\0') return fs::path(env);
  if (!exe.empty()) {
    const fs::path beside = (exe.parent_path() / VRSPH_DATA_RELATIVE).lexically_normal();
    std::error_code ec;
    if (fs::is_directory(beside / "cases", ec)) return beside;
  }
  return fs::path(VRSPH_SOURCE_DIR);
}

fs::path data_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return data_dir_for(std::getenv("VRSPH_DATA_DIR"), ec ? fs::path() : exe);
}

fs::path find_case_file(const fs::path& given) {
  std::error_code ec;
  if (given.empty() || given.is_absolute() || fs::exists(given, ec)) return given;
  const fs::path shipped = data_dir() / given;
  return fs::is_regular_file(shipped, ec) ? shipped : given;
}

}  // namespace vrsph
