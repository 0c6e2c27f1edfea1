// Atomic file writes: temp file in the same directory, fsync, rename (see atomic_file.hpp).
#include "vrsph/output/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace vrsph {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void throw_errno(std::string_view what, const fs::path& path, int err) {
  throw std::runtime_error(fmt::format("{} '{}': {}", what, path.string(), std::strerror(err)));
}

// Directory of `path`, "." when it has none.
fs::path parent_or_cwd(const fs::path& path) {
  fs::path dir = path.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

// Creates ".<name>.tmpXXXXXX" next to `target` (mkstemp) and returns its descriptor and path.
int make_temp(const fs::path& target, fs::path& temp) {
  if (target.filename().empty())
    throw std::runtime_error("cannot write to a directory path '" + target.string() + "'");
  std::string leaf = ".";
  leaf.append(target.filename().string()).append(".tmpXXXXXX");
  const std::string pattern = (parent_or_cwd(target) / leaf).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw_errno("cannot create a temporary file for", target, errno);
  ::fchmod(fd, 0644);  // mkstemp gives 0600; outputs are ordinary readable files
  temp = fs::path(name.data());
  return fd;
}

// Writes all of `content` to `fd`, retrying short writes and EINTR. Returns 0 or an errno.
int write_all(int fd, std::string_view content) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

// fsyncs and closes `fd`, then renames `temp` over `target`. Removes `temp` and throws on failure.
void finish_temp(int fd, const fs::path& temp, const fs::path& target) {
  int err = (::fsync(fd) == 0) ? 0 : errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && std::rename(temp.c_str(), target.c_str()) != 0) err = errno;
  if (err != 0) {
    ::unlink(temp.c_str());
    throw_errno("cannot write", target, err);
  }
  sync_directory(parent_or_cwd(target));
}

}  // namespace

bool is_temp_file_name(std::string_view name) {
  constexpr std::string_view kTag = ".tmp";
  constexpr std::size_t kRandom = 6;  // mkstemp's XXXXXX
  if (name.size() < 1 + 1 + kTag.size() + kRandom || name.front() != '.') return false;
  const std::size_t tag = name.size() - kRandom - kTag.size();
  if (name.substr(tag, kTag.size()) != kTag) return false;
  for (const char c : name.substr(tag + kTag.size())) {
    if (!std::isalnum(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

std::size_t remove_temp_files(const fs::path& dir) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file(ec) && is_temp_file_name(e.path().filename().string()))
      removed += fs::remove(e.path(), ec) ? 1 : 0;
  }
  return removed;
}

void sync_directory(const fs::path& dir) noexcept {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

std::string read_text_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_errno("cannot read", path, errno);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw_errno("cannot read", path, errno);
  return text;
}

void write_file_atomic(const fs::path& path, std::string_view content) {
  fs::path temp;
  const int fd = make_temp(path, temp);
  if (const int err = write_all(fd, content); err != 0) {
    ::close(fd);
    ::unlink(temp.c_str());
    throw_errno("cannot write", path, err);
  }
  finish_temp(fd, temp, path);
}

AtomicWriter::AtomicWriter(fs::path target) : target_(std::move(target)) {
  fd_ = make_temp(target_, temp_);
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    const int err = errno;
    discard();
    throw_errno("cannot open temporary file for", target_, err);
  }
}

AtomicWriter::~AtomicWriter() {
  if (!committed_) discard();
}

void AtomicWriter::discard() noexcept {
  if (out_.is_open()) out_.close();
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

void AtomicWriter::commit() {
  if (committed_) throw std::logic_error("AtomicWriter::commit called twice");
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) {
    const int err = errno != 0 ? errno : EIO;
    discard();
    throw_errno("cannot write", target_, err);
  }
  const int fd = fd_;
  fd_ = -1;
  committed_ = true;  // finish_temp removes the temp file itself on failure
  finish_temp(fd, temp_, target_);
}

}  // namespace vrsph
