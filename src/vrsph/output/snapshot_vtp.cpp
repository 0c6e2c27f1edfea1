// VTK XML PolyData writer (.vtp) with appended raw binary data. Layout of the file:
//   XML header with one <DataArray format="appended" offset="..."/> per array, then
//   <AppendedData encoding="raw">_ followed by, for each array, a UInt64 byte count and the values
//   in native byte order (byte_order in the header says which); with zlib compression
//   (compressor="vtkZLibDataCompressor" in the header) each array is the block header and zlib
//   streams of vtk_zlib.hpp instead. With float32 the particle fields are Float32; Points stay
//   Float64.
#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/snapshot.hpp"
#include "vrsph/output/snapshot_detail.hpp"
#include "vrsph/output/vtk_zlib.hpp"

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

// The VTK name of a floating-point element type.
template <class Real>
constexpr const char* real_type() {
  return sizeof(Real) == 8 ? "Float64" : "Float32";
}

// A vector quantity per particle padded to 3 components (z = 0 in 2D), stored as Real.
template <class Real, int D>
VtpArray vec3_array(std::string name, const std::vector<Vec<D>>& v) {
  VtpArray a = make_array<Real>(std::move(name), real_type<Real>(), 3, 3 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) put(a, 3 * i + k, static_cast<Real>(k < D ? v[i][k] : 0.0));
  return a;
}

template <class Real>
VtpArray scalar_array(std::string name, const std::vector<double>& v) {
  VtpArray a = make_array<Real>(std::move(name), real_type<Real>(), 1, v.size());
  for (std::size_t i = 0; i < v.size(); ++i) put(a, i, static_cast<Real>(v[i]));
  return a;
}

// An extra field; 2-component fields in 2D are padded to 3 so ParaView sees vectors.
template <class Real, int D>
VtpArray extra_array(const ExtraField& f, std::size_t n) {
  const int out_c = (D == 2 && f.components == 2) ? 3 : f.components;
  VtpArray a = make_array<Real>(f.name, real_type<Real>(), out_c, n * out_c);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < out_c; ++c)
      put(a, i * out_c + c,
          static_cast<Real>(c < f.components ? f.values[i * f.components + c] : 0.0));
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

// The PointData arrays in contract order: id, level, kind, velocity, rho, p, mass, extras; the
// fields after kind stored as Real.
template <class Real, int D>
std::vector<VtpArray> point_data(const ParticleSet<D>& ps, const TaitEos& eos,
                                 std::span<const ExtraField> extras,
                                 std::span<const std::uint8_t> level) {
  const std::size_t n = ps.size();
  std::vector<VtpArray> out;
  out.push_back(make_array<std::uint64_t>("id", "UInt64", 1, n));
  std::memcpy(out.back().bytes.data(), ps.id.data(), n * sizeof(std::uint64_t));
  out.push_back(make_array<std::uint8_t>("level", "UInt8", 1, n));
  if (!level.empty()) std::memcpy(out.back().bytes.data(), level.data(), n);
  out.push_back(make_array<std::uint8_t>("kind", "UInt8", 1, n));
  for (std::size_t i = 0; i < n; ++i) put(out.back(), i, static_cast<std::uint8_t>(ps.kind[i]));
  out.push_back(vec3_array<Real, D>("velocity", ps.vel));
  out.push_back(scalar_array<Real>("rho", ps.rho));
  out.push_back(make_array<Real>("p", real_type<Real>(), 1, n));
  for (std::size_t i = 0; i < n; ++i)
    put(out.back(), i, static_cast<Real>(eos.pressure(ps.rho[i])));
  out.push_back(scalar_array<Real>("mass", ps.masses()));
  for (const ExtraField& f : extras) out.push_back(extra_array<Real, D>(f, n));
  return out;
}

// The <DataArray .../> tag of `a`, whose data starts at `offset` in the appended block.
std::string array_tag(const VtpArray& a, std::uint64_t offset) {
  return fmt::format(
      "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
      "offset=\"{}\"/>\n",
      a.type, xml_escape(a.name), a.components, offset);
}

// The array's data as it goes into the appended block: a UInt64 byte count and the bytes, or
// with zlib the compression header and the compressed blocks.
std::string appended_block(const VtpArray& a, bool zlib) {
  if (zlib) return vtk_zlib_compress(a.bytes);
  const std::uint64_t nbytes = a.bytes.size();
  std::string out(sizeof(nbytes), '\0');
  std::memcpy(out.data(), &nbytes, sizeof(nbytes));
  return out + a.bytes;
}

// The arrays of one file in the order of the file: Points, the point data, connectivity, offsets.
struct VtpArrays {
  VtpArray points;
  std::vector<VtpArray> data;
  VtpArray conn, offs;
};

// Writes the header, the appended block and the closing tags. Arrays are listed in the order
// points, point data, connectivity, offsets, and their data follows in that same order.
void write_vtp_file(const std::filesystem::path& path, std::size_t n, const VtpArrays& arrays,
                    bool zlib) {
  std::uint64_t offset = 0;
  std::string blocks;
  auto tag = [&](const VtpArray& a) {
    std::string t = array_tag(a, offset);
    blocks += appended_block(a, zlib);
    offset = blocks.size();
    return t;
  };
  const char* order = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
  std::string head = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"{}\" header_type=\"UInt64\"{}>\n"
      "  <PolyData>\n"
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
      "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
      order, zlib ? " compressor=\"vtkZLibDataCompressor\"" : "", n, n);
  head += "      <Points>\n";
  head += tag(arrays.points);
  head += "      </Points>\n      <PointData>\n";
  for (const VtpArray& a : arrays.data) head += tag(a);
  head += "      </PointData>\n      <Verts>\n";
  head += tag(arrays.conn);  // separate statements: tag() advances the offset, order matters
  head += tag(arrays.offs);
  head += "      </Verts>\n";
  head += "    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";

  AtomicWriter w(path);
  std::ostream& os = w.stream();
  os.write(head.data(), static_cast<std::streamsize>(head.size()));
  os.write(blocks.data(), static_cast<std::streamsize>(blocks.size()));
  os << "\n  </AppendedData>\n</VTKFile>\n";
  w.commit();
}

}  // namespace

template <int D>
void write_vtp(const std::filesystem::path& path, const ParticleSet<D>& ps, const TaitEos& eos,
               std::span<const ExtraField> extras, std::span<const std::uint8_t> level,
               SnapshotFormat format) {
  check_snapshot_inputs(ps.size(), extras, level);
  VtpArrays arrays;
  arrays.points = vec3_array<double, D>("Points", ps.pos);
  arrays.data = format.float32 ? point_data<float, D>(ps, eos, extras, level)
                               : point_data<double, D>(ps, eos, extras, level);
  vert_arrays(ps.size(), arrays.conn, arrays.offs);
  write_vtp_file(path, ps.size(), arrays, format.zlib);
}

template void write_vtp<2>(const std::filesystem::path&, const ParticleSet<2>&, const TaitEos&,
                           std::span<const ExtraField>, std::span<const std::uint8_t>,
                           SnapshotFormat);
template void write_vtp<3>(const std::filesystem::path&, const ParticleSet<3>&, const TaitEos&,
                           std::span<const ExtraField>, std::span<const std::uint8_t>,
                           SnapshotFormat);

}  // namespace vrsph
