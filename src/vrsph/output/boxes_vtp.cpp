#include "vrsph/output/boxes_vtp.hpp"

#include <fmt/format.h>

#include "vrsph/output/atomic_file.hpp"

namespace vrsph {

void write_boxes_vtp(const std::filesystem::path& path, const std::vector<OutlineBox>& boxes,
                     int dimension) {
  std::string pts, conn, offs, level, role;
  int np = 0, nl = 0, off = 0;
  auto line = [&](int a, int b, const OutlineBox& o) {
    conn += fmt::format("{} {} ", a, b);
    off += 2;
    offs += fmt::format("{} ", off);
    level += fmt::format("{} ", o.level);
    role += fmt::format("{} ", o.role);
    ++nl;
  };
  for (const OutlineBox& o : boxes) {
    const int corners = dimension == 2 ? 4 : 8;
    for (int c = 0; c < corners; ++c) {  // bit 0: x, bit 1: y, bit 2: z (2D: counter-clockwise)
      const int bx = dimension == 2 ? ((c == 1 || c == 2) ? 1 : 0) : (c & 1);
      const int by = dimension == 2 ? (c >= 2 ? 1 : 0) : ((c >> 1) & 1);
      const int bz = dimension == 2 ? 0 : ((c >> 2) & 1);
      pts += fmt::format("{} {} {} ", bx ? o.hi[0] : o.lo[0], by ? o.hi[1] : o.lo[1],
                         dimension == 2 ? 0.0 : (bz ? o.hi[2] : o.lo[2]));
    }
    if (dimension == 2) {
      for (int c = 0; c < 4; ++c) line(np + c, np + (c + 1) % 4, o);
    } else {
      for (int c = 0; c < 8; ++c)
        for (int bit = 0; bit < 3; ++bit)
          if (!(c & (1 << bit))) line(np + c, np + (c | (1 << bit)), o);
    }
    np += corners;
  }
  const std::string xml = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "<PolyData><Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
      "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">{}"
      "</DataArray></Points>\n"
      "<Lines><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">{}</DataArray>\n"
      "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">{}</DataArray></Lines>\n"
      "<CellData><DataArray type=\"Int32\" Name=\"level\" format=\"ascii\">{}</DataArray>\n"
      "<DataArray type=\"Int32\" Name=\"role\" format=\"ascii\">{}</DataArray></CellData>\n"
      "</Piece></PolyData></VTKFile>\n",
      np, nl, pts, conn, offs, level, role);
  write_file_atomic(path, xml);
}

}  // namespace vrsph
