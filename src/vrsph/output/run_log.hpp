// run.log: the story of a run in its output folder, one timestamped line per event: the start
// (or resume), one line per output time, the takeover of a stale lock, and how the run ended.
// A fresh run starts the file, a resumed one appends to it. Each line is one write(2) in append
// mode, so a killed run leaves whole lines only.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace vrsph {

// The local time as "YYYY-MM-DD HH:MM:SS".
std::string local_time_text();

class RunLog {
 public:
  static constexpr const char* kFileName = "run.log";

  // fresh: start a new run.log in `dir` (replacing an earlier one); otherwise append to it.
  // Throws std::runtime_error (path and errno text) when it cannot be opened.
  RunLog(const std::filesystem::path& dir, bool fresh);
  ~RunLog();
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;

  // Appends "[local time] text\n". Throws std::runtime_error when it cannot be written.
  void line(std::string_view text);

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace vrsph
