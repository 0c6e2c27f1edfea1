// Output layer, snapshot size options (output.precision, output.compression; docs/outputs.md):
// float32 and zlib-compressed .vtp files read back by a small reader of their own (the XML
// header's DataArray tags, then the appended block raw or decompressed with zlib), against the
// double, uncompressed file; the float32 CSV; and the VTK block header of vtk_zlib_compress.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "output_fixtures.hpp"
#include "vrsph/output/snapshot.hpp"
#include "vrsph/output/vtk_zlib.hpp"

namespace {

using namespace vrsph;
using namespace vrsph::output_fixtures;

// One DataArray of a .vtp: its attributes and its decoded bytes.
struct VtpData {
  std::string type;
  int components = 0;
  std::string bytes;
};

// The value of attribute `name` in the tag text `tag` ("" when absent).
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

std::uint64_t u64_at(const std::string& s, std::size_t pos) {
  std::uint64_t v = 0;
  EXPECT_LE(pos + sizeof(v), s.size());
  if (pos + sizeof(v) <= s.size()) std::memcpy(&v, s.data() + pos, sizeof(v));
  return v;
}

// Decompresses one VTK zlib array (vtk_zlib.hpp) that starts at `pos`.
std::string inflate_vtk(const std::string& file, std::size_t pos) {
  const std::uint64_t n_blocks = u64_at(file, pos);
  const std::uint64_t block = u64_at(file, pos + 8);
  const std::uint64_t last = u64_at(file, pos + 16);
  std::size_t data = pos + 24 + 8 * n_blocks;
  std::string out;
  for (std::uint64_t b = 0; b < n_blocks; ++b) {
    const std::uint64_t packed = u64_at(file, pos + 24 + 8 * b);
    uLongf size = (b + 1 == n_blocks && last != 0) ? last : block;
    std::string buf(size, '\0');
    const int rc = uncompress(reinterpret_cast<Bytef*>(buf.data()), &size,
                              reinterpret_cast<const Bytef*>(file.data() + data), packed);
    EXPECT_EQ(rc, Z_OK) << "block " << b;
    EXPECT_EQ(size, buf.size()) << "block " << b;
    out += buf;
    data += packed;
  }
  return out;
}

// Every DataArray of a .vtp by name ("Points" for the positions), decoded.
std::map<std::string, VtpData> read_vtp(const std::string& file) {
  const bool zlib =
      attribute(file.substr(0, file.find("<PolyData")), "compressor") == "vtkZLibDataCompressor";
  const std::size_t base = file.find('_', file.find("<AppendedData encoding=\"raw\">")) + 1;
  std::map<std::string, VtpData> arrays;
  for (std::size_t at = file.find("<DataArray"); at < base; at = file.find("<DataArray", at + 1)) {
    const std::string tag = file.substr(at, file.find("/>", at) - at);
    VtpData d{attribute(tag, "type"), std::stoi(attribute(tag, "NumberOfComponents")), {}};
    const std::size_t pos = base + std::stoull(attribute(tag, "offset"));
    d.bytes = zlib ? inflate_vtk(file, pos) : file.substr(pos + 8, u64_at(file, pos));
    arrays[attribute(tag, "Name")] = d;
  }
  return arrays;
}

template <class T>
std::vector<T> values_of(const VtpData& d) {
  std::vector<T> v(d.bytes.size() / sizeof(T));
  std::memcpy(v.data(), d.bytes.data(), v.size() * sizeof(T));
  return v;
}

// The particle fields, the ones float32 changes.
const char* const kFields[] = {"velocity", "rho", "p", "mass", "lambda", "normal"};

std::vector<ExtraField> extras_2d() {
  return {{"lambda", 1, {0.9, 1.0, 0.5, 1.0 / 3.0}}, {"normal", 2, {1, 0, 0, 1, -1, 0, 0.6, 0.8}}};
}

std::map<std::string, VtpData> write_and_read(const ParticleSet<2>& ps, SnapshotFormat format) {
  TempDir dir;
  const std::vector<ExtraField> extras = extras_2d();
  const std::vector<std::uint8_t> level{0, 0, 1, 1};
  write_vtp<2>(dir.path / "p.vtp", ps, kEos, extras, level, format);
  return read_vtp(read_all(dir.path / "p.vtp"));
}

TEST(OutputFormat, Float32VtpMatchesDoubleToFloatPrecision) {
  const ParticleSet<2> ps = small_set_2d();
  const auto wide = write_and_read(ps, {});
  const auto narrow = write_and_read(ps, {.float32 = true});
  ASSERT_EQ(wide.size(), narrow.size());
  for (const char* name : kFields) {
    ASSERT_TRUE(narrow.count(name)) << name;
    EXPECT_EQ(wide.at(name).type, "Float64") << name;
    EXPECT_EQ(narrow.at(name).type, "Float32") << name;
    EXPECT_EQ(narrow.at(name).components, wide.at(name).components) << name;
    const std::vector<double> d = values_of<double>(wide.at(name));
    const std::vector<float> f = values_of<float>(narrow.at(name));
    ASSERT_EQ(f.size(), d.size()) << name;
    for (std::size_t k = 0; k < d.size(); ++k) EXPECT_EQ(f[k], static_cast<float>(d[k])) << name;
  }
  EXPECT_NE(values_of<double>(wide.at("rho"))[0], values_of<float>(narrow.at("rho"))[0]);
  // Positions, ids, levels, kinds and the cells are written as without the option.
  for (const char* name : {"Points", "id", "level", "kind", "connectivity", "offsets"}) {
    EXPECT_EQ(narrow.at(name).type, wide.at(name).type) << name;
    EXPECT_EQ(narrow.at(name).bytes, wide.at(name).bytes) << name;
  }
  EXPECT_EQ(narrow.at("Points").type, "Float64");
  EXPECT_EQ(values_of<double>(narrow.at("Points"))[1], ps.pos[0][1]);
}

TEST(OutputFormat, ZlibVtpDecompressesToTheSameBytes) {
  const ParticleSet<2> ps = small_set_2d();
  for (const bool float32 : {false, true}) {
    const auto plain = write_and_read(ps, {.float32 = float32});
    const auto packed = write_and_read(ps, {.float32 = float32, .zlib = true});
    ASSERT_EQ(packed.size(), plain.size());
    for (const auto& [name, d] : plain) {
      ASSERT_TRUE(packed.count(name)) << name;
      EXPECT_EQ(packed.at(name).type, d.type) << name;
      EXPECT_EQ(packed.at(name).bytes, d.bytes) << name << (float32 ? " (float32)" : "");
    }
  }
}

// A set large enough that each array spans several 32 KiB blocks, the last one partial.
TEST(OutputFormat, ZlibManyBlocksAndTheHeaderVtkReads) {
  ParticleSet<2> ps;
  const std::size_t n = 10000;
  for (std::size_t i = 0; i < n; ++i)
    ps.push_back(i, Kind::fluid, {{0.001 * i, 1.0 / (i + 1.0)}}, {{std::sin(i * 1.0), 0.0}},
                 1000.0 + 1e-3 * i, 1e-6);
  TempDir dir;
  write_vtp<2>(dir.path / "plain.vtp", ps, kEos, {}, {});
  write_vtp<2>(dir.path / "zlib.vtp", ps, kEos, {}, {}, {.zlib = true});
  const std::string plain = read_all(dir.path / "plain.vtp");
  const std::string packed = read_all(dir.path / "zlib.vtp");
  EXPECT_NE(packed.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  EXPECT_EQ(plain.find("compressor="), std::string::npos);
  EXPECT_LT(packed.size(), plain.size());
  const auto a = read_vtp(plain);
  const auto b = read_vtp(packed);
  EXPECT_EQ(b.at("rho").bytes.size(), 8 * n);
  for (const auto& [name, d] : a) EXPECT_EQ(b.at(name).bytes, d.bytes) << name;
  // The header of 80000 bytes: 3 blocks, 32768 each, a last block of 14464.
  const std::string rho(reinterpret_cast<const char*>(ps.rho.data()), 8 * n);
  const std::string z = vtk_zlib_compress(rho);
  EXPECT_EQ(u64_at(z, 0), 3u);
  EXPECT_EQ(u64_at(z, 8), kVtkBlockSize);
  EXPECT_EQ(u64_at(z, 16), 80000u - 2 * kVtkBlockSize);
  EXPECT_EQ(z.size(), 48 + u64_at(z, 24) + u64_at(z, 32) + u64_at(z, 40));
  // Exactly whole blocks: the last size is 0 (VTK reads the last block as a full one).
  const std::string two(2 * kVtkBlockSize, 'x');
  EXPECT_EQ(u64_at(vtk_zlib_compress(two), 0), 2u);
  EXPECT_EQ(u64_at(vtk_zlib_compress(two), 16), 0u);
  EXPECT_EQ(inflate_vtk(vtk_zlib_compress(two), 0), two);
  EXPECT_EQ(u64_at(vtk_zlib_compress(""), 0), 0u);
}

TEST(OutputFormat, Float32CsvHasFloatDigitsAndDoublePositions) {
  TempDir dir;
  const ParticleSet<2> ps = small_set_2d();
  const std::vector<ExtraField> extras = extras_2d();
  write_particles_csv<2>(dir.path / "d.csv", ps, kEos, extras, {});
  write_particles_csv<2>(dir.path / "f.csv", ps, kEos, extras, {}, {.float32 = true, .zlib = true});
  const auto wide = lines_of(read_all(dir.path / "d.csv"));
  const auto narrow = lines_of(read_all(dir.path / "f.csv"));
  ASSERT_EQ(narrow.size(), wide.size());
  EXPECT_EQ(narrow[0], wide[0]);
  EXPECT_LT(read_all(dir.path / "f.csv").size(), read_all(dir.path / "d.csv").size());
  for (std::size_t i = 1; i < wide.size(); ++i) {
    const auto d = split_csv(wide[i]);
    const auto f = split_csv(narrow[i]);
    ASSERT_EQ(f.size(), d.size());
    for (std::size_t c = 0; c < 5; ++c) EXPECT_EQ(f[c], d[c]) << "id, level, kind, x, y";
    for (std::size_t c = 5; c < d.size(); ++c) {
      EXPECT_EQ(std::stof(f[c]), static_cast<float>(std::stod(d[c]))) << narrow[i];
      EXPECT_LE(f[c].size(), d[c].size()) << narrow[i];
    }
  }
  EXPECT_EQ(split_csv(narrow[1])[4], "0.3333333333333333");  // y stays double
  EXPECT_EQ(split_csv(narrow[1])[7], "1000");                // rho 1000.0000001 as float
  EXPECT_EQ(split_csv(narrow[1])[10], "0.9");                // lambda
  EXPECT_EQ(split_csv(narrow[4])[10], "0.33333334");         // lambda 1/3 as float
}

}  // namespace
