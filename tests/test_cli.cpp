// The `vrsph` command as a user meets it (shared/CONTRACT.md "Command line", "Output folder"):
// bad input, `check`, the files of a run, an unstable run, thread independence. Every test runs
// the real binary on tiny cases (a few hundred to two thousand particles, a few ms simulated).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_util.hpp"

namespace {

using namespace vrsph_cli;

// A small valid case: 100 fluid particles in a 1 m tank (340 particles in all).
const std::string kTiny = R"([case]
name = "tiny"
dimension = 2
end_time = 0.005

[fluid]
gravity = [0.0, -9.81]

[resolution]
dp = 0.04
h_over_dp = 1.3

[numerics]
viscosity = { model = "artificial", alpha = 0.01 }

[[fluid_block]]
shape = "box"
min = [0.04, 0.04]
max = [0.4, 0.4]

[[wall_block]]
shape = "tank"
min = [0.0, 0.0]
max = [1.0, 1.0]
layers = 3
)";

// A circle of fluid, for radius checks.
const std::string kCircle = R"([case]
name = "circle"
dimension = 2
end_time = 0.001

[eos]
max_speed = 1.0

[resolution]
dp = 0.01

[[fluid_block]]
shape = "circle"
center = [0.0, 0.0]
radius = 0.005
)";

std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "test set-up: '" << from << "' not in the case text";
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

// 1-based number of the line of `text` that contains `needle`.
int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

// ---------------------------------------------------------------------------------------------
// Bad input: exit status 1 and exactly one line on stderr naming the key, the value, the reason.

struct BadInput {
  std::string name;
  std::string case_text;            // written to bad.toml; empty: no file written
  std::string case_arg;             // the case path given on the command line (default bad.toml)
  std::vector<std::string> args;    // extra arguments (--set ...)
  std::vector<std::string> expect;  // substrings of the one stderr line
};

std::ostream& operator<<(std::ostream& os, const BadInput& b) { return os << b.name; }

std::vector<BadInput> bad_inputs() {
  std::vector<BadInput> v;
  {
    const std::string text = replace_once(kTiny, "h_over_dp = 1.3", "h_over_dp = 1.3\nfoo = 3");
    v.push_back({"unknown_key_in_file",
                 text,
                 "",
                 {},
                 {"bad.toml:" + std::to_string(line_of(text, "foo = 3")), "resolution.foo", "3",
                  "unknown key"}});
  }
  v.push_back({"unknown_table_in_file",
               kTiny + "\n[solver]\nfoo = 1\n",
               "",
               {},
               {"bad.toml", "solver", "unknown key"}});
  v.push_back({"wrong_type_dp_string",
               replace_once(kTiny, "dp = 0.04", "dp = \"abc\""),
               "",
               {},
               {"resolution.dp", "abc", "must be a number"}});
  v.push_back({"wrong_type_gravity_scalar",
               replace_once(kTiny, "gravity = [0.0, -9.81]", "gravity = 9.81"),
               "",
               {},
               {"fluid.gravity", "9.81"}});
  v.push_back({"dp_zero",
               replace_once(kTiny, "dp = 0.04", "dp = 0.0"),
               "",
               {},
               {"resolution.dp", "0", "> 0"}});
  v.push_back({"dp_negative",
               replace_once(kTiny, "dp = 0.04", "dp = -0.01"),
               "",
               {},
               {"resolution.dp", "-0.01", "> 0"}});
  v.push_back(
      {"radius_below_dp", kCircle, "", {}, {"fluid_block.0.radius", "0.005", "resolution.dp"}});
  v.push_back(
      {"missing_dp", replace_once(kTiny, "dp = 0.04\n", ""), "", {}, {"resolution.dp", "missing"}});
  v.push_back({"missing_end_time",
               replace_once(kTiny, "end_time = 0.005\n", ""),
               "",
               {},
               {"case.end_time", "missing"}});
  v.push_back({"unknown_viscosity_model",
               replace_once(kTiny, "model = \"artificial\"", "model = \"foo\""),
               "",
               {},
               {"numerics.viscosity.model", "foo", "must be one of", "artificial", "laminar"}});
  {
    const std::string text = replace_once(kTiny, "alpha = 0.01", "alfa = 0.01");
    v.push_back({"unknown_key_in_inline_table",
                 text,
                 "",
                 {},
                 {"bad.toml:" + std::to_string(line_of(text, "alfa")), "numerics.viscosity.alfa",
                  "0.01", "unknown key"}});
  }
  v.push_back(
      {"missing_fluid_block",
       replace_once(kTiny,
                    "[[fluid_block]]\nshape = \"box\"\nmin = [0.04, 0.04]\nmax = [0.4, 0.4]\n", ""),
       "",
       {},
       {"fluid_block", "required"}});
  v.push_back({"set_unknown_key",
               kTiny,
               "",
               {"--set", "resolution.foo=1"},
               {"--set", "resolution.foo", "unknown key"}});
  v.push_back({"set_unknown_section",
               kTiny,
               "",
               {"--set", "solver.cfl=0.1"},
               {"--set", "solver", "unknown key"}});
  v.push_back({"set_bad_value_word",
               kTiny,
               "",
               {"--set", "resolution.dp=abc"},
               {"--set", "resolution.dp", "abc", "must be a number"}});
  v.push_back({"set_bad_value_negative",
               kTiny,
               "",
               {"--set", "resolution.dp=-1"},
               {"--set", "resolution.dp", "-1", "> 0"}});
  v.push_back({"set_unknown_enum",
               kTiny,
               "",
               {"--set", "numerics.viscosity.model=foo"},
               {"--set", "numerics.viscosity.model", "foo", "must be one of"}});
  v.push_back({"set_radius_below_dp",
               kCircle,
               "",
               {"--set", "fluid_block.0.radius=0.02", "--set", "resolution.dp=0.05"},
               {"fluid_block.0.radius", "0.02", "resolution.dp"}});
  v.push_back({"set_index_out_of_range",
               kTiny,
               "",
               {"--set", "fluid_block.3.min=[0, 0]"},
               {"fluid_block.3", "out of range"}});
  v.push_back(
      {"set_without_value", kTiny, "", {"--set", "resolution.dp"}, {"resolution.dp", "KEY=VALUE"}});
  v.push_back({"nonexistent_case_file",
               "",
               "no_such_case.toml",
               {},
               {"no_such_case.toml", "no such file"}});
  v.push_back(
      {"toml_syntax_error", "[case\nname = \"x\"\n", "", {}, {"bad.toml:1", "syntax error"}});
  return v;
}

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

void expect_bad_input(const CmdResult& r, const BadInput& b) {
  EXPECT_EQ(r.status, 1) << r;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r;
  EXPECT_EQ(r.err.back(), '\n') << r;
  for (const std::string& s : b.expect) {
    EXPECT_NE(lines[0].find(s), std::string::npos) << "stderr line lacks '" << s << "'\n" << r;
  }
}

TEST_P(CliBadInput, CheckAndRunRefuseWithOneLine) {
  const BadInput& b = GetParam();
  TempDir dir;
  if (!b.case_text.empty()) dir.write("bad.toml", b.case_text);
  const std::string case_arg = b.case_arg.empty() ? "bad.toml" : b.case_arg;

  std::vector<std::string> check{"check", case_arg};
  check.insert(check.end(), b.args.begin(), b.args.end());
  expect_bad_input(dir.run(check), b);

  std::vector<std::string> run{"run", case_arg, "--out", "out_run", "--quiet", "--threads", "1"};
  run.insert(run.end(), b.args.begin(), b.args.end());
  expect_bad_input(dir.run(run), b);
  EXPECT_FALSE(fs::exists(dir / "out_run")) << "bad input must not create the output folder";
  EXPECT_FALSE(fs::exists(dir / "out")) << "bad input must not create out/";
}

INSTANTIATE_TEST_SUITE_P(Cli, CliBadInput, ::testing::ValuesIn(bad_inputs()),
                         [](const auto& info) { return info.param.name; });

TEST(CliBadInputSanity, TheBaseCasesAreValid) {
  TempDir dir;
  dir.write("tiny.toml", kTiny);
  dir.write("circle.toml", replace_once(kCircle, "radius = 0.005", "radius = 0.05"));
  const CmdResult a = dir.run({"check", "tiny.toml"});
  EXPECT_EQ(a.status, 0) << a;
  EXPECT_NE(a.out.find("100 fluid"), std::string::npos) << a;
  EXPECT_NE(a.out.find("240 wall"), std::string::npos) << a;
  const CmdResult b = dir.run({"check", "circle.toml"});
  EXPECT_EQ(b.status, 0) << b;
}

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

TEST(CliCheck, ShippedCasesAreValid) {
  TempDir dir;
  for (const char* name : {"dam_break_2d.toml", "dam_break_3d.toml", "hydrostatic_2d.toml",
                           "bench_dam_break_2d.toml"}) {
    const CmdResult r = dir.run({"check", (kCases / name).string()});
    EXPECT_EQ(r.status, 0) << r;
    EXPECT_NE(r.out.find(" fluid"), std::string::npos) << r;
  }
}

// ---------------------------------------------------------------------------------------------
// A tiny run writes every file of the contract.

double num(const std::string& s) { return std::stod(s); }

TEST(CliRun, WritesEveryContractFile) {
  TempDir dir;
  // The dam break with a pressure line along the bottom of the column.
  dir.write("case.toml", read_text(dam_break_2d()) + R"(
[[output.line]]
name = "bottom"
from = [0.0, 0.05]
to = [1.0, 0.05]
)");
  const fs::path out = dir / "run";
  const double dp = 0.04, end = 0.01;
  const CmdResult r = dir.run({"run", "case.toml", "--out", out.string(), "--quiet", "--threads",
                               "1", "--set", "resolution.dp=0.04", "--set", "case.end_time=0.01",
                               "--set", "output.interval=0.005"});
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_TRUE(r.err.empty()) << r;

  // case.toml: every default filled in, the overrides applied, and re-loadable.
  const std::string resolved = read_text(out / "case.toml");
  for (const char* key :
       {"h_over_dp", "cfl", "gamma", "sound_speed_factor", "surface_tension", "kinematic_viscosity",
        "density_diffusion", "shifting", "interval", "formats", "[[output.line]]", "\"bottom\""}) {
    EXPECT_NE(resolved.find(key), std::string::npos) << "case.toml lacks " << key << "\n"
                                                     << resolved;
  }
  EXPECT_NE(resolved.find("dp = 0.04"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("end_time = 0.01"), std::string::npos) << resolved;
  const CmdResult chk = dir.run({"check", (out / "case.toml").string()});
  EXPECT_EQ(chk.status, 0) << chk;
  EXPECT_NE(chk.out.find("1250 fluid"), std::string::npos) << chk;
  EXPECT_NE(chk.out.find("687 wall"), std::string::npos) << chk;

  // Snapshots 0, 1, 2 (t = 0, 5 ms, 10 ms) as vtp and csv; no more.
  for (int k = 0; k <= 2; ++k) {
    EXPECT_TRUE(fs::exists(out / snapshot(k, "vtp"))) << k;
    EXPECT_TRUE(fs::exists(out / snapshot(k, "csv"))) << k;
  }
  EXPECT_FALSE(fs::exists(out / snapshot(3, "vtp")));
  EXPECT_FALSE(fs::exists(out / snapshot(3, "csv")));
  const std::string vtp = read_text(out / snapshot(2, "vtp"));
  EXPECT_EQ(vtp.rfind("<?xml", 0), 0u);
  EXPECT_NE(vtp.find("PolyData"), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfPoints=\"1937\""), std::string::npos);

  // particles.pvd: every snapshot once, increasing times, from 0 to the end time.
  const auto pvd = read_pvd(out / "particles.pvd");
  ASSERT_EQ(pvd.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(pvd[k].file, snapshot(k, "vtp"));
  EXPECT_EQ(pvd.front().time, 0.0);
  EXPECT_NEAR(pvd.back().time, end, 1e-12);
  for (std::size_t k = 1; k < pvd.size(); ++k) EXPECT_GT(pvd[k].time, pvd[k - 1].time);

  // series.csv: the contract header, one row per output time.
  const auto series = read_lines(out / "series.csv");
  ASSERT_EQ(series.size(), 4u);
  EXPECT_EQ(series[0].rfind("t,step,dt,n_fluid,n_buffer,mass_fluid,kinetic_energy,max_speed", 0),
            0u)
      << series[0];
  long last_step = -1;
  for (std::size_t k = 1; k < series.size(); ++k) {
    const auto c = split_csv(series[k]);
    ASSERT_GE(c.size(), 8u) << series[k];
    EXPECT_NEAR(num(c[0]), pvd[k - 1].time, 1e-12) << series[k];
    EXPECT_GT(std::stol(c[1]), last_step);
    last_step = std::stol(c[1]);
    EXPECT_EQ(c[3], "1250");
    EXPECT_EQ(c[4], "0");
    EXPECT_NEAR(num(c[5]), 1250 * 1000.0 * dp * dp, 1e-6);
    EXPECT_GE(num(c[6]), 0.0);
    EXPECT_GE(num(c[7]), 0.0);
  }
  EXPECT_EQ(num(split_csv(series[1])[0]), 0.0);
  EXPECT_EQ(split_csv(series[1])[1], "0");
  EXPECT_NEAR(num(split_csv(series.back())[0]), end, 1e-12);
  EXPECT_GT(num(split_csv(series.back())[6]), 0.0) << "the column has started to move";

  // summary.json.
  const auto sj = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(sj.at("completed"), true);
  for (const char* key : {"steps", "sim_time", "wall_seconds", "particle_steps_per_second",
                          "pair_interactions_per_second", "threads", "n_particles"}) {
    EXPECT_TRUE(sj.contains(key)) << key << "\n" << sj.dump(2);
  }
  EXPECT_EQ(sj.at("steps").get<long>(), last_step);
  EXPECT_NEAR(sj.at("sim_time").get<double>(), end, 1e-12);
  EXPECT_EQ(sj.at("threads").get<int>(), 1);
  EXPECT_GT(sj.at("wall_seconds").get<double>(), 0.0);
  EXPECT_GT(sj.at("particle_steps_per_second").get<double>(), 0.0);
  EXPECT_GT(sj.at("pair_interactions_per_second").get<double>(), 0.0);
  EXPECT_EQ(sj.at("n_particles").at("fluid").get<long>(), 1250);
  EXPECT_EQ(sj.at("n_particles").at("wall").get<long>(), 687);
  EXPECT_EQ(sj.at("n_particles").at("buffer").get<long>(), 0);

  // Particle CSV: header, one row per particle, kinds.
  for (int k : {0, 2}) {
    const auto rows = read_lines(out / snapshot(k, "csv"));
    ASSERT_EQ(rows.size(), 1u + 1937u) << k;
    EXPECT_EQ(rows[0].rfind("id,level,kind,x,y,vx,vy,rho,p,mass", 0), 0u) << rows[0];
    std::map<std::string, int> kinds;
    std::set<long> ids;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const auto c = split_csv(rows[i]);
      ASSERT_GE(c.size(), 10u) << rows[i];
      ++kinds[c[2]];
      ids.insert(std::stol(c[0]));
      EXPECT_EQ(c[1], "0");
      EXPECT_TRUE(std::isfinite(num(c[7])) && num(c[7]) > 0) << rows[i];
      EXPECT_NEAR(num(c[9]), 1000.0 * dp * dp, 1e-9) << rows[i];
    }
    EXPECT_EQ(kinds["fluid"], 1250);
    EXPECT_EQ(kinds["wall"], 687);
    EXPECT_EQ(ids.size(), 1937u) << "ids are unique";
  }

  // Line profiles: line_bottom_NNNN.csv at every output time, particles within dp/2, sorted by s.
  for (int k = 0; k <= 2; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "line_bottom_%04d.csv", k);
    ASSERT_TRUE(fs::exists(out / name)) << name;
    const auto rows = read_lines(out / name);
    ASSERT_GE(rows.size(), 2u) << name;
    EXPECT_EQ(rows[0].rfind("s,x,y,p,level", 0), 0u) << rows[0];
    double last_s = -1.0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const auto c = split_csv(rows[i]);
      ASSERT_GE(c.size(), 5u) << rows[i];
      const double s = num(c[0]), x = num(c[1]), y = num(c[2]);
      EXPECT_GE(s, last_s) << name << ": not sorted by s";
      last_s = s;
      EXPECT_NEAR(s, x, 1e-9) << "s is the distance from `from` along the segment";
      EXPECT_LE(std::abs(y - 0.05), 0.5 * dp + 1e-12) << rows[i];
      EXPECT_EQ(c[4], "0");
    }
  }
  EXPECT_FALSE(fs::exists(out / "line_bottom_0003.csv"));
}

// With analysis.laplace_pressure and a line, series.csv follows the Laplace figures in time
// (laplace_mean_interior, laplace_rmse at every output) and its last row repeats summary.json's.
TEST(CliRun, SeriesFollowsTheLaplaceError) {
  TempDir dir;
  const fs::path out = dir / "run";
  const CmdResult r =
      dir.run({"run", (kCases / "droplet_2d.toml").string(), "--out", out.string(), "--quiet",
               "--threads", "1", "--set", "resolution.dp=2e-4", "--set", "case.end_time=0.004",
               "--set", "output.interval=0.002", "--set", "output.formats=[\"csv\"]"});
  ASSERT_EQ(r.status, 0) << r;
  const auto series = read_lines(out / "series.csv");
  ASSERT_EQ(series.size(), 4u);
  const auto head = split_csv(series[0]);
  ASSERT_GE(head.size(), 2u);
  EXPECT_EQ(head[head.size() - 2], "laplace_mean_interior") << series[0];
  EXPECT_EQ(head.back(), "laplace_rmse") << series[0];
  // t = 0 at rest: every particle at p = 0, so the RMSE is the Laplace value itself.
  EXPECT_NEAR(num(split_csv(series[1]).back()), 36.4, 1e-9) << series[1];
  const auto last = split_csv(series.back());
  const auto sj = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_DOUBLE_EQ(num(last.back()), sj.at("laplace").at("rmse").get<double>());
  EXPECT_DOUBLE_EQ(num(last[last.size() - 2]), sj.at("laplace").at("mean_interior").get<double>());
  EXPECT_LT(num(last.back()), 36.4) << "the interior pressure has started to rise";
}

TEST(CliRun, ResolvedCaseReproducesTheRun) {
  // case.toml is "the case exactly as run": running it again gives the same particles.
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b";
  ASSERT_EQ(dir.run(tiny_dam_break(a, 0.005, 0.005)).status, 0);
  const CmdResult r = dir.run(
      {"run", (a / "case.toml").string(), "--out", b.string(), "--quiet", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_TRUE(same_bytes(a / snapshot(1, "csv"), b / snapshot(1, "csv")));
  EXPECT_TRUE(same_bytes(a / "series.csv", b / "series.csv"));
  EXPECT_TRUE(same_bytes(a / "case.toml", b / "case.toml"));
}

TEST(CliRun, ThreeDimensionalCsvHasZColumns) {
  TempDir dir;
  const fs::path out = dir / "run";
  const CmdResult r = dir.run({"run", dam_break_3d(), "--out", out.string(), "--quiet", "--threads",
                               "1", "--set", "resolution.dp=0.05", "--set", "case.end_time=0.001",
                               "--set", "output.formats=[\"vtp\", \"csv\"]"});
  ASSERT_EQ(r.status, 0) << r;
  const auto rows = read_lines(out / snapshot(1, "csv"));
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows[0].rfind("id,level,kind,x,y,z,vx,vy,vz,rho,p,mass", 0), 0u) << rows[0];
  EXPECT_EQ(rows.size(), 1u + 768u + 4629u);  // header, fluid, walls of the 1.2 x 0.3 x 0.9 m tank
}

TEST(CliRun, QuietRunPrintsNothingOnStdout) {
  TempDir dir;
  const CmdResult q = dir.run(tiny_dam_break(dir / "q", 0.002, 0.002));
  ASSERT_EQ(q.status, 0) << q;
  EXPECT_TRUE(q.out.empty()) << q;
  // Without --quiet and with stdout not a terminal: start and end summaries only, no progress.
  std::vector<std::string> args = tiny_dam_break(dir / "v", 0.002, 0.002);
  args.erase(std::find(args.begin(), args.end(), "--quiet"));
  const CmdResult v = dir.run(args);
  ASSERT_EQ(v.status, 0) << v;
  EXPECT_FALSE(v.out.empty()) << v;
  EXPECT_EQ(v.out.find('\r'), std::string::npos) << "no progress line when not on a terminal";
  EXPECT_LE(std::count(v.out.begin(), v.out.end(), '\n'), 3) << v;
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

TEST(CliUnstable, FluidLeavingTheDomainFailsTheDomainCheck) {
  TempDir dir;
  dir.write("tiny.toml", kTiny);
  const fs::path out = dir / "run";
  const CmdResult r = dir.run({"run", "tiny.toml", "--out", out.string(), "--quiet", "--threads",
                               "1", "--set", "fluid_block.0.velocity=[0, 30]", "--set",
                               "eos.sound_speed=300", "--set", "case.end_time=0.5"});
  expect_unstable(r, out, "domain");
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
  for (int k = 0; k <= 2; ++k) {
    EXPECT_TRUE(same_bytes(a / snapshot(k, "csv"), b / snapshot(k, "csv"))) << k;
  }
  EXPECT_TRUE(same_bytes(a / "series.csv", b / "series.csv"));
  EXPECT_TRUE(same_bytes(a / "refinement_boxes.vtp", b / "refinement_boxes.vtp"));
}

}  // namespace
