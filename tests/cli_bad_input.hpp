// The bad-input test shared by test_cli_bad_input.cpp (which defines it) and
// test_cli_setup_guards.cpp (more cases): each case is fed to `vrsph check` and `vrsph run`
// under a 4 GiB address-space limit and a timeout (TempDir::run_limited), and must give exit
// status 1 and exactly one line on stderr holding every expected fragment, without creating the
// output folder.
#pragma once

#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "cli_util.hpp"

namespace vrsph_cli_cases {

struct BadInput {
  std::string name;
  std::string case_text;            // written to bad.toml; empty: no file written
  std::string case_arg;             // the case path given on the command line (default bad.toml)
  std::vector<std::string> args;    // extra arguments (--set ...)
  std::vector<std::string> expect;  // substrings of the one stderr line
};

inline std::ostream& operator<<(std::ostream& os, const BadInput& b) { return os << b.name; }

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

inline void expect_bad_input(const vrsph_cli::CmdResult& r, const BadInput& b) {
  EXPECT_EQ(r.status, 1) << r;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r;
  EXPECT_EQ(r.err.back(), '\n') << r;
  for (const std::string& s : b.expect) {
    EXPECT_NE(lines[0].find(s), std::string::npos) << "stderr line lacks '" << s << "'\n" << r;
  }
}

}  // namespace vrsph_cli_cases
