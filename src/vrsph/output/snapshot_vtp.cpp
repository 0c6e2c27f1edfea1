// VTK XML PolyData writer (.vtp) with appended raw binary data. Layout of the file:
//   XML header with one <DataArray format="appended" offset="..."/> per array, then
//   <AppendedData encoding="raw">_ followed by, for each array, a UInt64 byte count and the values
//   in native byte order (byte_order in the header says which).
#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/snapshot.hpp"
#include "vrsph/output/snapshot_detail.hpp"

namespace vrsph {
namespace {

// One data array: its XML attributes and its raw bytes.
struct VtpArray {
  std::string name;
  const char* type = "";  // VTK type name
  int components = 1;
  std::string bytes;
};

template <class T>
VtpArray make_array(std::string name, const char* type, int components, std::size_t count) {
  VtpArray a{std::move(name), type, components, {}};
  a.bytes.resize(count * sizeof(T));
  return a;
}

// Copies `value` into element `k` of the array's byte buffer.
template <class T>
void put(VtpArray& a, std::size_t k, T value) {
  std::memcpy(a.bytes.data() + k * sizeof(T), &value, sizeof(T));
}

// A vector quantity per particle padded to 3 components (z = 0 in 2D).
template <int D>
VtpArray vec3_array(std::string name, const std::vector<Vec<D>>& v) {
  VtpArray a = make_array<double>(std::move(name), "Float64", 3, 3 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) put(a, 3 * i + k, k < D ? v[i][k] : 0.0);
  return a;
}

VtpArray scalar_array(std::string name, const std::vector<double>& v) {
  VtpArray a = make_array<double>(std::move(name), "Float64", 1, v.size());
  std::memcpy(a.bytes.data(), v.data(), a.bytes.size());
  return a;
}

// An extra field; 2-component fields in 2D are padded to 3 so ParaView sees vectors.
template <int D>
VtpArray extra_array(const ExtraField& f, std::size_t n) {
  const int out_c = (D == 2 && f.components == 2) ? 3 : f.components;
  VtpArray a = make_array<double>(f.name, "Float64", out_c, n * out_c);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < out_c; ++c)
      put(a, i * out_c + c, c < f.components ? f.values[i * f.components + c] : 0.0);
  return a;
}

// Verts: vertex i is point i; offsets are the running end of each cell's connectivity.
void vert_arrays(std::size_t n, VtpArray& connectivity, VtpArray& offsets) {
  connectivity = make_array<std::int64_t>("connectivity", "Int64", 1, n);
  offsets = make_array<std::int64_t>("offsets", "Int64", 1, n);
  for (std::size_t i = 0; i < n; ++i) {
    put(connectivity, i, static_cast<std::int64_t>(i));
    put(offsets, i, static_cast<std::int64_t>(i + 1));
  }
}

// The PointData arrays in contract order: id, level, kind, velocity, rho, p, mass, extras.
template <int D>
std::vector<VtpArray> point_data(const ParticleSet<D>& ps, std::span<const ExtraField> extras,
                                 std::span<const std::uint8_t> level) {
  const std::size_t n = ps.size();
  std::vector<VtpArray> out;
  out.push_back(make_array<std::uint64_t>("id", "UInt64", 1, n));
  std::memcpy(out.back().bytes.data(), ps.id.data(), n * sizeof(std::uint64_t));
  out.push_back(make_array<std::uint8_t>("level", "UInt8", 1, n));
  if (!level.empty()) std::memcpy(out.back().bytes.data(), level.data(), n);
  out.push_back(make_array<std::uint8_t>("kind", "UInt8", 1, n));
  for (std::size_t i = 0; i < n; ++i) put(out.back(), i, static_cast<std::uint8_t>(ps.kind[i]));
  out.push_back(vec3_array<D>("velocity", ps.vel));
  out.push_back(scalar_array("rho", ps.rho));
  out.push_back(scalar_array("p", ps.p));
  out.push_back(scalar_array("mass", ps.mass));
  for (const ExtraField& f : extras) out.push_back(extra_array<D>(f, n));
  return out;
}

// The <DataArray .../> tag of `a`, whose data starts at `offset` in the appended block.
std::string array_tag(const VtpArray& a, std::uint64_t offset) {
  return fmt::format(
      "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
      "offset=\"{}\"/>\n",
      a.type, xml_escape(a.name), a.components, offset);
}

// Writes the header, the appended block and the closing tags. Arrays are listed in the order
// points, point data, connectivity, offsets, and their data follows in that same order.
void write_vtp_file(const std::filesystem::path& path, std::size_t n, const VtpArray& points,
                    const std::vector<VtpArray>& data, const VtpArray& conn, const VtpArray& offs) {
  std::uint64_t offset = 0;
  auto tag = [&offset](const VtpArray& a) {
    std::string t = array_tag(a, offset);
    offset += sizeof(std::uint64_t) + a.bytes.size();
    return t;
  };
  const char* order = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
  std::string head = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"{}\" header_type=\"UInt64\">\n"
      "  <PolyData>\n"
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
      "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
      order, n, n);
  head += "      <Points>\n";
  head += tag(points);
  head += "      </Points>\n      <PointData>\n";
  for (const VtpArray& a : data) head += tag(a);
  head += "      </PointData>\n      <Verts>\n";
  head += tag(conn);  // separate statements: tag() advances the offset, order matters
  head += tag(offs);
  head += "      </Verts>\n";
  head += "    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";

  AtomicWriter w(path);
  std::ostream& os = w.stream();
  os.write(head.data(), static_cast<std::streamsize>(head.size()));
  auto block = [&os](const VtpArray& a) {
    const std::uint64_t nbytes = a.bytes.size();
    os.write(reinterpret_cast<const char*>(&nbytes), sizeof(nbytes));
    os.write(a.bytes.data(), static_cast<std::streamsize>(a.bytes.size()));
  };
  block(points);
  for (const VtpArray& a : data) block(a);
  block(conn);
  block(offs);
  os << "\n  </AppendedData>\n</VTKFile>\n";
  w.commit();
}

}  // namespace

template <int D>
void write_vtp(const std::filesystem::path& path, const ParticleSet<D>& ps,
               std::span<const ExtraField> extras, std::span<const std::uint8_t> level) {
  check_snapshot_inputs(ps.size(), extras, level, ps.p.size());
  const VtpArray points = vec3_array<D>("Points", ps.pos);
  const std::vector<VtpArray> data = point_data(ps, extras, level);
  VtpArray conn, offs;
  vert_arrays(ps.size(), conn, offs);
  write_vtp_file(path, ps.size(), points, data, conn, offs);
}

template void write_vtp<2>(const std::filesystem::path&, const ParticleSet<2>&,
                           std::span<const ExtraField>, std::span<const std::uint8_t>);
template void write_vtp<3>(const std::filesystem::path&, const ParticleSet<3>&,
                           std::span<const ExtraField>, std::span<const std::uint8_t>);

}  // namespace vrsph
