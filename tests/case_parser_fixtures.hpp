// The smallest valid case and the parse / error helpers shared by the case-file tests
// (test_case_parser.cpp, test_case_errors.cpp, and the tests of single numerics keys).
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <string_view>

#include "vrsph/setup/case_parser.hpp"

namespace vrsph::case_fixtures {

// The smallest valid case; line numbers matter for the error tests.
inline constexpr const char* kMinimal = R"(
[case]
name = "droplet"
dimension = 2
end_time = 0.2
[resolution]
dp = 1e-4
[[fluid_block]]
shape = "circle"
center = [0.0, 0.0]
radius = 0.002
)";

// kMinimal with `from` replaced by `to` (the text must occur).
inline std::string edited(const std::string& from, const std::string& to,
                          std::string text = kMinimal) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

// Parses a case text (as "test.toml") after applying --set overrides.
inline CaseSpec parse_text(const std::string& text, std::initializer_list<std::string> sets = {}) {
  toml::table tbl = toml::parse(std::string_view(text), std::string_view("test.toml"));
  for (const auto& s : sets) apply_override(tbl, s);
  return parse_case(tbl, "test.toml");
}

// parse_case() of a case_to_toml() text.
inline CaseSpec reparse(const std::string& text) {
  return parse_case(toml::parse(std::string_view(text), std::string_view("case.toml")),
                    "case.toml");
}

// kMinimal with a [numerics] table of the given lines ("key = value\n" each).
inline std::string with_numerics(const std::string& lines) {
  return std::string(kMinimal) + "[numerics]\n" + lines;
}

// The spec as a run folder's case.toml gives it back: written (case_to_toml) and parsed again.
inline CaseSpec written_back(const CaseSpec& s) { return reparse(case_to_toml(s)); }

// The CaseError message for a case text (empty, and a test failure, when it parses).
inline std::string error_of(const std::string& text, std::initializer_list<std::string> sets = {}) {
  try {
    parse_text(text, sets);
  } catch (const CaseError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no CaseError for:\n" << text;
  return {};
}

// Expects every fragment in the message.
inline void expect_contains(const std::string& message,
                            std::initializer_list<std::string> fragments) {
  for (const auto& f : fragments) EXPECT_NE(message.find(f), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
}

}  // namespace vrsph::case_fixtures
