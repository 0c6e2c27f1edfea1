// Atomic file writes: content goes to a temporary file in the target's directory
// (".<name>.tmpXXXXXX"), is flushed and fsync'ed, then renamed over the target. A run killed at any
// moment therefore leaves either the old file or the complete new one, never a partial file.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace vrsph {

// Writes `content` to `path` atomically. Throws std::runtime_error (with the path and the errno
// text) on any failure; the temporary file is removed in that case.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

// Streaming variant for large files:
//   AtomicWriter w(path);
//   w.stream() << ...;   // or .write(bytes, n)
//   w.commit();          // flush, fsync, rename over `path`
// If commit() is not reached (exception, early return) the destructor removes the temporary file
// and the target is left untouched.
class AtomicWriter {
 public:
  explicit AtomicWriter(std::filesystem::path target);
  ~AtomicWriter();
  AtomicWriter(const AtomicWriter&) = delete;
  AtomicWriter& operator=(const AtomicWriter&) = delete;

  std::ostream& stream() { return out_; }
  void commit();

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temp_path() const { return temp_; }

 private:
  void discard() noexcept;

  std::filesystem::path target_;
  std::filesystem::path temp_;
  int fd_ = -1;  // kept open for fsync; the ofstream writes through its own descriptor
  std::ofstream out_;
  bool committed_ = false;
};

// Reads a whole file into a string; throws std::runtime_error (path and errno text) on failure.
std::string read_text_file(const std::filesystem::path& path);

// Removes the temporary files of atomic writes (".<name>.tmpXXXXXX") that a killed process left in
// `dir` and returns how many. Only for a folder no other process writes to (its run lock held).
std::size_t remove_temp_files(const std::filesystem::path& dir);

// Whether a file name has the form of such a temporary file.
bool is_temp_file_name(std::string_view name);

// fsyncs a directory so that a rename inside it is durable; errors are ignored (best effort).
void sync_directory(const std::filesystem::path& dir) noexcept;

}  // namespace vrsph
