// `vrsph run --resume DIR` on variable resolution (test_restart.cpp for the rest): two levels,
// with the capillary refresh and with local time stepping, halted and resumed to the same bytes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_util.hpp"
#include "restart_util.hpp"

namespace {

using namespace vrsph_cli;

// droplet_vr_2d at dp 2e-4 / 1e-4 to 6 ms, a snapshot every 1.5 ms, halted after snapshot 2 and
// resumed: two levels, buffers, mass points with stored masses and kind changes all go through
// the checkpoint (and, with the capillary refresh, the held capillary acceleration).
void expect_vr_drop_resumes(const std::vector<std::string>& sets) {
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b";
  auto args = [&](const fs::path& out) {
    std::vector<std::string> v = {"run",     (kCases / "droplet_vr_2d.toml").string(),
                                  "--out",   out.string(),
                                  "--quiet", "--threads",
                                  "1"};
    for (const char* k : {"resolution.dp=2e-4", "case.end_time=0.006", "output.interval=0.0015"})
      v.insert(v.end(), {"--set", k});
    return with(v, sets);
  };
  const CmdResult ra = dir.run(args(a));
  ASSERT_EQ(ra.status, 0) << ra;
  const CmdResult halted = dir.run(with(args(b), {"--halt-after-output", "2"}));
  ASSERT_EQ(halted.status, kExitHalted) << halted;
  const CmdResult resumed = dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1"});
  ASSERT_EQ(resumed.status, 0) << resumed;
  expect_same_outputs(a, b, 4, true);
  const auto lines = read_lines(a / "series.csv");
  EXPECT_NE(lines.front().find("n_fluid_L1"), std::string::npos);
}

TEST(Restart, HaltedVariableResolutionRunResumesToTheSameBytes) { expect_vr_drop_resumes({}); }

// A folder whose case.toml has no refresh key (every_step runs, and every run made before the
// key existed) resumes refreshing every step, although "capillary" is the default of case files,
// and its case.toml still has no such key.
TEST(Restart, FolderWithoutTheRefreshKeyResumesRefreshingEveryStep) {
  const std::vector<std::string> every = {"--set",
                                          "numerics.surface_tension.refresh=\"every_step\""};
  expect_vr_drop_resumes(every);
  TempDir dir;
  const fs::path a = dir / "a";
  ASSERT_EQ(dir.run(with({"run", (kCases / "droplet_2d.toml").string(), "--out", a.string(),
                          "--quiet", "--set", "resolution.dp=2e-4", "--set", "case.end_time=0.001"},
                         every))
                .status,
            0);
  const std::string text = read_text(a / "case.toml");
  EXPECT_EQ(text.find("refresh"), std::string::npos) << text;
}

// A folder whose case.toml has no numerics.precision (double runs, and every run made before the
// key existed) resumes in double to the bytes of the uninterrupted double run, although "mixed"
// is the default of case files; a mixed run's folder names the key.
TEST(Restart, FolderWithoutThePrecisionKeyResumesInDouble) {
  const std::vector<std::string> dbl = {"--set", "numerics.precision=\"double\""};
  expect_vr_drop_resumes(dbl);
  TempDir dir;
  const fs::path d = dir / "d", m = dir / "m";
  const std::vector<std::string> small = {"--quiet", "--set", "resolution.dp=2e-4", "--set",
                                          "case.end_time=0.001"};
  const std::string drop = (kCases / "droplet_2d.toml").string();
  ASSERT_EQ(dir.run(with(with({"run", drop, "--out", d.string()}, small), dbl)).status, 0);
  const std::vector<std::string> mixed = {"--set", "numerics.precision=\"mixed\""};
  ASSERT_EQ(dir.run(with(with({"run", drop, "--out", m.string()}, small), mixed)).status, 0);
  EXPECT_EQ(read_text(d / "case.toml").find("precision = \"mixed\""), std::string::npos);
  EXPECT_NE(read_text(m / "case.toml").find("precision = \"mixed\""), std::string::npos);
}

// The halt falls between two refreshes (the resumed run must not refresh early), and with local
// time stepping at a meeting of the levels, each with its own next dt.
TEST(Restart, HaltedCapillaryRefreshAndLocalTimeSteppingRunsResumeToTheSameBytes) {
  const std::vector<std::string> cap = {"--set", "numerics.surface_tension.refresh=\"capillary\"",
                                        "--set", "numerics.surface_tension.refresh_interval=0.5"};
  expect_vr_drop_resumes(cap);
  expect_vr_drop_resumes(with(cap, {"--set", "numerics.local_time_stepping=true"}));
}

}  // namespace
