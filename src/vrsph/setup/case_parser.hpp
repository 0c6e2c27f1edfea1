// The case-file layer: TOML case file (+ --set overrides) -> validated CaseSpec, and back.
// docs/cases.md describes every key, its default and its checks.
//
// Typical use (the `vrsph` command):
//   toml::table tbl = load_case_table(path);
//   for (const auto& s : sets) apply_override(tbl, s);
//   CaseSpec spec = parse_case(tbl, path);
//   write_file(out / "case.toml", case_to_toml(spec));
//
// Every error is a CaseError with a one-line message
//   "<file>:<line>: <key> = <value>: <reason>"      e.g. "x.toml:12: resolution.dp = -1: must be >
//   0"
// where <key> is the dotted path also accepted by --set ("fluid_block.0.radius"). The line is
// omitted when unknown; a value that came from --set is reported as "--set <key> = <value>: ...";
// a missing key has no value: "<file>: case.name: required key is missing".
#pragma once

#include <toml++/toml.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "vrsph/setup/case_spec.hpp"

namespace vrsph {

// Bad input in a case file or a --set override; what() is a one-line, user-facing reason.
struct CaseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads and parses a TOML file. Throws CaseError for a missing/unreadable file or a TOML syntax
// error ("<file>:<line>:<column>: TOML syntax error: ...").
toml::table load_case_table(const std::string& path);

// Applies one --set KEY=VALUE to the table. KEY is a dotted path ("resolution.dp",
// "fluid_block.0.radius", "numerics.shifting.model"); numeric segments index arrays (out of range
// is an error); missing intermediate tables are created. VALUE is parsed as a TOML value, or taken
// as a string when it is not valid TOML. Nodes it creates carry the source name "--set", so that
// parse_case() can say an error came from the command line. Throws CaseError.
void apply_override(toml::table& tbl, const std::string& key_eq_value);

// Validates the table (unknown keys, missing required keys, types, impossible values) and returns
// the spec with every default filled in. source_name (usually the file path) prefixes errors.
CaseSpec parse_case(const toml::table& tbl, const std::string& source_name);

// Every key a case file may hold, as its dotted --set path with "N" standing for an array index
// ("case.name", "numerics.viscosity.model", "fluid_block.N.radius", "output.line.N.name"): the
// keys of the schema parse_case() checks against (case_schema.hpp) that are not tables
// themselves, in schema order.
std::vector<std::string> known_case_keys();

// The resolved case as TOML, every default written out; parse_case() of it gives an equal spec.
std::string case_to_toml(const CaseSpec& spec);

}  // namespace vrsph
