// Internal to the case-file layer: the checks of a parsed case that look at its geometry as a
// whole, run by parse_case() once every table is read, so that nothing the fill would drop or
// duplicate passes silently (CONTRACT.md "Refused at set-up"):
//  - every fluid block holds particles at resolution.dp;
//  - with [domain], every fluid and wall block lies inside it (the particles outside would be
//    dropped at the first sort);
//  - fluid blocks do not overlap (their particles would lie on top of each other);
//  - walls are at least as thick as the kernel support 2h (layers x dp >= 2h);
//  - without [domain], refinement boxes lie inside the default domain.
// Each error is a CaseError naming the key of the block at fault (file:line, value, reason).
#pragma once

#include <span>

#include "vrsph/setup/case_reader.hpp"

namespace vrsph::case_detail {

// The readers of the tables a case's geometry comes from (element i of each span is block i).
struct GeometryReaders {
  std::span<const TableReader> fluid;
  std::span<const TableReader> wall;
  std::span<const TableReader> refinement;
};

void check_geometry(const GeometryReaders& r, const CaseSpec& spec);

}  // namespace vrsph::case_detail
