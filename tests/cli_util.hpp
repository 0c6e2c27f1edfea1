// Helpers for the tests that run the real `vrsph` binary (test_cli.cpp, test_restart.cpp): a
// private temp folder per test, running the command with stdout/stderr captured to files, and
// small file readers.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace vrsph_cli {

namespace fs = std::filesystem;

inline const std::string kBinary = VRSPH_BINARY;
inline const fs::path kCases = VRSPH_CASES_DIR;

// The shipped cases.
inline std::string dam_break_2d() { return (kCases / "dam_break_2d.toml").string(); }
inline std::string dam_break_3d() { return (kCases / "dam_break_3d.toml").string(); }
inline std::string bench_case() { return (kCases / "bench_dam_break_2d.toml").string(); }

// What one invocation of the command gave back.
struct CmdResult {
  int status = -1;  // exit status; -1 when the process did not exit normally
  std::string out;  // stdout
  std::string err;  // stderr
  std::string command;

  // Non-empty lines of stderr.
  std::vector<std::string> err_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string l; std::getline(in, l);) {
      if (!l.empty()) lines.push_back(l);
    }
    return lines;
  }
};

inline std::ostream& operator<<(std::ostream& os, const CmdResult& r) {
  return os << "command: " << r.command << "\nstatus: " << r.status << "\nstdout:\n"
            << r.out << "\nstderr:\n"
            << r.err;
}

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::vector<std::string> read_lines(const fs::path& p) {
  std::vector<std::string> lines;
  std::ifstream in(p);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

inline void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

inline std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// Two files have the same bytes; on failure, says where they first differ (not the whole files).
inline ::testing::AssertionResult same_bytes(const fs::path& a, const fs::path& b) {
  if (!fs::exists(a)) return ::testing::AssertionFailure() << a << " does not exist";
  if (!fs::exists(b)) return ::testing::AssertionFailure() << b << " does not exist";
  const std::string ta = read_text(a), tb = read_text(b);
  if (ta == tb) return ::testing::AssertionSuccess();
  std::size_t i = 0;
  while (i < ta.size() && i < tb.size() && ta[i] == tb[i]) ++i;
  const long line = 1 + std::count(ta.begin(), ta.begin() + static_cast<long>(i), '\n');
  auto line_at = [](const std::string& t, std::size_t pos) {
    const std::size_t from = t.rfind('\n', pos == 0 ? 0 : pos - 1);
    const std::size_t start = from == std::string::npos ? 0 : from + 1;
    std::string l = t.substr(start, std::min<std::size_t>(t.find('\n', start) - start, 160));
    for (char& c : l) {
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    }
    return l;
  };
  return ::testing::AssertionFailure()
         << a << " (" << ta.size() << " bytes) and " << b << " (" << tb.size()
         << " bytes) differ from byte " << i << ", line " << line << ":\n  " << line_at(ta, i)
         << "\n  " << line_at(tb, i);
}

// Quotes a word for /bin/sh.
inline std::string sh_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

// A fresh folder under the system temp dir for one test, removed at the end (kept when the test
// failed, or when VRSPH_KEEP_TEST_DIRS is set, to look at afterwards). The command runs with this
// folder as its working directory, so a default `out/<case name>` lands in here too.
class TempDir {
 public:
  TempDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "_" + info->name() : "x";
    for (char& c : name) {
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    path_ = fs::temp_directory_path() / ("vrsph_cli_" + name + "_" + std::to_string(::getpid()) +
                                         "_" + std::to_string(counter()++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const bool failed = info && info->result() && info->result()->Failed();
    if (!failed && std::getenv("VRSPH_KEEP_TEST_DIRS") == nullptr) {
      std::error_code ec;
      fs::remove_all(path_, ec);
    }
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

  // Writes a file in the folder and returns its path.
  fs::path write(const std::string& name, const std::string& text) const {
    write_text(path_ / name, text);
    return path_ / name;
  }

  // Runs `vrsph ARGS...` in this folder; stdout and stderr go to files here, then into the result.
  // `shell` runs in the shell before it and `wrapper` wraps the command (see run_limited).
  CmdResult run(const std::vector<std::string>& args, const std::string& shell = "",
                const std::string& wrapper = "") {
    const int k = runs_++;
    const std::string stem = "cmd_" + std::to_string(k);
    const fs::path out_file = path_ / (stem + ".stdout");
    const fs::path err_file = path_ / (stem + ".stderr");
    std::string cmd = sh_quote(kBinary);
    for (const std::string& a : args) {
      cmd += ' ';
      cmd += sh_quote(a);
    }
    CmdResult r;
    r.command = cmd;
    std::string full = "cd ";  // built with += (g++ 12 warns falsely on "lit" + string)
    full += sh_quote(path_.string());
    // Threads that wait sleep instead of spinning: the results are the same, and a 2-thread run
    // on a busy 2-core machine does not crawl.
    full += " && ";
    full += shell;
    full += "OMP_WAIT_POLICY=passive ";
    full += wrapper;
    full += cmd;
    full += " >";
    full += sh_quote(out_file.string());
    full += " 2>";
    full += sh_quote(err_file.string());
    full += " </dev/null";
    const int raw = std::system(full.c_str());
    r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
    r.out = read_text(out_file);
    r.err = read_text(err_file);
    return r;
  }

  // run() with at most 4 GiB of address space and 120 s: a command that should refuse a case at
  // once fails (std::bad_alloc, exit 3; or the timeout, exit 124) instead of filling the machine.
  CmdResult run_limited(const std::vector<std::string>& args) {
    return run(args, "ulimit -v 4194304 && ", "timeout 120 ");
  }

 private:
  static int& counter() {
    static int n = 0;
    return n;
  }
  fs::path path_;
  int runs_ = 0;
};

// The arguments of a tiny 2D dam break run (dp = 0.04 m: 1250 fluid + 687 wall particles, about
// 120 us per step) into `out`, ending at `end_time` with snapshots every `interval` seconds.
inline std::vector<std::string> tiny_dam_break(const fs::path& out, double end_time,
                                               double interval, int threads = 1) {
  std::ostringstream e, i;
  e.precision(17);
  i.precision(17);
  e << end_time;
  i << interval;
  return {"run",
          dam_break_2d(),
          "--out",
          out.string(),
          "--quiet",
          "--threads",
          std::to_string(threads),
          "--set",
          "resolution.dp=0.04",
          "--set",
          "case.end_time=" + e.str(),
          "--set",
          "output.interval=" + i.str()};
}

// The file names of snapshot k.
inline std::string snapshot(int k, const std::string& ext) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "particles_%04d.%s", k, ext.c_str());
  return buf;
}

// The `timestep` / `file` attributes of the DataSet entries of a .pvd collection.
struct PvdEntry {
  double time;
  std::string file;
};
inline std::vector<PvdEntry> read_pvd(const fs::path& p) {
  std::vector<PvdEntry> entries;
  for (const std::string& line : read_lines(p)) {
    const auto ts = line.find("timestep=\"");
    const auto fl = line.find("file=\"");
    if (line.find("<DataSet") == std::string::npos || ts == std::string::npos ||
        fl == std::string::npos) {
      continue;
    }
    const auto ts_end = line.find('"', ts + 10);
    const auto fl_end = line.find('"', fl + 6);
    entries.push_back(
        {std::stod(line.substr(ts + 10, ts_end - ts - 10)), line.substr(fl + 6, fl_end - fl - 6)});
  }
  return entries;
}

}  // namespace vrsph_cli
