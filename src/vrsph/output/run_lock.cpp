// The output folder's lock (see run_lock.hpp).
#include "vrsph/output/run_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "vrsph/output/run_log.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace vrsph {
namespace {

std::string host_name() {
  char buf[HOST_NAME_MAX + 1] = {};
  if (::gethostname(buf, sizeof(buf) - 1) != 0) return "unknown";
  return buf;
}

std::string read_all(int fd) {
  std::string text(4096, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return text;
}

// The holder written in a lock file: "pid N", "host H" and "started T" lines.
struct Holder {
  long pid = 0;
  std::string host, started;

  static Holder parse(const std::string& text) {
    Holder h;
    std::istringstream in(text);
    for (std::string key, rest; in >> key && std::getline(in >> std::ws, rest);) {
      if (key == "pid") h.pid = std::strtol(rest.c_str(), nullptr, 10);
      if (key == "host") h.host = rest;
      if (key == "started") h.started = rest;
    }
    return h;
  }
  std::string text() const {
    return fmt::format("pid {} on host {}, started {}", pid, host.empty() ? "?" : host,
                       started.empty() ? "?" : started);
  }
  // Only for file systems without flock: the holder is a live process of this host (or of
  // another host, which cannot be told).
  bool may_be_alive() const {
    if (pid <= 0) return false;
    if (host != host_name()) return true;
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
  }
};

// The holder of a taken lock; a run that has just taken it may not have written itself yet.
Holder wait_for_holder(int fd) {
  Holder h = Holder::parse(read_all(fd));
  for (int k = 0; k < 100 && h.pid == 0; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    h = Holder::parse(read_all(fd));
  }
  return h;
}

[[noreturn]] void refuse(std::string_view option, const std::filesystem::path& dir,
                         const Holder& h) {
  throw CaseError(fmt::format(
      "{} {}: another vrsph run ({}) is writing to this folder: wait for it to end or stop it "
      "(kill {}); the lock is {}",
      option, dir.string(), h.text(), h.pid, (dir / RunLock::kFileName).string()));
}

// Whether `fd` is still the file at `path` (its holder removes the file when it ends, so a lock
// taken on the descriptor of a removed file is no lock).
bool same_file(int fd, const std::filesystem::path& path) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

}  // namespace

RunLock::RunLock(const std::filesystem::path& dir, std::string_view option)
    : path_(dir / kFileName) {
  for (;;) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) {
      throw std::runtime_error(fmt::format("cannot create the lock file '{}': {}", path_.string(),
                                           std::strerror(errno)));
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      const Holder h = wait_for_holder(fd_);
      if (err == EWOULDBLOCK || h.may_be_alive()) {
        ::close(fd_);
        fd_ = -1;
        refuse(option, dir, h);
      }
      // No flock on this file system and the holder is gone: taken over without one.
    }
    if (same_file(fd_, path_)) break;
    ::close(fd_);  // the holder ended and removed the file in between: lock the new one
  }
  const std::string before = read_all(fd_);
  if (!before.empty()) stale_holder_ = Holder::parse(before).text();
  const std::string mine =
      fmt::format("pid {}\nhost {}\nstarted {}\n", ::getpid(), host_name(), local_time_text());
  if (::ftruncate(fd_, 0) != 0 ||
      ::pwrite(fd_, mine.data(), mine.size(), 0) != static_cast<ssize_t>(mine.size())) {
    const int err = errno;
    ::close(fd_);
    throw std::runtime_error(
        fmt::format("cannot write the lock file '{}': {}", path_.string(), std::strerror(err)));
  }
}

RunLock::~RunLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // before the flock goes, so no one locks a file about to vanish
  ::close(fd_);
}

}  // namespace vrsph
