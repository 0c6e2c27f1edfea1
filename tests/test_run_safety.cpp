// A run's folder is its own (README "Output folder, lock and run.log"): a second run into a live
// folder is refused naming the holder and leaves the first run's files as an uninterrupted run's;
// a killed run's lock and temporary files are cleared; a damaged, truncated or foreign
// checkpoint is refused naming the file and what is wrong; SIGTERM and SIGINT stop a run with a
// checkpoint it resumes from bit for bit; off a terminal a run prints a line per output time, and
// run.log keeps them all.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_cases.hpp"
#include "cli_util.hpp"
#include "spawn_util.hpp"

namespace {

using namespace vrsph_cli;

constexpr int kExitHalted = 9;

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

std::vector<std::string> resume(const fs::path& dir, const std::vector<std::string>& more = {}) {
  return with({"run", "--resume", dir.string(), "--quiet", "--threads", "1"}, more);
}

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

// Snapshots 0..last (csv and vtp), series.csv and particles.pvd have the same bytes.
void expect_same_run(const fs::path& a, const fs::path& b, int last) {
  for (int k = 0; k <= last; ++k) {
    EXPECT_TRUE(same_bytes(a / snapshot(k, "csv"), b / snapshot(k, "csv"))) << k;
    EXPECT_TRUE(same_bytes(a / snapshot(k, "vtp"), b / snapshot(k, "vtp"))) << k;
  }
  EXPECT_FALSE(fs::exists(b / snapshot(last + 1, "vtp")));
  EXPECT_TRUE(same_bytes(a / "series.csv", b / "series.csv"));
  EXPECT_TRUE(same_bytes(a / "particles.pvd", b / "particles.pvd"));
}

TEST(RunSafety, SecondRunIntoALiveFolderIsRefusedAndTheFirstIsIntact) {
  // Run A is frozen (SIGSTOP) once it has written its case, so it holds the folder for sure
  // while a second run, a --force run and a --resume try it; then it goes on to its end.
  TempDir dir;
  const fs::path a = dir / "a", c = dir / "c";
  const auto args = tiny_dam_break(a, 0.05, 0.0125);
  Spawned first(dir.path(), args, "first");
  ASSERT_TRUE(wait_for_file(a / "case.toml", first)) << first.err();
  first.signal(SIGSTOP);
  ASSERT_FALSE(first.ended()) << "the run ended before it could be frozen";
  const std::string holder = "pid " + std::to_string(first.pid());
  for (const auto& second : {args, with(args, {"--force"}), resume(a)}) {
    const CmdResult r = dir.run(second);
    EXPECT_EQ(r.status, 1) << r;
    ASSERT_EQ(r.err_lines().size(), 1u) << r;
    EXPECT_TRUE(contains(r.err, holder)) << r;
    EXPECT_TRUE(contains(r.err, a.string())) << r;
  }
  first.signal(SIGCONT);
  ASSERT_EQ(first.wait(), 0) << first.err();
  EXPECT_FALSE(fs::exists(a / "run.lock")) << "released at the end";
  EXPECT_FALSE(contains(read_text(a / "run.log"), "another vrsph run"));
  ASSERT_EQ(dir.run(tiny_dam_break(c, 0.05, 0.0125)).status, 0);
  expect_same_run(c, a, 4);
  EXPECT_TRUE(same_bytes(c / "case.toml", a / "case.toml"));
}

TEST(RunSafety, KilledRunsLockAndTemporaryFilesAreCleared) {
  TempDir dir;
  const fs::path b = dir / "b";
  ASSERT_EQ(dir.run(tiny_dam_break(b, 0.02, 0.005)).status, 0);
  const fs::path h = dir / "h";
  ASSERT_EQ(dir.run(with(tiny_dam_break(h, 0.02, 0.005), {"--halt-after-output", "1"})).status,
            kExitHalted);
  // The halted run (as a kill) left its lock naming it; a write it was doing left a temp file.
  const std::string lock = read_text(h / "run.lock");
  ASSERT_EQ(lock.rfind("pid ", 0), 0u) << lock;
  const std::string dead_pid = lock.substr(4, lock.find('\n') - 4);
  write_text(h / ".series.csv.tmpAb12Cd", "t,step\n0,");
  write_text(h / "notes.tmp", "mine");
  const CmdResult r = dir.run(resume(h));
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_TRUE(contains(r.out, "took over the stale lock of pid " + dead_pid)) << r;
  EXPECT_TRUE(contains(r.out, "removed 1 temporary file")) << r;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r;
  EXPECT_FALSE(fs::exists(h / ".series.csv.tmpAb12Cd"));
  EXPECT_TRUE(fs::exists(h / "notes.tmp"));
  EXPECT_FALSE(fs::exists(h / "run.lock"));
  EXPECT_TRUE(contains(read_text(h / "run.log"), "took over the stale lock of pid " + dead_pid));
  expect_same_run(b, h, 4);
}

TEST(RunSafety, DamagedOrTruncatedCheckpointIsRefusedNamingIt) {
  TempDir dir;
  const fs::path b = dir / "b";
  ASSERT_EQ(dir.run(with(tiny_dam_break(b, 0.02, 0.005), {"--halt-after-output", "1"})).status,
            kExitHalted);
  const fs::path ck = b / "checkpoint.bin";
  const std::string good = read_text(ck);
  const std::string series = read_text(b / "series.csv");
  // One bit flipped in the middle of the densities.
  const std::string record = "level0.rho";
  const std::size_t at = good.find(record);
  ASSERT_NE(at, std::string::npos);
  std::string damaged = good;
  damaged[at + record.size() + 1 + 8 + 8 * 500 + 3] ^= 0x04;
  const std::vector<std::pair<std::string, std::string>> variants = {
      {"damaged", damaged}, {"truncated", good.substr(0, good.size() * 3 / 5)}};
  for (const auto& [what, bytes] : variants) {
    write_text(ck, bytes);
    const CmdResult r = dir.run(resume(b));
    EXPECT_EQ(r.status, 1) << what << "\n" << r;
    const auto lines = r.err_lines();
    ASSERT_EQ(lines.size(), 1u) << what << "\n" << r;
    EXPECT_TRUE(contains(lines[0], ck.string())) << r;
    const std::string reason =
        what == "damaged" ? "record 'level0.rho' fails its checksum" : "truncated";
    EXPECT_TRUE(contains(lines[0], reason)) << r;
    EXPECT_EQ(read_text(b / "series.csv"), series) << what;
    EXPECT_FALSE(fs::exists(b / snapshot(2, "csv"))) << what;
    EXPECT_FALSE(fs::exists(b / "run.lock")) << what;
  }
  write_text(ck, good);
  const CmdResult ok = dir.run(resume(b));
  EXPECT_EQ(ok.status, 0) << ok;
}

TEST(RunSafety, ResumeWithAChangedPhysicalKeyIsRefusedNamingTheKey) {
  TempDir dir;
  const fs::path b = dir / "b";
  ASSERT_EQ(dir.run(with(tiny_dam_break(b, 0.02, 0.005), {"--halt-after-output", "1"})).status,
            kExitHalted);
  const std::string ck = (b / "checkpoint.bin").string();
  // By --set.
  const CmdResult set = dir.run(resume(b, {"--set", "resolution.dp=0.05"}));
  EXPECT_EQ(set.status, 1) << set;
  ASSERT_EQ(set.err_lines().size(), 1u) << set;
  EXPECT_TRUE(contains(set.err, ck)) << set;
  EXPECT_TRUE(contains(set.err, "resolution.dp = 0.05 (checkpoint: 0.04)")) << set;
  // By editing the folder's case.toml.
  const std::string case_toml = read_text(b / "case.toml");
  write_text(b / "case.toml", vrsph_cli_cases::replace_once(case_toml, "cfl = 0.2", "cfl = 0.25"));
  const CmdResult edit = dir.run(resume(b));
  EXPECT_EQ(edit.status, 1) << edit;
  EXPECT_TRUE(contains(edit.err, "numerics.cfl = 0.25 (checkpoint: 0.2)")) << edit;
  EXPECT_FALSE(contains(edit.err, "end_time = ")) << edit;  // not a change of the case
  write_text(b / "case.toml", case_toml);
  // The end time may change, and a physical key set to the value it has is no change.
  const CmdResult later =
      dir.run(resume(b, {"--set", "case.end_time=0.025", "--set", "resolution.dp=0.04"}));
  EXPECT_EQ(later.status, 0) << later;
  EXPECT_TRUE(fs::exists(b / snapshot(5, "csv")));
}

TEST(RunSafety, SigtermWritesACheckpointThatResumesToTheSameBytes) {
  TempDir dir;
  const fs::path b = dir / "b", c = dir / "c";
  Spawned run(dir.path(), tiny_dam_break(b, 0.05, 0.0125), "run");
  ASSERT_TRUE(wait_for_file(b / "checkpoint.bin", run)) << run.err();
  run.signal(SIGTERM);
  ASSERT_EQ(run.wait(), 128 + SIGTERM) << run.out() << run.err();
  EXPECT_TRUE(contains(run.err(), "stopped by SIGTERM")) << run.err();
  EXPECT_TRUE(contains(run.err(), "--resume " + b.string())) << run.err();
  const auto sj = nlohmann::json::parse(read_text(b / "summary.json"));
  EXPECT_EQ(sj.at("completed"), false);
  EXPECT_EQ(sj.at("stopped_by"), "SIGTERM");
  EXPECT_LT(sj.at("sim_time").get<double>(), 0.05);
  EXPECT_TRUE(contains(read_text(b / "run.log"), "stopped by SIGTERM"));
  EXPECT_FALSE(fs::exists(b / "run.lock"));

  const CmdResult r = dir.run(resume(b));
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_TRUE(r.out.empty()) << r;  // a lock released at the stop: nothing to take over
  ASSERT_EQ(dir.run(tiny_dam_break(c, 0.05, 0.0125)).status, 0);
  expect_same_run(c, b, 4);
  EXPECT_EQ(nlohmann::json::parse(read_text(b / "summary.json")).at("completed"), true);
}

TEST(RunSafety, SigintStopsWithItsOwnStatus) {
  TempDir dir;
  const fs::path b = dir / "b";
  Spawned run(dir.path(), tiny_dam_break(b, 0.05, 0.0125), "run");
  ASSERT_TRUE(wait_for_file(b / "checkpoint.bin", run)) << run.err();
  run.signal(SIGINT);
  ASSERT_EQ(run.wait(), 128 + SIGINT) << run.out() << run.err();
  EXPECT_TRUE(contains(run.err(), "stopped by SIGINT")) << run.err();
  const auto sj = nlohmann::json::parse(read_text(b / "summary.json"));
  EXPECT_EQ(sj.at("completed"), false);
  EXPECT_EQ(sj.at("stopped_by"), "SIGINT");
}

TEST(RunSafety, BatchRunPrintsALinePerOutputTimeAndRunLogKeepsThem) {
  TempDir dir;
  const fs::path b = dir / "b";
  std::vector<std::string> args = tiny_dam_break(b, 0.02, 0.005);
  args.erase(std::find(args.begin(), args.end(), "--quiet"));
  const CmdResult r = dir.run(args);  // stdout is a file: no terminal
  ASSERT_EQ(r.status, 0) << r;
  std::vector<std::string> lines;
  std::istringstream out(r.out);
  for (std::string l; std::getline(out, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 1u + 5u + 1u) << r;  // start, t = 0, 5, ..., 20 ms, end
  EXPECT_TRUE(contains(lines.front(), "1250 fluid")) << r;
  EXPECT_TRUE(contains(lines.back(), "done")) << r;
  for (std::size_t k = 1; k <= 5; ++k) {
    for (const char* field : {"t = ", " step ", " dt = ", " 1937 particles", " wall ", " ETA "})
      EXPECT_TRUE(contains(lines[k], field)) << field << " in " << lines[k];
  }
  EXPECT_TRUE(contains(lines[5], "t = 0.02000 / 0.02000 s  step 173")) << lines[5];
  EXPECT_FALSE(contains(r.out, "\r"));
  // run.log: the same lines, timestamped, after the program's version and commit.
  const std::string log = read_text(b / "run.log");
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const std::string text = lines[k].substr(lines[k].find_first_not_of(' '));
    EXPECT_TRUE(contains(log, "] " + text.substr(text.rfind("vrsph: ", 0) == 0 ? 7 : 0)))
        << lines[k] << "\n"
        << log;
  }
  EXPECT_TRUE(contains(log, "(commit ")) << log;
  // summary.json names the program and its commit.
  const auto sj = nlohmann::json::parse(read_text(b / "summary.json"));
  EXPECT_FALSE(sj.at("version").get<std::string>().empty());
  const std::string commit = sj.at("git_commit");
  EXPECT_TRUE(
      commit == "unknown" ||
      (commit.size() == 40 && commit.find_first_not_of("0123456789abcdef") == std::string::npos))
      << commit;
  // A resume appends to run.log.
  ASSERT_EQ(dir.run(resume(b, {"--set", "case.end_time=0.025"})).status, 0);
  const std::string more = read_text(b / "run.log");
  EXPECT_EQ(more.rfind(log, 0), 0u) << more;
  EXPECT_TRUE(contains(more.substr(log.size()), "resumed at t = 0.02 s")) << more;
  EXPECT_TRUE(contains(more.substr(log.size()), "t = 0.02500 / 0.02500 s")) << more;
}

}  // namespace
