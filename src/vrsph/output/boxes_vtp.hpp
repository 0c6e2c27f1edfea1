// refinement_boxes.vtp: the outlines of the variable-resolution regions for ParaView (VTK XML
// PolyData, ASCII): per refinement box its fluid box, the outer edge of the child's buffer and
// the inner edge of the parent's buffer, as line cells with `level` and `role` cell data
// (role 0: refinement box, 1: child buffer outer edge, 2: parent buffer inner edge).
#pragma once

#include <array>
#include <filesystem>
#include <vector>

namespace vrsph {

struct OutlineBox {
  std::array<double, 3> lo{}, hi{};
  int level = 0;  // the level whose region the outline bounds
  int role = 0;
};

void write_boxes_vtp(const std::filesystem::path& path, const std::vector<OutlineBox>& boxes,
                     int dimension);

}  // namespace vrsph
