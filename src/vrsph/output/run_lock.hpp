// One run per output folder. A run holds `run.lock` in its folder for as long as it writes there:
// an exclusive flock(2) on the file, which the kernel drops when the process ends however it
// ends, and in the file the holder's pid, host and start time (to name it). A second run, resume
// or --force on that folder finds the flock taken and is refused naming the holder. A lock file
// whose flock is free was left by a run that died (killed, or the machine went down): it is taken
// over. Where the file system has no flock, the pid is checked for life on this host instead.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace vrsph {

class RunLock {
 public:
  static constexpr const char* kFileName = "run.lock";

  // Takes the lock of folder `dir` (which must exist). Throws CaseError
  // "<option> DIR: another vrsph run (pid N on host H, started T) is writing to this folder: ..."
  // when a live run holds it, std::runtime_error when the lock file cannot be made.
  RunLock(const std::filesystem::path& dir, std::string_view option);
  // Removes the lock file and releases the lock.
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

  // The holder named in a lock file that was taken over ("pid N on host H, started T"), or empty
  // when the folder was free.
  const std::string& stale_holder() const { return stale_holder_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::string stale_holder_;
};

}  // namespace vrsph
