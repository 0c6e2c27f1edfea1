// Loads a shipped case (cases/NAME) with --set style overrides, for tests that drive the library.
#pragma once

#include <string>
#include <vector>

#include "vrsph/setup/case_parser.hpp"

namespace vrsph::test {

inline CaseSpec load_case(const std::string& name, const std::vector<std::string>& sets) {
  toml::table tbl = load_case_table(std::string(VRSPH_CASES_DIR) + "/" + name);
  for (const auto& s : sets) apply_override(tbl, s);
  return parse_case(tbl, name);
}

// Overrides that give cases/droplet_2d.toml the start and model it shipped with until issue #20
// (item 5) made rings at the Laplace pressure with three options its default: the lattice from
// rest, with the Cen et al. 2024 model alone. For the tests that study that start; `more` after.
inline std::vector<std::string> droplet_lattice_cen_alone(std::vector<std::string> more = {}) {
  std::vector<std::string> sets = {"fluid_block.0.fill=\"lattice\"", "fluid_block.0.pressure=0",
                                   "numerics.surface_tension.surface_offset=false",
                                   "numerics.surface_tension.curvature_correction=false",
                                   "numerics.surface_tension.zero_net_force=false"};
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

}  // namespace vrsph::test
