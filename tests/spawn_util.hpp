// Starting the `vrsph` binary in the background (the tests of the output folder's lock and of
// stop signals need a run that is still going): fork + exec with stdout and stderr to files,
// waiting for a file to appear, and collecting the exit status.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli_util.hpp"

namespace vrsph_cli {

// A `vrsph ARGS...` process started in folder `cwd`; stdout and stderr go to `<stem>.stdout` and
// `<stem>.stderr` there.
class Spawned {
 public:
  Spawned(const fs::path& cwd, const std::vector<std::string>& args, const std::string& stem)
      : out_(cwd / (stem + ".stdout")), err_(cwd / (stem + ".stderr")) {
    // Everything the child needs is made before fork: it only opens, dups and execs.
    std::vector<std::string> argv_s = {kBinary};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string dir = cwd.string(), out = out_.string(), err = err_.string();
    ::setenv("OMP_WAIT_POLICY", "passive", 1);  // as TempDir::run
    pid_ = ::fork();
    if (pid_ == 0) {
      const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int in = ::open("/dev/null", O_RDONLY);
      if (o < 0 || e < 0 || in < 0 || ::chdir(dir.c_str()) != 0) ::_exit(127);
      ::dup2(o, 1), ::dup2(e, 2), ::dup2(in, 0);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~Spawned() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      wait();
    }
  }
  Spawned(const Spawned&) = delete;
  Spawned& operator=(const Spawned&) = delete;

  pid_t pid() const { return pid_; }
  void signal(int sig) const { ::kill(pid_, sig); }

  // Waits for the process; the exit status, or 128 + the signal that killed it.
  int wait() {
    if (waited_) return status_;
    int raw = 0;
    ::waitpid(pid_, &raw, 0);
    waited_ = true;
    status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    return status_;
  }
  // Whether the process has ended (reaps it when it has).
  bool ended() {
    if (waited_) return true;
    int raw = 0;
    if (::waitpid(pid_, &raw, WNOHANG) != pid_) return false;
    waited_ = true;
    status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    return true;
  }
  std::string out() const { return read_text(out_); }
  std::string err() const { return read_text(err_); }

 private:
  fs::path out_, err_;
  pid_t pid_ = -1;
  bool waited_ = false;
  int status_ = -1;
};

// Waits until `path` exists (up to `seconds`) or the process ends; whether it exists.
inline bool wait_for_file(const fs::path& path, Spawned& p, double seconds = 60.0) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!fs::exists(path)) {
    if (p.ended() || std::chrono::steady_clock::now() > until) return fs::exists(path);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace vrsph_cli
