// docs/cases.md against the parser: every key the parser knows (known_case_keys(), the schema of
// setup/case_schema.hpp) has its row in a key table of the page, every row names a known key,
// and every value of an enum key appears, quoted, in its row. A key added to the parser without
// its documentation fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "vrsph/setup/case_parser.hpp"
#include "vrsph/setup/case_reader.hpp"
#include "vrsph/setup/case_schema.hpp"

namespace vrsph {
namespace {

const std::string kCasesDoc = std::string(VRSPH_DOCS_DIR) + "/cases.md";

// The key tables' rows: "| `dotted.key` | ..." -> the whole row, by key. Only first cells that
// hold a dotted name count (a top-level table's own row would read `[case]`, not a key).
std::map<std::string, std::string> documented_rows(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot open " << path;
  std::map<std::string, std::string> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.starts_with("| `")) continue;
    const std::size_t end = line.find('`', 3);
    if (end == std::string::npos) continue;
    const std::string key = line.substr(3, end - 3);
    if (key.find('.') == std::string::npos || key.find(' ') != std::string::npos) continue;
    rows[key] = line;
  }
  return rows;
}

TEST(CaseDocs, KnownKeysAreDottedPathsOfTheSchema) {
  const std::vector<std::string> keys = known_case_keys();
  const std::set<std::string> unique(keys.begin(), keys.end());
  EXPECT_EQ(unique.size(), keys.size()) << "a key is listed twice";
  // Spot checks of the three forms: plain table, nested model table, arrays of tables.
  for (const char* k :
       {"case.name", "resolution.dp", "numerics.cfl", "numerics.viscosity.model",
        "numerics.surface_tension.zero_net_force", "fluid_block.N.radius", "wall_block.N.layers",
        "refinement.N.buffer_width", "output.line.N.name", "analysis.laplace_pressure"}) {
    EXPECT_EQ(unique.count(k), 1u) << k;
  }
  // Tables are not leaves.
  for (const char* k : {"numerics", "numerics.viscosity", "output.line", "output.line.N"}) {
    EXPECT_EQ(unique.count(k), 0u) << k;
  }
  std::size_t leaves = 0;
  for (const auto& t : case_detail::kCaseSchema) leaves += t.keys.size();
  EXPECT_EQ(keys.size(), leaves - (std::size(case_detail::kCaseSchema) - 1))
      << "every table but the root is a key of its parent";
}

// Every table of the schema is reachable: its last segment is a key of its parent table.
TEST(CaseDocs, EverySchemaTableIsAKeyOfItsParent) {
  for (const auto& t : case_detail::kCaseSchema) {
    if (t.path.empty()) continue;
    const std::size_t dot = t.path.rfind('.');
    const std::string_view parent = dot == std::string_view::npos ? "" : t.path.substr(0, dot);
    const std::string_view last = dot == std::string_view::npos ? t.path : t.path.substr(dot + 1);
    const auto* p =
        std::find_if(std::begin(case_detail::kCaseSchema), std::end(case_detail::kCaseSchema),
                     [&](const auto& s) { return s.path == parent; });
    ASSERT_NE(p, std::end(case_detail::kCaseSchema)) << t.path;
    EXPECT_NE(std::find(p->keys.begin(), p->keys.end(), last), p->keys.end()) << t.path;
  }
}

TEST(CaseDocs, EveryKnownKeyHasItsRowInCasesMd) {
  const auto rows = documented_rows(kCasesDoc);
  ASSERT_FALSE(rows.empty()) << kCasesDoc << " has no key rows";
  for (const std::string& k : known_case_keys()) {
    EXPECT_EQ(rows.count(k), 1u) << "docs/cases.md does not describe `" << k << "` (add a row \"| `"
                                 << k << "` | type | unit | default | "
                                 << "allowed | meaning |\")";
  }
}

TEST(CaseDocs, EveryRowOfCasesMdNamesAKnownKey) {
  const std::vector<std::string> keys = known_case_keys();
  const std::set<std::string> known(keys.begin(), keys.end());
  for (const auto& [key, row] : documented_rows(kCasesDoc)) {
    EXPECT_EQ(known.count(key), 1u)
        << "docs/cases.md describes `" << key << "`, which the parser does not know";
  }
}

// The names of one enum key, as the parser accepts them.
template <class E, std::size_t N>
std::vector<std::string> names_of(const case_detail::EnumName<E> (&names)[N]) {
  std::vector<std::string> out;
  for (const auto& n : names) out.emplace_back(n.name);
  return out;
}

TEST(CaseDocs, EveryEnumValueIsInItsRow) {
  using namespace case_detail;
  const std::map<std::string, std::vector<std::string>> enums = {
      {"numerics.viscosity.model", names_of(kViscosityNames)},
      {"numerics.density_diffusion.model", names_of(kDiffusionNames)},
      {"numerics.shifting.model", names_of(kShiftingNames)},
      {"fluid_block.N.shape", names_of(kBlockShapeNames)},
      {"fluid_block.N.fill", names_of(kFillNames)},
      {"wall_block.N.shape", names_of(kWallShapeNames)},
      {"output.precision", names_of(kPrecisionNames)},
      {"output.compression", names_of(kCompressionNames)},
  };
  const auto rows = documented_rows(kCasesDoc);
  for (const auto& [key, values] : enums) {
    const auto it = rows.find(key);
    ASSERT_NE(it, rows.end()) << key;
    for (const std::string& v : values) {
      EXPECT_NE(it->second.find("\"" + v + "\""), std::string::npos)
          << "the row of `" << key << "` does not list \"" << v << "\"";
    }
  }
}

// The check itself can fail: a page without one key's row is caught.
TEST(CaseDocs, AMissingRowIsDetected) {
  std::ifstream in(kCasesDoc);
  std::stringstream text;
  text << in.rdbuf();
  std::string cut;
  std::istringstream lines(text.str());
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.starts_with("| `numerics.cfl`")) cut += line + "\n";
  }
  const std::string tmp = ::testing::TempDir() + "cases_without_cfl.md";
  std::ofstream(tmp) << cut;
  const auto rows = documented_rows(tmp);
  EXPECT_EQ(rows.count("numerics.cfl"), 0u);
  EXPECT_EQ(rows.count("resolution.dp"), 1u);
}

}  // namespace
}  // namespace vrsph
