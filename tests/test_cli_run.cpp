// The files of a `vrsph run` as a user meets them: every contract file, the series with the
// Laplace error and with two levels, the resolved case, 3D columns, float32 and zlib snapshots,
// --quiet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_cases.hpp"
#include "cli_util.hpp"
#include "vres_fixtures.hpp"

namespace {

using namespace vrsph_cli;
using namespace vrsph_cli_cases;

// ---------------------------------------------------------------------------------------------
// A tiny run writes every file of the contract.

double num(const std::string& s) { return std::stod(s); }

// case.toml: every default filled in, the overrides applied, and re-loadable.
void expect_resolved_case(TempDir& dir, const fs::path& out) {
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
}

// Snapshots 0, 1, 2 (t = 0, 5 ms, 10 ms) as vtp and csv; no more.
void expect_snapshots(const fs::path& out) {
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
}

// particles.pvd: every snapshot once, increasing times, from 0 to the end time.
void expect_pvd(const std::vector<PvdEntry>& pvd, double end) {
  ASSERT_EQ(pvd.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(pvd[k].file, snapshot(k, "vtp"));
  EXPECT_EQ(pvd.front().time, 0.0);
  EXPECT_NEAR(pvd.back().time, end, 1e-12);
  for (std::size_t k = 1; k < pvd.size(); ++k) EXPECT_GT(pvd[k].time, pvd[k - 1].time);
}

// series.csv: the contract header, one row per output time.
void expect_series(const fs::path& out, const std::vector<PvdEntry>& pvd, double dp, double end,
                   long& last_step) {
  const auto series = read_lines(out / "series.csv");
  ASSERT_EQ(series.size(), 4u);
  EXPECT_EQ(series[0].rfind("t,step,dt,n_fluid,n_buffer,mass_fluid,kinetic_energy,max_speed", 0),
            0u)
      << series[0];
  EXPECT_EQ(series[0].find("kinetic_energy_cm"), std::string::npos) << "only with surface tension";
  last_step = -1;
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
}

// summary.json.
void expect_summary(const fs::path& out, long last_step, double end) {
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
}

// Particle CSV: header, one row per particle, kinds.
void expect_particle_csvs(const fs::path& out, double dp) {
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
}

// Line profiles: line_bottom_NNNN.csv at every output time, particles within dp/2, sorted by s.
void expect_line_profiles(const fs::path& out, double dp) {
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

  expect_resolved_case(dir, out);
  expect_snapshots(out);
  const auto pvd = read_pvd(out / "particles.pvd");
  ASSERT_NO_FATAL_FAILURE(expect_pvd(pvd, end));
  long last_step = -1;
  ASSERT_NO_FATAL_FAILURE(expect_series(out, pvd, dp, end, last_step));
  expect_summary(out, last_step, end);
  ASSERT_NO_FATAL_FAILURE(expect_particle_csvs(out, dp));
  ASSERT_NO_FATAL_FAILURE(expect_line_profiles(out, dp));
}

// With analysis.laplace_pressure and a line, series.csv follows the Laplace figures in time
// (laplace_mean_interior, laplace_rmse on the particle strip, laplace_interp_* on the interpolated
// line, at every output) and its last row repeats summary.json's.
TEST(CliRun, SeriesFollowsTheLaplaceError) {
  TempDir dir;
  const fs::path out = dir / "run";
  const CmdResult r = dir.run({"run", (kCases / "droplet_2d.toml").string(), "--out", out.string(),
                               "--quiet", "--threads", "1", "--set", "resolution.dp=2e-4", "--set",
                               "case.end_time=0.004", "--set", "output.interval=0.002", "--set",
                               "output.formats=[\"csv\"]", "--set", "fluid_block.0.pressure=0"});
  ASSERT_EQ(r.status, 0) << r;
  const auto series = read_lines(out / "series.csv");
  ASSERT_EQ(series.size(), 4u);
  const auto head = split_csv(series[0]);
  auto col = [&](const std::string& name) {
    const auto it = std::find(head.begin(), head.end(), name);
    EXPECT_NE(it, head.end()) << name << " not in " << series[0];
    return static_cast<std::size_t>(it - head.begin());
  };
  const std::size_t mean = col("laplace_mean_interior"), rmse = col("laplace_rmse");
  const std::size_t imean = col("laplace_interp_mean_interior");
  const std::size_t irmse = col("laplace_interp_rmse");
  ASSERT_EQ(irmse, head.size() - 1) << series[0];
  // t = 0 at rest: every particle at p = 0, so both RMSEs are the Laplace value itself.
  EXPECT_NEAR(num(split_csv(series[1])[rmse]), 36.4, 1e-9) << series[1];
  EXPECT_NEAR(num(split_csv(series[1])[irmse]), 36.4, 1e-9) << series[1];
  const auto last = split_csv(series.back());
  const auto lp = nlohmann::json::parse(read_text(out / "summary.json")).at("laplace");
  EXPECT_DOUBLE_EQ(num(last[rmse]), lp.at("rmse").get<double>());
  EXPECT_DOUBLE_EQ(num(last[mean]), lp.at("mean_interior").get<double>());
  EXPECT_DOUBLE_EQ(num(last[irmse]), lp.at("interp_rmse").get<double>());
  EXPECT_DOUBLE_EQ(num(last[imean]), lp.at("interp_mean_interior").get<double>());
  EXPECT_LT(num(last[rmse]), 36.4) << "the interior pressure has started to rise";
  // With surface tension, the kinetic energy in the fluid's centre-of-mass frame: none at the
  // start at rest, then the drop's own motion, at most all of its kinetic energy.
  const std::size_t ke = col("kinetic_energy"), ke_cm = col("kinetic_energy_cm");
  EXPECT_EQ(num(split_csv(series[1])[ke_cm]), 0.0) << series[1];
  EXPECT_GT(num(last[ke_cm]), 0.0) << series.back();
  EXPECT_LE(num(last[ke_cm]), num(last[ke]) * (1.0 + 1e-12)) << series.back();
  // The interpolated line: points every dp/2 across the 4 mm diameter, the interior ones (2h
  // from the ends of the points inside) counted, and a pressure that has risen as the strip's.
  EXPECT_GT(lp.at("interp_n_points").get<int>(), 20);
  EXPECT_GT(num(last[imean]), 10.0);
  EXPECT_LT(num(last[irmse]), 36.4);
  EXPECT_EQ(read_lines(out / "line_diameter_interp_0002.csv").size(), 1u + 41u);
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

// output.precision and output.compression change the snapshots' storage, not the run.
TEST(CliRun, Float32AndZlibSnapshotsOfTheSameRun) {
  TempDir dir;
  const fs::path a = dir / "a", b = dir / "b";
  ASSERT_EQ(dir.run(tiny_dam_break(a, 0.002, 0.002)).status, 0);
  std::vector<std::string> args = tiny_dam_break(b, 0.002, 0.002);
  for (const char* set : {"output.precision=\"float32\"", "output.compression=\"zlib\""})
    args.insert(args.end(), {"--set", set});
  const CmdResult r = dir.run(args);
  ASSERT_EQ(r.status, 0) << r;
  const std::string vtp = read_text(b / snapshot(1, "vtp"));
  EXPECT_NE(vtp.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  EXPECT_NE(vtp.find("type=\"Float64\" Name=\"Points\""), std::string::npos);
  EXPECT_NE(vtp.find("type=\"Float32\" Name=\"rho\""), std::string::npos);
  EXPECT_LT(vtp.size(), read_text(a / snapshot(1, "vtp")).size() / 2);
  EXPECT_LT(fs::file_size(b / snapshot(1, "csv")), fs::file_size(a / snapshot(1, "csv")));
  EXPECT_TRUE(same_bytes(a / "series.csv", b / "series.csv"));
  const std::string resolved = read_text(b / "case.toml");
  EXPECT_NE(resolved.find("precision = \"float32\""), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("compression = \"zlib\""), std::string::npos) << resolved;
  // Positions keep every digit in the CSV.
  const auto rows_a = read_lines(a / snapshot(1, "csv")),
             rows_b = read_lines(b / snapshot(1, "csv"));
  ASSERT_EQ(rows_a.size(), rows_b.size());
  for (std::size_t i = 1; i < rows_a.size(); ++i) {
    const auto ca = split_csv(rows_a[i]), cb = split_csv(rows_b[i]);
    for (std::size_t c = 0; c < 5; ++c) ASSERT_EQ(ca[c], cb[c]) << rows_b[i];
  }
}

TEST(CliRun, QuietRunPrintsNothingOnStdout) {
  TempDir dir;
  const CmdResult q = dir.run(tiny_dam_break(dir / "q", 0.002, 0.002));
  ASSERT_EQ(q.status, 0) << q;
  EXPECT_TRUE(q.out.empty()) << q;
  // Without --quiet and with stdout not a terminal: the start line, a line per output time
  // (t = 0 and 2 ms) and the end line, no progress line.
  std::vector<std::string> args = tiny_dam_break(dir / "v", 0.002, 0.002);
  args.erase(std::find(args.begin(), args.end(), "--quiet"));
  const CmdResult v = dir.run(args);
  ASSERT_EQ(v.status, 0) << v;
  EXPECT_FALSE(v.out.empty()) << v;
  EXPECT_EQ(v.out.find('\r'), std::string::npos) << "no progress line when not on a terminal";
  EXPECT_EQ(std::count(v.out.begin(), v.out.end(), '\n'), 4) << v;
  // Quiet or not, run.log has them all.
  for (const char* d : {"q", "v"}) {
    const std::string log = read_text(dir / d / "run.log");
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 5) << d << "\n" << log;
  }
}

// Two levels: series.csv gives each level's mass held by its mass points. A block at 1 m/s
// through the face of a refinement box for 0.1 s carries rho U H t = 40 kg/m into the fine
// level: what it created plus what its points still hold must account for that flux (measured:
// created 39.80, held 0.18 kg/m), tighter than the created mass alone.
TEST(CliRun, SeriesAccountsTheMassHeldByTheMassPoints) {
  TempDir dir;
  dir.write("flux.toml", vrsph::test::kUniformFlowThroughAFace);
  const fs::path out = dir / "run";
  const CmdResult r = dir.run({"run", "flux.toml", "--out", out.string(), "--quiet", "--threads",
                               "1", "--set", "output.interval=0.05", "--set", "output.formats=[]"});
  ASSERT_EQ(r.status, 0) << r;
  const auto lines = read_lines(out / "series.csv");
  ASSERT_EQ(lines.size(), 4u);  // header, t = 0, 0.05, 0.1
  const auto head = split_csv(lines[0]);
  auto col = [&](const std::string& name) {
    const auto it = std::find(head.begin(), head.end(), name);
    EXPECT_NE(it, head.end()) << "series.csv lacks " << name;
    return static_cast<std::size_t>(it - head.begin());
  };
  const std::size_t s0 = col("mass_stored_L0"), s1 = col("mass_stored_L1");
  const std::size_t created = col("created_mass");
  EXPECT_EQ(num(split_csv(lines[1])[s1]), 0.0);
  const auto last = split_csv(lines[3]);
  const double held = num(last[s1]), made = num(last[created]), flux = 40.0;
  EXPECT_GT(held, 0.0);
  EXPECT_LT(held, 0.01 * flux);  // a lag of a fraction of a particle mass per point
  EXPECT_NEAR(made + held, flux, 0.002 * flux);
  EXPECT_LT(std::abs(made + held - flux), std::abs(made - flux));
  EXPECT_LE(num(last[s0]), 0.0);  // the coarse level's points see outflow only
}

}  // namespace
