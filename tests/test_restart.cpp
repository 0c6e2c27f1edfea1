// `vrsph run --resume DIR` (docs/outputs.md "checkpoint.bin"; README: "--resume continues from
// the checkpoint and reaches the same final state, bit for bit, as an uninterrupted run with the
// same thread count"). A run is stopped abruptly with the hidden testing option
// `--halt-after-output K` (exit status 9 right after snapshot K, as a kill would), resumed, and
// compared byte for byte with an uninterrupted run.
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cli_util.hpp"
#include "restart_util.hpp"

namespace {

using namespace vrsph_cli;

// 2D dam break at dp = 0.04 m to 20 ms, a snapshot every 5 ms: snapshots 0..4, 172 steps.
std::vector<std::string> dam_break_20ms(const fs::path& out) {
  return tiny_dam_break(out, 0.02, 0.005);
}

TEST(Restart, HaltedRunResumesToTheSameBytes2D) {
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b";
  const CmdResult ra = dir.run(dam_break_20ms(a));
  ASSERT_EQ(ra.status, 0) << ra;

  const CmdResult halted = dir.run(with(dam_break_20ms(b), {"--halt-after-output", "2"}));
  ASSERT_EQ(halted.status, kExitHalted) << halted;
  ASSERT_TRUE(fs::exists(b / snapshot(2, "csv")));
  EXPECT_FALSE(fs::exists(b / snapshot(3, "csv"))) << "halted right after snapshot 2";
  EXPECT_TRUE(fs::exists(b / "checkpoint.bin"));
  EXPECT_EQ(read_lines(b / "series.csv").size(), 1u + 3u);
  expect_clean_pvd(b, 3);

  const CmdResult resumed = dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1"});
  ASSERT_EQ(resumed.status, 0) << resumed;
  EXPECT_TRUE(resumed.err.empty()) << resumed;
  expect_same_outputs(a, b, 4, true);
  EXPECT_TRUE(same_bytes(a / "case.toml", b / "case.toml"));
}

// The same in mixed precision (numerics.precision): the checkpoint holds the double state, and
// the float copies of the force pass are made again from it.
TEST(Restart, HaltedMixedPrecisionRunResumesToTheSameBytes) {
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b";
  const std::vector<std::string> mixed = {"--set", "numerics.precision=\"mixed\""};
  const CmdResult ra = dir.run(with(dam_break_20ms(a), mixed));
  ASSERT_EQ(ra.status, 0) << ra;
  const CmdResult halted =
      dir.run(with(with(dam_break_20ms(b), mixed), {"--halt-after-output", "2"}));
  ASSERT_EQ(halted.status, kExitHalted) << halted;
  const CmdResult resumed = dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1"});
  ASSERT_EQ(resumed.status, 0) << resumed;
  expect_same_outputs(a, b, 4, true);
  // and it is not the double run
  const fs::path c = dir / "c";
  ASSERT_EQ(dir.run(with(dam_break_20ms(c), {"--set", "numerics.precision=\"double\""})).status, 0);
  EXPECT_FALSE(same_bytes(a / snapshot(4, "csv"), c / snapshot(4, "csv")));
}

TEST(Restart, HaltedTwiceResumesToTheSameBytes) {
  // Halt after snapshot 1, resume and halt again after snapshot 3, resume to the end.
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b";
  ASSERT_EQ(dir.run(dam_break_20ms(a)).status, 0);
  const CmdResult h1 = dir.run(with(dam_break_20ms(b), {"--halt-after-output", "1"}));
  ASSERT_EQ(h1.status, kExitHalted) << h1;
  const CmdResult h2 = dir.run(
      {"run", "--resume", b.string(), "--quiet", "--threads", "1", "--halt-after-output", "3"});
  ASSERT_EQ(h2.status, kExitHalted) << h2;
  EXPECT_FALSE(fs::exists(b / snapshot(4, "csv")));
  const CmdResult r = dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r;
  expect_same_outputs(a, b, 4, true);
}

TEST(Restart, ResumeDropsOutputsWrittenAfterTheCheckpoint) {
  // A kill between a snapshot's files and its checkpoint leaves series rows and pvd entries newer
  // than the checkpoint: here a finished run gets the checkpoint of snapshot 2 back. Resuming
  // redoes snapshots 3 and 4 and lists each once.
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b", c = dir / "c";
  ASSERT_EQ(dir.run(dam_break_20ms(a)).status, 0);
  ASSERT_EQ(dir.run(with(dam_break_20ms(b), {"--halt-after-output", "2"})).status, kExitHalted);
  ASSERT_EQ(dir.run(dam_break_20ms(c)).status, 0);
  fs::copy_file(b / "checkpoint.bin", c / "checkpoint.bin", fs::copy_options::overwrite_existing);
  fs::remove(c / "summary.json");
  const CmdResult r = dir.run({"run", "--resume", c.string(), "--quiet", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r;
  expect_same_outputs(a, c, 4, true);
}

TEST(Restart, LaterEndTimeContinuesAFinishedRun) {
  TempDir dir;
  const fs::path a = dir / "a";
  ASSERT_EQ(dir.run(dam_break_20ms(a)).status, 0);
  const auto series_before = read_lines(a / "series.csv");

  // Resuming a finished run without a later end time: nothing to do, refused as bad input.
  const CmdResult same = dir.run({"run", "--resume", a.string(), "--quiet", "--threads", "1"});
  EXPECT_EQ(same.status, 1) << same;
  ASSERT_EQ(same.err_lines().size(), 1u) << same;
  EXPECT_NE(same.err.find("case.end_time"), std::string::npos) << same;
  EXPECT_EQ(read_lines(a / "series.csv"), series_before);

  const CmdResult more = dir.run(
      {"run", "--resume", a.string(), "--quiet", "--threads", "1", "--set", "case.end_time=0.03"});
  ASSERT_EQ(more.status, 0) << more;
  const auto series = read_lines(a / "series.csv");
  ASSERT_EQ(series.size(), 1u + 7u) << read_text(a / "series.csv");  // t = 0, 5, ..., 30 ms
  for (std::size_t k = 0; k < series_before.size(); ++k) EXPECT_EQ(series[k], series_before[k]);
  double last_t = -1.0;
  for (std::size_t k = 1; k < series.size(); ++k) {
    const double t = std::stod(split_csv(series[k])[0]);
    EXPECT_GT(t, last_t);
    last_t = t;
  }
  EXPECT_NEAR(last_t, 0.03, 1e-12);
  expect_clean_pvd(a, 7);
  EXPECT_TRUE(fs::exists(a / snapshot(6, "csv")));
  const auto sj = nlohmann::json::parse(read_text(a / "summary.json"));
  EXPECT_EQ(sj.at("completed"), true);
  EXPECT_NEAR(sj.at("sim_time").get<double>(), 0.03, 1e-12);
  EXPECT_NE(read_text(a / "case.toml").find("end_time = 0.03"), std::string::npos);
}

TEST(Restart, LaterEndTimeMatchesAnUninterruptedRun) {
  // Steps land on output times and the end time, so extending a run from its end time
  // retraces an uninterrupted one; output times follow the interval from the resume time.
  TempDir dir;
  const fs::path a = dir / "a", c = dir / "c";
  ASSERT_EQ(dir.run(dam_break_20ms(a)).status, 0);
  const CmdResult more = dir.run(
      {"run", "--resume", a.string(), "--quiet", "--threads", "1", "--set", "case.end_time=0.03"});
  ASSERT_EQ(more.status, 0) << more;
  ASSERT_EQ(dir.run(tiny_dam_break(c, 0.03, 0.005)).status, 0);
  expect_same_outputs(c, a, 6, true);
}

TEST(Restart, HaltedRunResumedToALaterEndTimeMatchesAnUninterruptedRun) {
  // A run halted before its end never took the short step that lands on the end time, so
  // resuming it to a later end time is the same as running there in one go.
  TempDir dir;
  const fs::path b = dir / "b", c = dir / "c";
  ASSERT_EQ(dir.run(with(dam_break_20ms(b), {"--halt-after-output", "2"})).status, kExitHalted);
  const CmdResult r = dir.run(
      {"run", "--resume", b.string(), "--quiet", "--threads", "1", "--set", "case.end_time=0.03"});
  ASSERT_EQ(r.status, 0) << r;
  ASSERT_EQ(dir.run(tiny_dam_break(c, 0.03, 0.005)).status, 0);
  expect_same_outputs(c, b, 6, true);
  EXPECT_TRUE(same_bytes(c / "case.toml", b / "case.toml"));
}

TEST(Restart, NewOutputIntervalAppliesFromTheResumeTime) {
  // Steps land on output times and the end time, so extending a run from its end time
  // retraces an uninterrupted one; output times follow the interval from the resume time.
  TempDir dir;
  const fs::path b = dir / "b";
  ASSERT_EQ(dir.run(with(dam_break_20ms(b), {"--halt-after-output", "2"})).status, kExitHalted);
  const CmdResult r = dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1", "--set",
                               "output.interval=0.0025"});
  ASSERT_EQ(r.status, 0) << r;
  const auto series = read_lines(b / "series.csv");
  ASSERT_EQ(series.size(), 1u + 3u + 4u) << read_text(b / "series.csv");
  const double dt_max = 2e-4;  // about 1.2e-4 s per step here
  for (int k = 0; k < 4; ++k) {
    const double t = std::stod(split_csv(series[4 + k])[0]);
    EXPECT_GE(t, 0.0125 + 0.0025 * k - 1e-12) << series[4 + k];
    EXPECT_LE(t, 0.0125 + 0.0025 * k + dt_max) << series[4 + k];
  }
  expect_clean_pvd(b, 7);
}

TEST(Restart, PhysicalOverridesAreRefused) {
  TempDir dir;
  const fs::path b = dir / "b";
  ASSERT_EQ(dir.run(with(dam_break_20ms(b), {"--halt-after-output", "1"})).status, kExitHalted);
  const std::string case_before = read_text(b / "case.toml");
  const std::string series_before = read_text(b / "series.csv");
  for (const char* set : {"resolution.dp=0.05", "eos.sound_speed=50", "numerics.cfl=0.1",
                          "fluid_block.0.max=[0.5, 1.0]"}) {
    const CmdResult r =
        dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1", "--set", set});
    EXPECT_EQ(r.status, 1) << r;
    const auto lines = r.err_lines();
    ASSERT_EQ(lines.size(), 1u) << r;
    const std::string key = std::string(set).substr(0, std::string(set).find('='));
    EXPECT_NE(lines[0].find(key), std::string::npos) << r;
    EXPECT_EQ(read_text(b / "case.toml"), case_before) << set;
    EXPECT_EQ(read_text(b / "series.csv"), series_before) << set;
  }
  // A case file and --resume together are refused too.
  const CmdResult both = dir.run({"run", dam_break_2d(), "--resume", b.string(), "--quiet"});
  EXPECT_EQ(both.status, 1) << both;
  EXPECT_EQ(both.err_lines().size(), 1u) << both;
  // The folder can still be resumed afterwards.
  const CmdResult ok = dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1"});
  EXPECT_EQ(ok.status, 0) << ok;
}

TEST(Restart, SpacedEndTimeOverrideIsAcceptedOnResume) {
  // Steps land on output times and the end time, so extending a run from its end time
  // retraces an uninterrupted one; output times follow the interval from the resume time.
  TempDir dir;
  const fs::path a = dir / "a";
  ASSERT_EQ(dir.run(dam_break_20ms(a)).status, 0);
  const CmdResult r = dir.run({"run", "--resume", a.string(), "--quiet", "--threads", "1", "--set",
                               "case.end_time = 0.025"});
  EXPECT_EQ(r.status, 0) << r;
}

TEST(Restart, FolderWithoutCheckpointFailsCleanly) {
  TempDir dir;
  // No such folder; an empty folder.
  fs::create_directories(dir / "empty");
  for (const char* d : {"missing", "empty"}) {
    const CmdResult r = dir.run({"run", "--resume", (dir / d).string(), "--quiet"});
    EXPECT_EQ(r.status, 1) << r;
    EXPECT_EQ(r.err_lines().size(), 1u) << r;
    EXPECT_NE(r.err.find(d), std::string::npos) << r;
  }
  EXPECT_FALSE(fs::exists(dir / "missing"));
  EXPECT_TRUE(fs::is_empty(dir / "empty"));

  // A finished run whose checkpoint is gone, garbage or truncated: a one-line reason naming the
  // checkpoint, a failure status (1 bad input or 3 I/O error), and the folder left as it was.
  const fs::path a = dir / "a";
  ASSERT_EQ(dir.run(tiny_dam_break(a, 0.005, 0.005)).status, 0);
  const std::string checkpoint = read_text(a / "checkpoint.bin");
  ASSERT_GT(checkpoint.size(), 1000u);
  const std::string case_before = read_text(a / "case.toml");
  const std::string series_before = read_text(a / "series.csv");
  const std::string pvd_before = read_text(a / "particles.pvd");
  const std::string summary_before = read_text(a / "summary.json");
  const std::vector<std::pair<std::string, std::string>> variants = {
      {"missing", ""},
      {"garbage", "this is not a checkpoint\n"},
      {"truncated", checkpoint.substr(0, checkpoint.size() / 2)}};
  for (const auto& [what, content] : variants) {
    fs::remove(a / "checkpoint.bin");
    if (what != "missing") write_text(a / "checkpoint.bin", content);
    const CmdResult r = dir.run({"run", "--resume", a.string(), "--quiet", "--threads", "1",
                                 "--set", "case.end_time=0.01"});
    EXPECT_TRUE(r.status == 1 || r.status == 3) << what << "\n" << r;
    const auto lines = r.err_lines();
    ASSERT_EQ(lines.size(), 1u) << what << "\n" << r;
    EXPECT_NE(lines[0].find("checkpoint"), std::string::npos) << what << "\n" << r;
    EXPECT_EQ(read_text(a / "case.toml"), case_before) << what;
    EXPECT_EQ(read_text(a / "series.csv"), series_before) << what;
    EXPECT_EQ(read_text(a / "particles.pvd"), pvd_before) << what;
    EXPECT_EQ(read_text(a / "summary.json"), summary_before) << what;
    EXPECT_FALSE(fs::exists(a / snapshot(2, "csv"))) << what;
  }
}

// A checkpoint of an older format (version 1: counters by position) is refused on resume with
// one line naming its version, and the folder is left as it was.
TEST(Restart, CheckpointOfAnOlderFormatIsRefused) {
  TempDir dir;
  const fs::path a = dir / "a";
  ASSERT_EQ(dir.run(tiny_dam_break(a, 0.005, 0.005)).status, 0);
  std::string checkpoint = read_text(a / "checkpoint.bin");
  ASSERT_GT(checkpoint.size(), 12u);
  const std::uint32_t old_version = 1;
  checkpoint.replace(8, 4, reinterpret_cast<const char*>(&old_version), 4);
  write_text(a / "checkpoint.bin", checkpoint);
  const std::string series_before = read_text(a / "series.csv");
  const CmdResult r = dir.run(
      {"run", "--resume", a.string(), "--quiet", "--threads", "1", "--set", "case.end_time=0.01"});
  EXPECT_NE(r.status, 0) << r;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r;
  EXPECT_NE(lines[0].find("checkpoint format version 1 is not supported"), std::string::npos) << r;
  EXPECT_EQ(read_text(a / "series.csv"), series_before);
  EXPECT_FALSE(fs::exists(a / snapshot(2, "vtp")));
}

TEST(Restart, HaltedRunResumesToTheSameBytes3D) {
  // 3D dam break at dp = 0.05 m (768 fluid + 6261 wall particles) to 4 ms, a snapshot every ms
  // (18 steps), with csv snapshots too.
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b";
  auto args = [&](const fs::path& out) {
    return std::vector<std::string>{"run",
                                    dam_break_3d(),
                                    "--out",
                                    out.string(),
                                    "--quiet",
                                    "--threads",
                                    "1",
                                    "--set",
                                    "resolution.dp=0.05",
                                    "--set",
                                    "case.end_time=0.004",
                                    "--set",
                                    "output.interval=0.001",
                                    "--set",
                                    "output.formats=[\"vtp\", \"csv\"]"};
  };
  const CmdResult ra = dir.run(args(a));
  ASSERT_EQ(ra.status, 0) << ra;
  const CmdResult halted = dir.run(with(args(b), {"--halt-after-output", "2"}));
  ASSERT_EQ(halted.status, kExitHalted) << halted;
  EXPECT_FALSE(fs::exists(b / snapshot(3, "vtp")));
  const CmdResult resumed = dir.run({"run", "--resume", b.string(), "--quiet", "--threads", "1"});
  ASSERT_EQ(resumed.status, 0) << resumed;
  expect_same_outputs(a, b, 4, true);
}

}  // namespace
