// Output layer: particle CSV and VTP snapshots, the .pvd collection, series.csv with resume,
// line profiles, atomic writes, summary.json and the progress line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/line_profile.hpp"
#include "vrsph/output/progress.hpp"
#include "vrsph/output/series.hpp"
#include "vrsph/output/snapshot.hpp"
#include "vrsph/output/summary.hpp"

namespace fs = std::filesystem;
using namespace vrsph;

namespace {

// A fresh directory under the system temp dir, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() /
           ("vrsph_output_test_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
};

std::string read_all(const fs::path& p) { return read_text_file(p); }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
  return out;
}

// Four 2D particles of every kind with awkward (non-short) numbers; p is set.
ParticleSet<2> small_set_2d() {
  ParticleSet<2> ps;
  ps.push_back(7, Kind::fluid, {{0.1, 1.0 / 3.0}}, {{-2.5e-3, 1e-17}}, 1000.0000001, 2.5e-6);
  ps.push_back(3, Kind::wall, {{-4e-3, 0.0}}, {{0.0, 0.0}}, 999.5, 2.5e-6);
  ps.push_back(11, Kind::buffer, {{1e-300, -7.25}}, {{0.3, 0.4}}, 1001.0, 6.25e-7);
  ps.push_back(12, Kind::fluid, {{2.0, 3.0}}, {{3.0, 4.0}}, 1000.0, 1.0);
  ps.p = {12.5, -0.1, 36.4, 1.0 / 7.0};
  return ps;
}

ParticleSet<3> small_set_3d() {
  ParticleSet<3> ps;
  ps.push_back(1, Kind::fluid, {{0.1, 0.2, 0.3}}, {{1.0, 2.0, 2.0}}, 1000.0, 1e-9);
  ps.push_back(2, Kind::wall, {{-0.1, 0.2, -0.3}}, {{0.0, 0.0, 0.0}}, 1000.0, 1e-9);
  ps.p = {5.0, 6.0};
  return ps;
}

}  // namespace

TEST(OutputCsv, HeaderAndValuesRoundTrip2D) {
  TempDir dir;
  const ParticleSet<2> ps = small_set_2d();
  std::vector<ExtraField> extras{{"lambda", 1, {0.9, 1.0, 0.5, 1.0 / 3.0}},
                                 {"normal", 2, {1, 0, 0, 1, -1, 0, 0.6, 0.8}}};
  const std::vector<std::uint8_t> level{0, 0, 1, 1};
  write_particles_csv<2>(dir.path / "p.csv", ps, extras, level);
  const auto lines = lines_of(read_all(dir.path / "p.csv"));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "id,level,kind,x,y,vx,vy,rho,p,mass,lambda,normal_x,normal_y");
  const char* kinds[] = {"fluid", "wall", "buffer", "fluid"};
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const auto f = split_csv(lines[i + 1]);
    ASSERT_EQ(f.size(), 13u);
    EXPECT_EQ(std::stoull(f[0]), ps.id[i]);
    EXPECT_EQ(std::stoi(f[1]), level[i]);
    EXPECT_EQ(f[2], kinds[i]);
    EXPECT_EQ(std::stod(f[3]), ps.pos[i][0]);  // exact: shortest repr round-trips
    EXPECT_EQ(std::stod(f[4]), ps.pos[i][1]);
    EXPECT_EQ(std::stod(f[5]), ps.vel[i][0]);
    EXPECT_EQ(std::stod(f[6]), ps.vel[i][1]);
    EXPECT_EQ(std::stod(f[7]), ps.rho[i]);
    EXPECT_EQ(std::stod(f[8]), ps.p[i]);
    EXPECT_EQ(std::stod(f[9]), ps.mass[i]);
    EXPECT_EQ(std::stod(f[10]), extras[0].values[i]);
    EXPECT_EQ(std::stod(f[11]), extras[1].values[2 * i]);
    EXPECT_EQ(std::stod(f[12]), extras[1].values[2 * i + 1]);
  }
}

TEST(OutputCsv, Header3DAndDefaultLevel) {
  TempDir dir;
  std::vector<ExtraField> extras{{"normal", 3, {1, 0, 0, 0, 0, 1}}};
  write_particles_csv<3>(dir.path / "p.csv", small_set_3d(), extras, {});
  const auto lines = lines_of(read_all(dir.path / "p.csv"));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "id,level,kind,x,y,z,vx,vy,vz,rho,p,mass,normal_x,normal_y,normal_z");
  EXPECT_EQ(lines[2], "2,0,wall,-0.1,0.2,-0.3,0,0,0,1000,6,1e-09,0,0,1");
}

TEST(OutputCsv, RejectsBadSizes) {
  TempDir dir;
  std::vector<ExtraField> bad{{"lambda", 1, {1.0}}};
  EXPECT_THROW(write_particles_csv<2>(dir.path / "p.csv", small_set_2d(), bad, {}),
               std::invalid_argument);
  const std::vector<std::uint8_t> level{0};
  EXPECT_THROW(write_vtp<2>(dir.path / "p.vtp", small_set_2d(), {}, level), std::invalid_argument);
  EXPECT_TRUE(dir.files().empty());
}

namespace {

// Reads the appended raw block of the DataArray named `name` ("" = Points) from a .vtp.
template <class T>
std::vector<T> vtp_array(const std::string& vtp, const std::string& name) {
  const std::string key = "Name=\"" + (name.empty() ? std::string("Points") : name) + "\"";
  const std::size_t at = vtp.find(key);
  EXPECT_NE(at, std::string::npos) << name;
  if (at == std::string::npos) return {};
  const std::size_t off_at = vtp.find("offset=\"", at) + 8;
  const std::size_t offset = std::stoull(vtp.substr(off_at));
  const std::size_t data = vtp.find("<AppendedData encoding=\"raw\">");
  const std::size_t base = vtp.find('_', data) + 1;
  std::uint64_t nbytes = 0;
  std::memcpy(&nbytes, vtp.data() + base + offset, sizeof(nbytes));
  std::vector<T> values(nbytes / sizeof(T));
  std::memcpy(values.data(), vtp.data() + base + offset + sizeof(nbytes), nbytes);
  return values;
}

}  // namespace

TEST(OutputVtp, WellFormedWithArraysThatDecode) {
  TempDir dir;
  const ParticleSet<2> ps = small_set_2d();
  std::vector<ExtraField> extras{{"normal", 2, {1, 0, 0, 1, -1, 0, 0.6, 0.8}}};
  const std::vector<std::uint8_t> level{0, 0, 1, 1};
  write_vtp<2>(dir.path / "p.vtp", ps, extras, level);
  const std::string vtp = read_all(dir.path / "p.vtp");
  EXPECT_NE(vtp.find("<VTKFile type=\"PolyData\""), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfPoints=\"4\""), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfVerts=\"4\""), std::string::npos);
  for (const char* name :
       {"id", "level", "kind", "velocity", "rho", "p", "mass", "normal", "connectivity", "offsets"})
    EXPECT_NE(vtp.find("Name=\"" + std::string(name) + "\""), std::string::npos) << name;
  EXPECT_TRUE(vtp.ends_with("</AppendedData>\n</VTKFile>\n"));

  EXPECT_EQ(vtp_array<double>(vtp, "rho"), ps.rho);
  EXPECT_EQ(vtp_array<double>(vtp, "p"), ps.p);
  EXPECT_EQ(vtp_array<std::uint64_t>(vtp, "id"), ps.id);
  EXPECT_EQ(vtp_array<std::uint8_t>(vtp, "level"), level);
  EXPECT_EQ(vtp_array<std::uint8_t>(vtp, "kind"), (std::vector<std::uint8_t>{0, 1, 2, 0}));
  EXPECT_EQ(vtp_array<std::int64_t>(vtp, "offsets"), (std::vector<std::int64_t>{1, 2, 3, 4}));
  const auto points = vtp_array<double>(vtp, "");
  ASSERT_EQ(points.size(), 12u);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    EXPECT_EQ(points[3 * i], ps.pos[i][0]);
    EXPECT_EQ(points[3 * i + 1], ps.pos[i][1]);
    EXPECT_EQ(points[3 * i + 2], 0.0);
  }
  const auto normal = vtp_array<double>(vtp, "normal");  // padded to 3 components in 2D
  EXPECT_EQ(normal, (std::vector<double>{1, 0, 0, 0, 1, 0, -1, 0, 0, 0.6, 0.8, 0}));
}

TEST(OutputVtp, ThreeDimensionalVelocity) {
  TempDir dir;
  const ParticleSet<3> ps = small_set_3d();
  write_vtp<3>(dir.path / "p.vtp", ps, {}, {});
  const std::string vtp = read_all(dir.path / "p.vtp");
  EXPECT_NE(vtp.find("NumberOfPoints=\"2\""), std::string::npos);
  EXPECT_EQ(vtp_array<double>(vtp, "velocity"), (std::vector<double>{1, 2, 2, 0, 0, 0}));
  EXPECT_EQ(vtp_array<std::uint8_t>(vtp, "level"), (std::vector<std::uint8_t>{0, 0}));
}

TEST(OutputSnapshot, NamesAndMergedLevels) {
  EXPECT_EQ(snapshot_file_name(7, "vtp"), "particles_0007.vtp");
  EXPECT_EQ(snapshot_file_name(12345, "csv"), "particles_12345.csv");
  EXPECT_EQ(line_file_name("diameter", 3), "line_diameter_0003.csv");
  const ParticleSet<3> a = small_set_3d();
  ParticleSet<3> b;
  b.push_back(9, Kind::buffer, {{1, 1, 1}}, {{0, 0, 0}}, 1.0, 2.0);
  b.p = {3.0};
  const ParticleSet<3>* levels[] = {&a, &b};
  const MergedLevels<3> m = merge_levels<3>(levels);
  EXPECT_EQ(m.particles.id, (std::vector<std::uint64_t>{1, 2, 9}));
  EXPECT_EQ(m.level, (std::vector<std::uint8_t>{0, 0, 1}));
  EXPECT_EQ(m.particles.p, (std::vector<double>{5, 6, 3}));
  EXPECT_EQ(m.particles.kind[2], Kind::buffer);
}

TEST(OutputPvd, TimeOrderReloadAndResume) {
  TempDir dir;
  const fs::path pvd_path = dir.path / "particles.pvd";
  PvdCollection pvd(pvd_path);
  pvd.add(0.0, "particles_0000.vtp");
  pvd.add(0.02, "particles_0002.vtp");
  pvd.add(0.01, "particles_0001.vtp");
  pvd.write();
  const std::string xml = read_all(pvd_path);
  EXPECT_NE(xml.find("<VTKFile type=\"Collection\""), std::string::npos);
  const std::size_t a =
      xml.find("timestep=\"0\" group=\"\" part=\"0\" file=\"particles_0000.vtp\"");
  const std::size_t b =
      xml.find("timestep=\"0.01\" group=\"\" part=\"0\" file=\"particles_0001.vtp\"");
  const std::size_t c =
      xml.find("timestep=\"0.02\" group=\"\" part=\"0\" file=\"particles_0002.vtp\"");
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(c, std::string::npos);
  EXPECT_LT(a, b);
  EXPECT_LT(b, c);

  // Reload and add: the old entries stay.
  PvdCollection again = PvdCollection::load(pvd_path);
  again.add(0.03, "particles_0003.vtp");
  again.write();
  const PvdCollection check = PvdCollection::load(pvd_path);
  ASSERT_EQ(check.entries().size(), 4u);
  EXPECT_EQ(check.entries()[1].time, 0.01);
  EXPECT_EQ(check.entries()[3].file, "particles_0003.vtp");

  // Resume from t = 0.01: later entries are dropped; re-adding a file name replaces it.
  PvdCollection resumed = PvdCollection::load(pvd_path, 0.01);
  ASSERT_EQ(resumed.entries().size(), 2u);
  resumed.add(0.01, "particles_0001.vtp");
  EXPECT_EQ(resumed.entries().size(), 2u);
  EXPECT_EQ(PvdCollection::load(dir.path / "missing.pvd").entries().size(), 0u);
}

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
  ps.p = {10, 20, 30, 40, 50, 60, 70, 80, 90};
  const std::vector<std::uint8_t> level{0, 0, 0, 1, 0, 0, 0, 0, 1};
  const Vec<2> from{{-1, 0}}, to{{1, 0}};
  const auto samples = sample_line<2>(ps, level, from, to, 0.1);
  std::vector<std::uint64_t> ids;
  for (const auto& q : samples) ids.push_back(q.id);
  EXPECT_EQ(ids, (std::vector<std::uint64_t>{2, 4, 1, 8}));
  EXPECT_NEAR(samples[0].s, 0.1, 1e-15);
  EXPECT_EQ(samples[1].level, 1);
  EXPECT_EQ(samples[1].p, 40.0);

  write_line_profile<2>(dir.path / "line.csv", ps, level, from, to, 0.1);
  const auto lines = lines_of(read_all(dir.path / "line.csv"));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "s,x,y,p,level");
  EXPECT_EQ(lines[2], "1,0,0,40,1");
  EXPECT_EQ(lines[4], "2,1,0,80,0");
  EXPECT_THROW(sample_line<2>(ps, {}, from, from, 0.1), std::invalid_argument);
}

TEST(OutputLine, ThreeDimensionalHeader) {
  TempDir dir;
  const ParticleSet<3> ps = small_set_3d();
  write_line_profile<3>(dir.path / "line.csv", ps, {}, Vec<3>{{0, 0, 0}}, Vec<3>{{0.2, 0.4, 0.6}},
                        1e-6);
  const auto lines = lines_of(read_all(dir.path / "line.csv"));
  ASSERT_EQ(lines.size(), 2u);  // only the fluid particle at (0.1, 0.2, 0.3) lies on the line
  EXPECT_EQ(lines[0], "s,x,y,z,p,level");
  EXPECT_TRUE(lines[1].ends_with(",0.1,0.2,0.3,5,0"));
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
