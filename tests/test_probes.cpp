// Point probes ([[output.probe]] -> probe_<name>.csv) and the interpolated lines
// (line_<name>_interp_NNNN.csv), docs/outputs.md:
//  - the probe writer: header, a row per call, empty values outside the fluid, resume cuts the
//    file back to the checkpoint's time (a partial last line included), a foreign header refused;
//  - a dam break with a probe in the water column and one in the air: a row per output time, the
//    water probe at rest at t = 0 reads the hydrostatic pressure, the air probe only empty values;
//    the line's interpolated file every dp/2 with the fluid values where there is fluid;
//  - a resumed run, also one whose probe files went past its checkpoint, writes the same bytes
//    as an uninterrupted one.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_util.hpp"
#include "vrsph/output/probe_series.hpp"

namespace {

using namespace vrsph_cli;

TEST(ProbeWriter, RowsEmptyValuesAndResume) {
  TempDir dir;
  const fs::path p = dir / "probe_a.csv";
  vrsph::ProbeWriter<2> w(p);
  vrsph::FluidPoint<2> in;
  in.level = 0;
  in.p = 12.5;
  in.rho = 1000.25;
  in.vel = vrsph::Vec<2>{{0.5, -1.0}};
  w.append(0.0, in);
  w.append(0.5, vrsph::FluidPoint<2>{});  // outside: level -1
  w.append(1.0, in);
  std::vector<std::string> rows = read_lines(p);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], "t,p,rho,vx,vy");
  EXPECT_EQ(rows[1], "0,12.5,1000.25,0.5,-1");
  EXPECT_EQ(rows[2], "0.5,,,,");
  EXPECT_EQ(split_csv(rows[2]).size(), 5u);
  // A resume at t = 0.5 keeps the rows up to it and drops a broken last line.
  write_text(p, read_text(p) + "1.5,3,4");
  vrsph::ProbeWriter<2>::resume(p, 0.5).append(0.75, in);
  rows = read_lines(p);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[2], "0.5,,,,");
  EXPECT_EQ(rows[3], "0.75,12.5,1000.25,0.5,-1");
  EXPECT_EQ(vrsph::ProbeWriter<3>::header(), "t,p,rho,vx,vy,vz");
  EXPECT_THROW(vrsph::ProbeWriter<3>::resume(p, 1.0), std::runtime_error);
  // A missing file starts anew.
  vrsph::ProbeWriter<3>::resume(dir / "probe_b.csv", 1.0);
  EXPECT_EQ(read_lines(dir / "probe_b.csv"), std::vector<std::string>{"t,p,rho,vx,vy,vz"});
}

// The dam break (water column [0.01, 1] x [0.01, 2] m) with a probe in the water, one in the air
// and a horizontal line through the column.
std::string probe_case() {
  return read_text(dam_break_2d()) + R"(
[[output.probe]]
name = "water"
position = [0.5, 0.5]

[[output.probe]]
name = "air"
position = [3.0, 2.0]

[[output.line]]
name = "across"
from = [0.0, 0.5]
to = [2.0, 0.5]
)";
}

std::vector<std::string> probe_run(const fs::path& out) {
  return {"run",
          "probes.toml",
          "--out",
          out.string(),
          "--quiet",
          "--set",
          "resolution.dp=0.04",
          "--set",
          "case.end_time=0.02",
          "--set",
          "output.interval=0.005",
          "--threads",
          "1"};
}

void expect_water_probe(const fs::path& out) {
  const auto rows = read_lines(out / "probe_water.csv");
  ASSERT_EQ(rows.size(), 1u + 5u);
  EXPECT_EQ(rows[0], "t,p,rho,vx,vy");
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto c = split_csv(rows[k]);
    ASSERT_EQ(c.size(), 5u) << rows[k];
    EXPECT_NEAR(std::stod(c[0]), 0.005 * static_cast<double>(k - 1), 1e-12);
    for (std::size_t q = 1; q < c.size(); ++q) EXPECT_TRUE(std::isfinite(std::stod(c[q])));
    EXPECT_NEAR(std::stod(c[2]), 1000.0, 10.0) << rows[k];
  }
  // At rest at t = 0: rho0 g depth below the top row (y = 0.01 + 49 dp = 1.97 m), and v = 0.
  const auto first = split_csv(rows[1]);
  EXPECT_NEAR(std::stod(first[1]), 1000.0 * 9.81 * (1.97 - 0.5), 0.01 * 14420.0) << rows[1];
  EXPECT_EQ(first[3], "0");
  EXPECT_EQ(first[4], "0");
}

void expect_air_probe(const fs::path& out) {
  const auto rows = read_lines(out / "probe_air.csv");
  ASSERT_EQ(rows.size(), 1u + 5u);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto c = split_csv(rows[k]);
    ASSERT_EQ(c.size(), 5u) << rows[k];
    for (std::size_t q = 1; q < c.size(); ++q) EXPECT_EQ(c[q], "") << rows[k];
  }
}

// Points every dp/2 = 0.02 m from x = 0 to 2; the fluid values inside the column, none beyond.
void expect_interp_line(const fs::path& out) {
  const auto rows = read_lines(out / "line_across_interp_0000.csv");
  ASSERT_EQ(rows.size(), 1u + 101u);
  EXPECT_EQ(rows[0], "s,x,y,p,rho,vx,vy,level,shepard");
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto c = split_csv(rows[k]);
    ASSERT_EQ(c.size(), 9u) << rows[k];
    const double x = std::stod(c[1]);
    EXPECT_NEAR(x, 0.02 * static_cast<double>(k - 1), 1e-12);
    if (x > 0.1 && x < 0.9) EXPECT_EQ(c[7], "0") << rows[k];        // inside the column
    if (x > 1.2) EXPECT_EQ(c[3] + c[7], "") << rows[k];             // beyond its face
    if (!c[7].empty()) EXPECT_GE(std::stod(c[8]), 0.5) << rows[k];  // inside: S >= 1/2
  }
  EXPECT_TRUE(fs::exists(out / "line_across_0004.csv"));
  EXPECT_TRUE(fs::exists(out / "line_across_interp_0004.csv"));
}

TEST(Probes, DamBreakProbesAndInterpolatedLine) {
  TempDir dir;
  dir.write("probes.toml", probe_case());
  const fs::path out = dir / "run";
  const CmdResult r = dir.run(probe_run(out));
  ASSERT_EQ(r.status, 0) << r;
  expect_water_probe(out);
  expect_air_probe(out);
  expect_interp_line(out);
  EXPECT_NE(read_text(out / "case.toml").find("[[output.probe]]"), std::string::npos);
  // --force removes the probe files with the rest of the run's files.
  write_text(out / "probe_gone.csv", "t\n");
  ASSERT_EQ(dir.run({"run", "probes.toml", "--out", out.string(), "--quiet", "--force", "--set",
                     "resolution.dp=0.04", "--set", "case.end_time=0.005"})
                .status,
            0);
  EXPECT_FALSE(fs::exists(out / "probe_gone.csv"));
}

TEST(Probes, ResumedRunWritesTheSameProbeFiles) {
  TempDir dir;
  dir.write("probes.toml", probe_case());
  const fs::path a = dir / "a", b = dir / "b", c = dir / "c";
  ASSERT_EQ(dir.run(probe_run(a)).status, 0);
  std::vector<std::string> halted = probe_run(b);
  halted.insert(halted.end(), {"--halt-after-output", "2"});
  ASSERT_EQ(dir.run(halted).status, 9);
  EXPECT_EQ(read_lines(b / "probe_water.csv").size(), 1u + 3u);
  // c: a finished run given the checkpoint of snapshot 2, its probe files past it.
  ASSERT_EQ(dir.run(probe_run(c)).status, 0);
  fs::copy_file(b / "checkpoint.bin", c / "checkpoint.bin", fs::copy_options::overwrite_existing);
  for (const fs::path& d : {b, c}) {
    const CmdResult r = dir.run({"run", "--resume", d.string(), "--quiet", "--threads", "1"});
    ASSERT_EQ(r.status, 0) << r;
    for (const char* f :
         {"probe_water.csv", "probe_air.csv", "line_across_interp_0004.csv", "series.csv"}) {
      EXPECT_TRUE(same_bytes(a / f, d / f)) << d << " " << f;
    }
  }
}

}  // namespace
