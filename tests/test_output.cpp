// Output layer: line profiles, atomic writes, series.csv with resume, summary.json and the
// progress line (particle files: test_output_particles.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "output_fixtures.hpp"
#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/line_profile.hpp"
#include "vrsph/output/progress.hpp"
#include "vrsph/output/series.hpp"
#include "vrsph/output/summary.hpp"

namespace fs = std::filesystem;
using namespace vrsph;
using namespace vrsph::output_fixtures;

TEST(OutputLine, SelectsNearbyFluidParticlesSortedByS) {
  TempDir dir;
  ParticleSet<2> ps;
  const Vec<2> zero{{0, 0}};
  // Segment from (-1, 0) to (1, 0), half width 0.1.
  ps.push_back(1, Kind::fluid, {{0.5, 0.05}}, zero, 1000, 1);   // in, s = 1.5
  ps.push_back(2, Kind::fluid, {{-0.9, -0.1}}, zero, 1000, 1);  // in (on the edge), s = 0.1
  ps.push_back(3, Kind::wall, {{0.0, 0.0}}, zero, 1000, 1);     // wall: out
  ps.push_back(4, Kind::fluid, {{0.0, 0.0}}, zero, 1000, 1);    // in (level 1), s = 1
  ps.push_back(5, Kind::fluid, {{0.0, 0.11}}, zero, 1000, 1);   // too far: out
  ps.push_back(6, Kind::fluid, {{1.05, 0.0}}, zero, 1000, 1);   // beyond the end: out
  ps.push_back(7, Kind::fluid, {{-1.01, 0.0}}, zero, 1000, 1);  // before the start: out
  ps.push_back(8, Kind::fluid, {{1.0, 0.0}}, zero, 1000, 1);    // at the end, s = 2
  ps.push_back(9, Kind::buffer, {{0.2, 0.0}}, zero, 1000, 1);   // buffer mirrors: out
  for (std::size_t i = 0; i < ps.size(); ++i) ps.rho[i] = kEos.density(10.0 * double(i + 1));
  const std::vector<std::uint8_t> level{0, 0, 0, 1, 0, 0, 0, 0, 1};
  const Vec<2> from{{-1, 0}}, to{{1, 0}};
  const auto samples = sample_line<2>(ps, kEos, level, from, to, 0.1);
  std::vector<std::uint64_t> ids;
  for (const auto& q : samples) ids.push_back(q.id);
  EXPECT_EQ(ids, (std::vector<std::uint64_t>{2, 4, 1, 8}));
  EXPECT_NEAR(samples[0].s, 0.1, 1e-15);
  EXPECT_EQ(samples[1].level, 1);
  EXPECT_NEAR(samples[1].p, 40.0, 1e-9);

  write_line_profile<2>(dir.path / "line.csv", ps, kEos, level, from, to, 0.1);
  const auto lines = lines_of(read_all(dir.path / "line.csv"));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "s,x,y,p,level");
  // Each row: s, x, y, the EOS pressure of the particle's density, level.
  const auto row = [&](std::size_t k) {
    std::vector<std::string> f;
    std::stringstream in(lines[k]);
    for (std::string cell; std::getline(in, cell, ',');) f.push_back(cell);
    return f;
  };
  EXPECT_EQ(row(2)[0] + "," + row(2)[1] + "," + row(2)[2] + "," + row(2)[4], "1,0,0,1");
  EXPECT_NEAR(std::stod(row(2)[3]), 40.0, 1e-9);
  EXPECT_EQ(row(4)[0] + "," + row(4)[1] + "," + row(4)[2] + "," + row(4)[4], "2,1,0,0");
  EXPECT_NEAR(std::stod(row(4)[3]), 80.0, 1e-9);
  EXPECT_THROW(sample_line<2>(ps, kEos, {}, from, from, 0.1), std::invalid_argument);
}

TEST(OutputLine, ThreeDimensionalHeader) {
  TempDir dir;
  const ParticleSet<3> ps = small_set_3d();
  write_line_profile<3>(dir.path / "line.csv", ps, kEos, {}, Vec<3>{{0, 0, 0}},
                        Vec<3>{{0.2, 0.4, 0.6}}, 1e-6);
  const auto lines = lines_of(read_all(dir.path / "line.csv"));
  ASSERT_EQ(lines.size(), 2u);  // only the fluid particle at (0.1, 0.2, 0.3) lies on the line
  EXPECT_EQ(lines[0], "s,x,y,z,p,level");
  EXPECT_TRUE(lines[1].ends_with(",0.1,0.2,0.3,0,0"));  // rho0: p = 0
}

TEST(OutputAtomic, ReplacesTargetAndLeavesNoTempFiles) {
  TempDir dir;
  const fs::path target = dir.path / "a.txt";
  write_file_atomic(target, "first\n");
  write_file_atomic(target, "second\n");
  EXPECT_EQ(read_all(target), "second\n");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"a.txt"});
  {
    AtomicWriter w(target);
    w.stream() << "third\n";
    EXPECT_TRUE(fs::exists(w.temp_path()));
    EXPECT_EQ(read_all(target), "second\n");  // nothing visible before commit
    w.commit();
  }
  EXPECT_EQ(read_all(target), "third\n");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"a.txt"});
}

TEST(OutputAtomic, UncommittedWriterLeavesTargetUntouched) {
  TempDir dir;
  const fs::path target = dir.path / "a.txt";
  write_file_atomic(target, "keep\n");
  try {
    AtomicWriter w(target);
    w.stream() << "half a fi";
    throw std::runtime_error("killed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read_all(target), "keep\n");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"a.txt"});
}

TEST(OutputAtomic, FailureNamesThePath) {
  TempDir dir;
  const fs::path target = dir.path / "no_such_dir" / "a.txt";
  try {
    write_file_atomic(target, "x");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
  }
}

TEST(OutputSeries, ComputeRowOverFluidOnly) {
  const ParticleSet<2> ps = small_set_2d();
  const SeriesRow row = compute_series_row<2>(ps, 0.5, 42, 1e-5);
  EXPECT_EQ(row.t, 0.5);
  EXPECT_EQ(row.step, 42);
  EXPECT_EQ(row.dt, 1e-5);
  EXPECT_EQ(row.n_fluid, 2);
  EXPECT_EQ(row.n_buffer, 1);
  EXPECT_DOUBLE_EQ(row.mass_fluid, 2.5e-6 + 1.0);
  EXPECT_DOUBLE_EQ(row.kinetic_energy, 0.5 * 2.5e-6 * (2.5e-3 * 2.5e-3 + 1e-34) + 0.5 * 25.0);
  EXPECT_DOUBLE_EQ(row.max_speed, 5.0);  // the buffer particle (speed 0.5) does not count
  SeriesRow total = row;
  accumulate_series_row(total, compute_series_row<2>(ps, 0.5, 42, 1e-5));
  EXPECT_EQ(total.n_fluid, 4);
  EXPECT_DOUBLE_EQ(total.mass_fluid, 2 * row.mass_fluid);
  EXPECT_EQ(total.max_speed, 5.0);
}

// Two fluid particles of masses m1, m2 (a wall and a buffer particle beside them, which do not
// count): in the centre-of-mass frame their kinetic energy is m1 m2 / (m1 + m2) |v1 - v2|^2 / 2,
// whatever velocity the pair shares, and split over two sets it is the same.
TEST(OutputSeries, CentreOfMassKineticEnergy) {
  ParticleSet<2> a;
  a.push_back(1, Kind::fluid, {{0.0, 0.0}}, {{1.0, 2.0}}, 1000.0, 2.0);
  a.push_back(2, Kind::wall, {{1.0, 0.0}}, {{50.0, 0.0}}, 1000.0, 9.0);
  a.push_back(3, Kind::buffer, {{2.0, 0.0}}, {{0.0, -70.0}}, 1000.0, 9.0);
  ParticleSet<2> b;
  b.push_back(4, Kind::fluid, {{3.0, 0.0}}, {{-2.0, 6.0}}, 1000.0, 3.0);
  const double expected = 0.5 * (2.0 * 3.0 / 5.0) * (3.0 * 3.0 + 4.0 * 4.0);  // 7.5
  const std::vector<const ParticleSet<2>*> two{&a, &b};
  EXPECT_NEAR(centre_of_mass_kinetic_energy<2>(two), expected, 1e-12);
  // the same pair translating at 100 m/s more: its energy in its own frame does not change
  for (ParticleSet<2>* ps : {&a, &b})
    for (auto& v : ps->vel) v[0] += 100.0;
  EXPECT_NEAR(centre_of_mass_kinetic_energy<2>(two), expected, 1e-9);
  // one set alone: a single fluid particle has none
  const std::vector<const ParticleSet<2>*> one{&b};
  EXPECT_EQ(centre_of_mass_kinetic_energy<2>(one), 0.0);
  const std::vector<const ParticleSet<2>*> none{};
  EXPECT_EQ(centre_of_mass_kinetic_energy<2>(none), 0.0);
}

TEST(OutputSeries, AppendAndResumeDropsLaterRows) {
  TempDir dir;
  const fs::path path = dir.path / "series.csv";
  {
    SeriesWriter w(path, {"surface_count"});
    for (int k = 0; k < 4; ++k) {
      SeriesRow row;
      row.t = 0.1 * k;
      row.step = 10 * k;
      row.extra = {double(k)};
      w.append(row);
    }
    SeriesRow bad;
    EXPECT_THROW(w.append(bad), std::invalid_argument);
  }
  auto lines = lines_of(read_all(path));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0],
            "t,step,dt,n_fluid,n_buffer,mass_fluid,kinetic_energy,max_speed,surface_count");
  EXPECT_EQ(lines[2], "0.1,10,0,0,0,0,0,0,1");

  // A killed run may leave a partial last line: resume drops it and every row after t = 0.15.
  { std::ofstream(path, std::ios::app) << "0.4,40,0,0"; }
  SeriesWriter w = SeriesWriter::resume(path, 0.15);
  EXPECT_EQ(w.extra_columns(), std::vector<std::string>{"surface_count"});
  lines = lines_of(read_all(path));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[2], "0.1,10,0,0,0,0,0,0,1");
  SeriesRow row;
  row.t = 0.2;
  row.step = 20;
  row.extra = {9.0};
  w.append(row);
  lines = lines_of(read_all(path));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[3], "0.2,20,0,0,0,0,0,0,9");
  EXPECT_THROW(SeriesWriter::resume(path, 1.0, {"other"}), std::runtime_error);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"series.csv"});
}

TEST(OutputSummary, WritesIndentedJson) {
  TempDir dir;
  nlohmann::json j;
  j["completed"] = true;
  j["steps"] = 12;
  write_summary_json(dir.path / "summary.json", j);
  const std::string text = read_all(dir.path / "summary.json");
  EXPECT_EQ(text, "{\n  \"completed\": true,\n  \"steps\": 12\n}\n");
  EXPECT_EQ(read_json_file(dir.path / "summary.json"), j);
}

TEST(OutputProgress, ThrottledLineAndFinish) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress progress(0.2, true, f);
  EXPECT_EQ(progress.line(0.0123, 1234, 540.2, 83.0),
            "  t = 0.0123 / 0.2000 s  step 1234  540 steps/s  ETA 00:01:23");
  progress.update(0.01, 1, 100.0);
  progress.update(0.02, 2, 100.0);  // within 0.25 s of the first draw: not drawn
  progress.finish();
  std::rewind(f);
  std::string text(4096, '\0');
  text.resize(std::fread(text.data(), 1, text.size(), f));
  std::fclose(f);
  ASSERT_EQ(std::count(text.begin(), text.end(), '\r'), 2);
  EXPECT_TRUE(text.starts_with("\r  t = 0.0100 / 0.2000 s  step 1  100 steps/s  ETA "));
  EXPECT_NE(text.find("\r  t = 0.0200 / 0.2000 s  step 2"), std::string::npos);
  EXPECT_TRUE(text.ends_with("\n"));

  std::FILE* g = std::tmpfile();
  Progress quiet(0.2, false, g);
  quiet.update(0.1, 1, 1.0);
  quiet.finish();
  EXPECT_EQ(std::ftell(g), 0);
  std::fclose(g);
}
