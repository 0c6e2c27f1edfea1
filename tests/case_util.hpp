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

}  // namespace vrsph::test
