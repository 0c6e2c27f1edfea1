// Output layer, particle files: particle CSV and VTP snapshots (their arrays decoded), snapshot
// names and merged levels, the .pvd collection with reload and resume.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "output_fixtures.hpp"
#include "vrsph/output/line_profile.hpp"
#include "vrsph/output/snapshot.hpp"

namespace fs = std::filesystem;
using namespace vrsph;
using namespace vrsph::output_fixtures;

TEST(OutputCsv, HeaderAndValuesRoundTrip2D) {
  TempDir dir;
  const ParticleSet<2> ps = small_set_2d();
  std::vector<ExtraField> extras{{"lambda", 1, {0.9, 1.0, 0.5, 1.0 / 3.0}},
                                 {"normal", 2, {1, 0, 0, 1, -1, 0, 0.6, 0.8}}};
  const std::vector<std::uint8_t> level{0, 0, 1, 1};
  write_particles_csv<2>(dir.path / "p.csv", ps, kEos, extras, level);
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
    EXPECT_EQ(std::stod(f[8]), kEos.pressure(ps.rho[i]));
    EXPECT_EQ(std::stod(f[9]), ps.mass_of(i));
    EXPECT_EQ(std::stod(f[10]), extras[0].values[i]);
    EXPECT_EQ(std::stod(f[11]), extras[1].values[2 * i]);
    EXPECT_EQ(std::stod(f[12]), extras[1].values[2 * i + 1]);
  }
}

TEST(OutputCsv, Header3DAndDefaultLevel) {
  TempDir dir;
  std::vector<ExtraField> extras{{"normal", 3, {1, 0, 0, 0, 0, 1}}};
  write_particles_csv<3>(dir.path / "p.csv", small_set_3d(), kEos, extras, {});
  const auto lines = lines_of(read_all(dir.path / "p.csv"));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "id,level,kind,x,y,z,vx,vy,vz,rho,p,mass,normal_x,normal_y,normal_z");
  EXPECT_EQ(lines[2], "2,0,wall,-0.1,0.2,-0.3,0,0,0,1000,0,1e-09,0,0,1");
}

TEST(OutputCsv, RejectsBadSizes) {
  TempDir dir;
  std::vector<ExtraField> bad{{"lambda", 1, {1.0}}};
  EXPECT_THROW(write_particles_csv<2>(dir.path / "p.csv", small_set_2d(), kEos, bad, {}),
               std::invalid_argument);
  const std::vector<std::uint8_t> level{0};
  EXPECT_THROW(write_vtp<2>(dir.path / "p.vtp", small_set_2d(), kEos, {}, level),
               std::invalid_argument);
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
  write_vtp<2>(dir.path / "p.vtp", ps, kEos, extras, level);
  const std::string vtp = read_all(dir.path / "p.vtp");
  EXPECT_NE(vtp.find("<VTKFile type=\"PolyData\""), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfPoints=\"4\""), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfVerts=\"4\""), std::string::npos);
  for (const char* name :
       {"id", "level", "kind", "velocity", "rho", "p", "mass", "normal", "connectivity", "offsets"})
    EXPECT_NE(vtp.find("Name=\"" + std::string(name) + "\""), std::string::npos) << name;
  EXPECT_TRUE(vtp.ends_with("</AppendedData>\n</VTKFile>\n"));

  EXPECT_EQ(vtp_array<double>(vtp, "rho"), ps.rho);
  EXPECT_EQ(vtp_array<double>(vtp, "p"), pressures(ps));
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
  write_vtp<3>(dir.path / "p.vtp", ps, kEos, {}, {});
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
  const ParticleSet<3>* levels[] = {&a, &b};
  const MergedLevels<3> m = merge_levels<3>(levels);
  EXPECT_EQ(m.particles.id, (std::vector<std::uint64_t>{1, 2, 9}));
  EXPECT_EQ(m.level, (std::vector<std::uint8_t>{0, 0, 1}));
  EXPECT_EQ(m.particles.rho, (std::vector<double>{1000, 1000, 1}));
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
