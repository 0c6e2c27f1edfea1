#include "vrsph/output/csv_rows.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <stdexcept>

namespace vrsph {

std::vector<std::string> split_fields(std::string_view line, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t k = 0; k <= line.size(); ++k) {
    if (k == line.size() || line[k] == sep) {
      parts.emplace_back(line.substr(start, k - start));
      start = k + 1;
    }
  }
  return parts;
}

void append_durably(const std::filesystem::path& path, std::string_view text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  int err = fd < 0 ? errno : 0;
  if (err == 0) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0)
      err = errno;
    else if (static_cast<std::size_t>(n) != text.size())
      err = EIO;
    if (err == 0 && ::fsync(fd) != 0) err = errno;
    ::close(fd);
  }
  if (err != 0)
    throw std::runtime_error(
        fmt::format("cannot append to '{}': {}", path.string(), std::strerror(err)));
}

std::vector<std::string> complete_lines(const std::string& text) {
  const std::size_t end = text.rfind('\n');
  if (end == std::string::npos) return {};
  std::vector<std::string> lines = split_fields(std::string_view(text).substr(0, end + 1), '\n');
  lines.pop_back();  // the empty piece after the last '\n'
  return lines;
}

bool row_up_to(const std::string& line, std::size_t n_columns, std::size_t t_column, double t_max) {
  const std::vector<std::string> fields = split_fields(line);
  if (fields.size() != n_columns || t_column >= n_columns) return false;
  const std::string& f = fields[t_column];
  double t = 0.0;
  const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), t);
  return ec == std::errc() && ptr == f.data() + f.size() && t <= t_max;
}

}  // namespace vrsph
