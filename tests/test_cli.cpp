// The `vrsph` command as a user meets it (README "Using it", docs/outputs.md):
// usage errors, the output folder, `check`, an unstable run, thread independence (bad input:
// test_cli_bad_input.cpp; the files of a run: test_cli_run.cpp). Every test runs
// the real binary on tiny cases (a few hundred to two thousand particles, a few ms simulated).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli_cases.hpp"
#include "cli_util.hpp"

namespace {

using namespace vrsph_cli;
using namespace vrsph_cli_cases;

TEST(CliCommandLine, UsageErrorsExitWithStatus1) {
  TempDir dir;
  dir.write("tiny.toml", kTiny);
  for (const std::vector<std::string>& args : {std::vector<std::string>{},
                                               {"run"},
                                               {"frobnicate"},
                                               {"run", "tiny.toml", "--bogus"},
                                               {"run", "tiny.toml", "--threads", "0"},
                                               {"check"}}) {
    const CmdResult r = dir.run(args);
    EXPECT_EQ(r.status, 1) << r;
    EXPECT_EQ(r.err_lines().size(), 1u) << r;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  // An unknown launch policy in the environment: one line naming the variable and the value.
  const CmdResult r = dir.run({"check", "tiny.toml"}, "VRSPH_LAUNCH=sometimes ");
  EXPECT_EQ(r.status, 1) << r;
  ASSERT_EQ(r.err_lines().size(), 1u) << r;
  EXPECT_NE(r.err_lines()[0].find("VRSPH_LAUNCH = 'sometimes'"), std::string::npos) << r;
}

// ---------------------------------------------------------------------------------------------
// Output folder: an earlier run is kept unless --force.

TEST(CliOutputFolder, ExistingRunIsRefusedWithoutForce) {
  TempDir dir;
  const fs::path out = dir / "run";
  // First run: snapshots at 0, 2.5, 5 ms (3 of them).
  const CmdResult first = dir.run(tiny_dam_break(out, 0.005, 0.0025));
  ASSERT_EQ(first.status, 0) << first;
  ASSERT_TRUE(fs::exists(out / snapshot(2, "csv")));
  const std::string series_before = read_text(out / "series.csv");
  const std::string summary_before = read_text(out / "summary.json");

  // Same folder again, no --force: refused, nothing touched.
  const CmdResult again = dir.run(tiny_dam_break(out, 0.0025, 0.0025));
  EXPECT_NE(again.status, 0) << again;
  EXPECT_EQ(again.status, 1) << again;
  const auto lines = again.err_lines();
  ASSERT_EQ(lines.size(), 1u) << again;
  EXPECT_NE(lines[0].find(out.string()), std::string::npos) << again;
  EXPECT_NE(lines[0].find("--force"), std::string::npos) << again;
  EXPECT_EQ(read_text(out / "series.csv"), series_before);
  EXPECT_EQ(read_text(out / "summary.json"), summary_before);

  // With --force: runs, and no stale snapshot of the earlier (longer) run survives.
  std::vector<std::string> forced = tiny_dam_break(out, 0.0025, 0.0025);
  forced.push_back("--force");
  const CmdResult f = dir.run(forced);
  ASSERT_EQ(f.status, 0) << f;
  EXPECT_TRUE(fs::exists(out / snapshot(1, "csv")));
  EXPECT_FALSE(fs::exists(out / snapshot(2, "csv"))) << "stale snapshot of the earlier run";
  EXPECT_FALSE(fs::exists(out / snapshot(2, "vtp"))) << "stale snapshot of the earlier run";
  EXPECT_EQ(read_lines(out / "series.csv").size(), 3u);  // header + t = 0 + t = 2.5 ms
  EXPECT_EQ(read_pvd(out / "particles.pvd").size(), 2u);
}

TEST(CliOutputFolder, ForceKeepsFilesThatAreNotARunsOwn) {
  TempDir dir;
  const fs::path out = dir / "run";
  ASSERT_EQ(dir.run(tiny_dam_break(out, 0.0025, 0.0025)).status, 0);
  write_text(out / "notes.txt", "mine");
  std::vector<std::string> forced = tiny_dam_break(out, 0.0025, 0.0025);
  forced.push_back("--force");
  const CmdResult f = dir.run(forced);
  ASSERT_EQ(f.status, 0) << f;
  EXPECT_EQ(read_text(out / "notes.txt"), "mine");
}

TEST(CliOutputFolder, DefaultIsOutSlashCaseName) {
  TempDir dir;
  dir.write("tiny.toml", kTiny);
  const CmdResult r = dir.run({"run", "tiny.toml", "--quiet", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_TRUE(fs::exists(dir / "out/tiny/summary.json")) << r;
  EXPECT_TRUE(fs::exists(dir / "out/tiny/case.toml")) << r;
  // A second run there is refused, not silently overwritten.
  const CmdResult again = dir.run({"run", "tiny.toml", "--quiet", "--threads", "1"});
  EXPECT_EQ(again.status, 1) << again;
  EXPECT_EQ(again.err_lines().size(), 1u) << again;
}

// ---------------------------------------------------------------------------------------------
// vrsph check

TEST(CliCheck, ReportsParticleCountsOfTheBenchmarkCase) {
  TempDir dir;
  const CmdResult r = dir.run({"check", bench_case()});
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_NE(r.out.find("80000 fluid"), std::string::npos) << r;
  EXPECT_NE(r.out.find("5415 wall"), std::string::npos) << r;
  EXPECT_TRUE(r.err.empty()) << r;
  EXPECT_FALSE(fs::exists(dir / "out")) << "check must not write outputs";
}

TEST(CliCheck, AppliesOverrides) {
  TempDir dir;
  const CmdResult r = dir.run({"check", dam_break_2d(), "--set", "resolution.dp=0.04"});
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_NE(r.out.find("1250 fluid"), std::string::npos) << r;
  EXPECT_NE(r.out.find("687 wall"), std::string::npos) << r;
  // The value of --set is a TOML value: 4e-2 is the same number.
  const CmdResult e = dir.run({"check", dam_break_2d(), "--set", "resolution.dp=4e-2"});
  ASSERT_EQ(e.status, 0) << e;
  EXPECT_NE(e.out.find("1250 fluid"), std::string::npos) << e;
  // A bare word is a string (and a valid enum value here).
  const CmdResult w = dir.run({"check", dam_break_2d(), "--set", "resolution.dp=0.04", "--set",
                               "numerics.viscosity.model=laminar"});
  EXPECT_EQ(w.status, 0) << w;
  // A key of an inline table that the file does not have is created.
  const CmdResult s = dir.run({"check", dam_break_2d(), "--set", "resolution.dp=0.04", "--set",
                               "numerics.shifting.coefficient=0.05"});
  EXPECT_EQ(s.status, 0) << s;
}

// Every level's fluid, buffer and wall particles, and totals that are their sums.
TEST(CliCheck, ListsTheParticlesOfEveryLevel) {
  TempDir dir;
  const CmdResult r = dir.run({"check", (kCases / "droplet_vr_2d.toml").string()});
  ASSERT_EQ(r.status, 0) << r;
  const std::regex total(
      R"(particles: (\d+) fluid, (\d+) buffer, (\d+) wall \((\d+) in all, 2 levels\))");
  const std::regex level(
      R"(level (\d) \([^)]*\): dp = [^,]+, h = [^,]+, (\d+) fluid, (\d+) buffer, (\d+) wall)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, total)) << r;
  const long fluid = std::stol(m[1]), buffer = std::stol(m[2]), wall = std::stol(m[3]);
  EXPECT_EQ(fluid + buffer + wall, std::stol(m[4]));
  long sums[3] = {0, 0, 0};
  int levels = 0;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), level);
       it != std::sregex_iterator(); ++it, ++levels) {
    EXPECT_EQ(std::stoi((*it)[1]), levels) << r;
    EXPECT_GT(std::stol((*it)[2]), 0) << "level " << levels << " has fluid\n" << r;
    EXPECT_GT(std::stol((*it)[3]), 0) << "level " << levels << " has buffer particles\n" << r;
    for (int k = 0; k < 3; ++k) sums[k] += std::stol((*it)[k + 2]);
  }
  EXPECT_EQ(levels, 2) << r;
  EXPECT_EQ(sums[0], fluid);
  EXPECT_EQ(sums[1], buffer);
  EXPECT_EQ(sums[2], wall);
  EXPECT_NE(r.out.find("level 0 (base level)"), std::string::npos) << r;
}

TEST(CliCheck, ShippedCasesAreValid) {
  TempDir dir;
  for (const char* name : {"dam_break_2d.toml", "dam_break_3d.toml", "hydrostatic_2d.toml",
                           "bench_dam_break_2d.toml", "dam_break_impact_vr_2d.toml"}) {
    const CmdResult r = dir.run({"check", (kCases / name).string()});
    EXPECT_EQ(r.status, 0) << r;
    EXPECT_NE(r.out.find(" fluid"), std::string::npos) << r;
  }
}

// ---------------------------------------------------------------------------------------------
// An unstable run stops with status 2, says where and why, and keeps what it wrote.

void expect_unstable(const CmdResult& r, const fs::path& out, const std::string& check) {
  EXPECT_EQ(r.status, 2) << r;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r;
  const std::string& l = lines[0];
  for (const std::string& s : {std::string("t = "), std::string("step"), std::string("particle"),
                               std::string("id "), "check: " + check}) {
    EXPECT_NE(l.find(s), std::string::npos) << "diagnosis lacks '" << s << "'\n" << r;
  }
  const auto sj = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(sj.at("completed"), false);
  EXPECT_TRUE(sj.contains("steps"));
  EXPECT_TRUE(fs::exists(out / "case.toml"));
  EXPECT_TRUE(fs::exists(out / snapshot(0, "vtp")));
  const auto series = read_lines(out / "series.csv");
  ASSERT_GE(series.size(), 2u);
  EXPECT_EQ(split_csv(series[1])[0], "0");
}

TEST(CliUnstable, TinySoundSpeedFailsTheDensityCheck) {
  TempDir dir;
  const fs::path out = dir / "run";
  std::vector<std::string> args = tiny_dam_break(out, 0.5, 0.05);
  for (const char* s : {"eos.sound_speed=0.5", "numerics.density_diffusion.model=molteni"}) {
    args.push_back("--set");
    args.push_back(s);
  }
  const CmdResult r = dir.run(args);
  expect_unstable(r, out, "density");
  EXPECT_TRUE(fs::exists(out / snapshot(0, "csv")));
}

// The tiny case to 0.5 s with its fluid started at `velocity`, at sound speed c0.
CmdResult run_moving_tiny(TempDir& dir, const fs::path& out, const std::string& velocity,
                          const std::string& c0) {
  dir.write("tiny.toml", kTiny);
  return dir.run({"run", "tiny.toml", "--out", out.string(), "--quiet", "--threads", "1", "--set",
                  "fluid_block.0.velocity=" + velocity, "--set", "eos.sound_speed=" + c0, "--set",
                  "case.end_time=0.5"});
}

// Fluid at four times the sound speed: the next dt falls below 0.05 h / c0 after the first step.
// The diagnosis names the fastest fluid particle (the accelerations are gone after the step's last
// sort, so a particle named by its acceleration would be a stranger).
TEST(CliUnstable, FluidFasterThanSoundFailsTheDtCheck) {
  TempDir dir;
  const fs::path out = dir / "run";
  const CmdResult r = run_moving_tiny(dir, out, "[8, 0]", "2");
  expect_unstable(r, out, "dt");
  const std::string l = r.err_lines().empty() ? "" : r.err_lines()[0];
  const std::smatch m = [&] {
    std::smatch s;
    std::regex_search(l, s, std::regex(R"(fastest fluid particle id \d+ .* speed ([0-9.]+) m/s)"));
    return s;
  }();
  ASSERT_EQ(m.size(), 2u) << l;
  EXPECT_NEAR(std::stod(m[1].str()), 8.0, 0.1) << l;  // the fluid's speed after one short step
}

TEST(CliUnstable, FluidLeavingTheDomainFailsTheDomainCheck) {
  TempDir dir;
  const fs::path out = dir / "run";
  expect_unstable(run_moving_tiny(dir, out, "[0, 30]", "300"), out, "domain");
}

// ---------------------------------------------------------------------------------------------
// Thread independence: byte-identical outputs with 1 and 2 threads.

TEST(CliThreads, OneAndTwoThreadsGiveIdenticalFiles) {
  TempDir dir;
  const fs::path a = dir / "t1", b = dir / "t2";
  const CmdResult ra = dir.run(tiny_dam_break(a, 0.01, 0.005, 1));
  ASSERT_EQ(ra.status, 0) << ra;
  const CmdResult rb = dir.run(tiny_dam_break(b, 0.01, 0.005, 2));
  ASSERT_EQ(rb.status, 0) << rb;
  for (int k = 0; k <= 2; ++k) {
    EXPECT_TRUE(same_bytes(a / snapshot(k, "csv"), b / snapshot(k, "csv"))) << k;
  }
  EXPECT_TRUE(same_bytes(a / "series.csv", b / "series.csv"));
  EXPECT_EQ(nlohmann::json::parse(read_text(b / "summary.json")).at("threads").get<int>(), 2);
}

// The same with two resolution levels (droplet_vr_2d at dp 2e-4 / 1e-4, 3 ms): buffer
// interpolation, mass points and kind changes do not depend on the thread count either.
TEST(CliThreads, VariableResolutionIndependentOfThreadCount) {
  TempDir dir;
  auto args = [&](const fs::path& out, int threads) {
    return std::vector<std::string>{"run",
                                    (kCases / "droplet_vr_2d.toml").string(),
                                    "--out",
                                    out.string(),
                                    "--quiet",
                                    "--threads",
                                    std::to_string(threads),
                                    "--set",
                                    "resolution.dp=2e-4",
                                    "--set",
                                    "case.end_time=0.003",
                                    "--set",
                                    "output.interval=0.0015"};
  };
  const fs::path a = dir / "t1", b = dir / "t2";
  ASSERT_EQ(dir.run(args(a, 1)).status, 0);
  ASSERT_EQ(dir.run(args(b, 2)).status, 0);
  // Two threads with every short loop on the team, and with every one on the calling thread
  // (exec/launch_tuner.hpp): the tuner's choices move no bit either.
  const fs::path team = dir / "team", alone = dir / "alone";
  ASSERT_EQ(dir.run(args(team, 2), "VRSPH_LAUNCH=team ").status, 0);
  ASSERT_EQ(dir.run(args(alone, 2), "VRSPH_LAUNCH=alone ").status, 0);
  for (const fs::path& other : {b, team, alone}) {
    for (int k = 0; k <= 2; ++k) {
      EXPECT_TRUE(same_bytes(a / snapshot(k, "csv"), other / snapshot(k, "csv"))) << k;
    }
    EXPECT_TRUE(same_bytes(a / "series.csv", other / "series.csv")) << other;
    EXPECT_TRUE(same_bytes(a / "refinement_boxes.vtp", other / "refinement_boxes.vtp"));
  }
}

}  // namespace

namespace {

// `vrsph bench`: its figures, and the candidate-block width changes the speed, not the pairs.
TEST(CliBench, ReportsPairsAndMemoryPerParticle) {
  TempDir dir;
  dir.write("tiny.toml", kTiny);
  std::map<int, nlohmann::json> figures;
  for (int width : {1, 2}) {
    const std::string json = "bench" + std::to_string(width) + ".json";
    const CmdResult r = dir.run({"bench", "tiny.toml", "--time", "0.002", "--threads", "1",
                                 "--cells-per-block", std::to_string(width), "--json", json});
    ASSERT_EQ(r.status, 0) << r;
    EXPECT_NE(r.out.find("bytes per particle"), std::string::npos) << r;
    figures[width] = nlohmann::json::parse(read_text(dir / json));
    EXPECT_EQ(figures[width]["cells_per_block"].get<int>(), width);
    EXPECT_GT(figures[width]["particle_steps_per_second"].get<double>(), 0.0);
    const double bytes = figures[width]["bytes_per_particle"].get<double>();
    EXPECT_GT(bytes, 50.0);  // the particle arrays alone hold more
    EXPECT_LT(bytes, 1e5);
  }
  EXPECT_GT(figures[2]["pairs_per_particle_step"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(figures[1]["pairs_per_particle_step"].get<double>(),
                   figures[2]["pairs_per_particle_step"].get<double>());
}

}  // namespace
