// What the resume tests share (test_restart*.cpp): the exit status of a halted run and the
// byte-for-byte comparison of two output folders.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_util.hpp"

namespace vrsph_cli {

inline constexpr int kExitHalted = 9;

inline std::vector<std::string> with(std::vector<std::string> args,
                                     const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// Every snapshot in the pvd once, in order, with increasing times.
inline void expect_clean_pvd(const fs::path& dir, std::size_t n) {
  const auto pvd = read_pvd(dir / "particles.pvd");
  ASSERT_EQ(pvd.size(), n) << read_text(dir / "particles.pvd");
  std::set<std::string> files;
  for (std::size_t k = 0; k < pvd.size(); ++k) {
    EXPECT_EQ(pvd[k].file, snapshot(static_cast<int>(k), "vtp"));
    files.insert(pvd[k].file);
    if (k > 0) {
      EXPECT_GT(pvd[k].time, pvd[k - 1].time);
    }
  }
  EXPECT_EQ(files.size(), n);
}

// The deterministic part of summary.json (no timings) is the same.
inline void expect_same_summary(const fs::path& a, const fs::path& b) {
  const auto ja = nlohmann::json::parse(read_text(a / "summary.json"));
  const auto jb = nlohmann::json::parse(read_text(b / "summary.json"));
  for (const char* key :
       {"completed", "steps", "sim_time", "n_particles", "threads", "lost_fluid", "dt_limits"}) {
    EXPECT_EQ(ja.value(key, nlohmann::json()), jb.value(key, nlohmann::json())) << key;
  }
}

// Snapshots 0..last of both folders are byte-identical (csv where written, and vtp), as are
// series.csv and particles.pvd.
inline void expect_same_outputs(const fs::path& a, const fs::path& b, int last, bool csv) {
  for (int k = 0; k <= last; ++k) {
    ASSERT_TRUE(fs::exists(b / snapshot(k, "vtp"))) << k;
    EXPECT_TRUE(same_bytes(a / snapshot(k, "vtp"), b / snapshot(k, "vtp"))) << "snapshot " << k;
    if (csv) {
      EXPECT_TRUE(same_bytes(a / snapshot(k, "csv"), b / snapshot(k, "csv"))) << "snapshot " << k;
    }
  }
  EXPECT_FALSE(fs::exists(b / snapshot(last + 1, "vtp")));
  EXPECT_TRUE(same_bytes(a / "series.csv", b / "series.csv"));
  EXPECT_TRUE(same_bytes(a / "particles.pvd", b / "particles.pvd"));
  expect_clean_pvd(b, static_cast<std::size_t>(last + 1));
  expect_same_summary(a, b);
}

}  // namespace vrsph_cli
