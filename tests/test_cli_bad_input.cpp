// The `vrsph` command on bad input: exit status 1 and one line on stderr naming the key, the
// value and the reason, for `check` and `run` alike (the set-up guards' cases are in
// test_cli_setup_guards.cpp, run by the same test).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_bad_input.hpp"
#include "cli_cases.hpp"
#include "cli_util.hpp"

namespace {

using namespace vrsph_cli;
using namespace vrsph_cli_cases;

// ---------------------------------------------------------------------------------------------
// Bad input: exit status 1 and exactly one line on stderr naming the key, the value, the reason.

// Keys the format does not know, in a table, an inline table or as a whole table.
void add_unknown_keys(std::vector<BadInput>& v) {
  {
    const std::string text = replace_once(kTiny, "h_over_dp = 1.3", "h_over_dp = 1.3\nfoo = 3");
    v.push_back({"unknown_key_in_file",
                 text,
                 "",
                 {},
                 {"bad.toml:" + std::to_string(line_of(text, "foo = 3")), "resolution.foo", "3",
                  "unknown key"}});
  }
  v.push_back({"unknown_table_in_file",
               kTiny + "\n[solver]\nfoo = 1\n",
               "",
               {},
               {"bad.toml", "solver", "unknown key"}});
  {
    const std::string text = replace_once(kTiny, "alpha = 0.01", "alfa = 0.01");
    v.push_back({"unknown_key_in_inline_table",
                 text,
                 "",
                 {},
                 {"bad.toml:" + std::to_string(line_of(text, "alfa")), "numerics.viscosity.alfa",
                  "0.01", "unknown key"}});
  }
}

// Values of the wrong type, out of range or not among an enum's names.
void add_wrong_types_and_values(std::vector<BadInput>& v) {
  v.push_back({"wrong_type_dp_string",
               replace_once(kTiny, "dp = 0.04", "dp = \"abc\""),
               "",
               {},
               {"resolution.dp", "abc", "must be a number"}});
  v.push_back({"wrong_type_gravity_scalar",
               replace_once(kTiny, "gravity = [0.0, -9.81]", "gravity = 9.81"),
               "",
               {},
               {"fluid.gravity", "9.81"}});
  v.push_back({"dp_zero",
               replace_once(kTiny, "dp = 0.04", "dp = 0.0"),
               "",
               {},
               {"resolution.dp", "0", "> 0"}});
  v.push_back({"dp_negative",
               replace_once(kTiny, "dp = 0.04", "dp = -0.01"),
               "",
               {},
               {"resolution.dp", "-0.01", "> 0"}});
  v.push_back(
      {"radius_below_dp", kCircle, "", {}, {"fluid_block.0.radius", "0.005", "resolution.dp"}});
  v.push_back({"unknown_viscosity_model",
               replace_once(kTiny, "model = \"artificial\"", "model = \"foo\""),
               "",
               {},
               {"numerics.viscosity.model", "foo", "must be one of", "artificial", "laminar"}});
}

// Required keys and blocks left out.
void add_missing_keys(std::vector<BadInput>& v) {
  v.push_back(
      {"missing_dp", replace_once(kTiny, "dp = 0.04\n", ""), "", {}, {"resolution.dp", "missing"}});
  v.push_back({"missing_end_time",
               replace_once(kTiny, "end_time = 0.005\n", ""),
               "",
               {},
               {"case.end_time", "missing"}});
  v.push_back(
      {"missing_fluid_block",
       replace_once(kTiny,
                    "[[fluid_block]]\nshape = \"box\"\nmin = [0.04, 0.04]\nmax = [0.4, 0.4]\n", ""),
       "",
       {},
       {"fluid_block", "required"}});
}

// The same classes of error from --set, and --set without a value.
void add_set_errors(std::vector<BadInput>& v) {
  v.push_back({"set_unknown_key",
               kTiny,
               "",
               {"--set", "resolution.foo=1"},
               {"--set", "resolution.foo", "unknown key"}});
  v.push_back({"set_unknown_section",
               kTiny,
               "",
               {"--set", "solver.cfl=0.1"},
               {"--set", "solver", "unknown key"}});
  v.push_back({"set_bad_value_word",
               kTiny,
               "",
               {"--set", "resolution.dp=abc"},
               {"--set", "resolution.dp", "abc", "must be a number"}});
  v.push_back({"set_bad_value_negative",
               kTiny,
               "",
               {"--set", "resolution.dp=-1"},
               {"--set", "resolution.dp", "-1", "> 0"}});
  v.push_back({"set_unknown_enum",
               kTiny,
               "",
               {"--set", "numerics.viscosity.model=foo"},
               {"--set", "numerics.viscosity.model", "foo", "must be one of"}});
  v.push_back({"set_radius_below_dp",
               kCircle,
               "",
               {"--set", "fluid_block.0.radius=0.02", "--set", "resolution.dp=0.05"},
               {"fluid_block.0.radius", "0.02", "resolution.dp"}});
  v.push_back({"set_index_out_of_range",
               kTiny,
               "",
               {"--set", "fluid_block.3.min=[0, 0]"},
               {"fluid_block.3", "out of range"}});
  v.push_back(
      {"set_without_value", kTiny, "", {"--set", "resolution.dp"}, {"resolution.dp", "KEY=VALUE"}});
}

// A case file that does not exist or is not TOML.
void add_unreadable_case_files(std::vector<BadInput>& v) {
  v.push_back({"nonexistent_case_file",
               "",
               "no_such_case.toml",
               {},
               {"no_such_case.toml", "no such file"}});
  v.push_back(
      {"toml_syntax_error", "[case\nname = \"x\"\n", "", {}, {"bad.toml:1", "syntax error"}});
}

std::vector<BadInput> bad_inputs() {
  std::vector<BadInput> v;
  add_unknown_keys(v);
  add_wrong_types_and_values(v);
  add_missing_keys(v);
  add_set_errors(v);
  add_unreadable_case_files(v);
  return v;
}

TEST_P(CliBadInput, CheckAndRunRefuseWithOneLine) {
  const BadInput& b = GetParam();
  TempDir dir;
  if (!b.case_text.empty()) dir.write("bad.toml", b.case_text);
  const std::string case_arg = b.case_arg.empty() ? "bad.toml" : b.case_arg;

  std::vector<std::string> check{"check", case_arg};
  check.insert(check.end(), b.args.begin(), b.args.end());
  expect_bad_input(dir.run_limited(check), b);

  std::vector<std::string> run{"run", case_arg, "--out", "out_run", "--quiet", "--threads", "1"};
  run.insert(run.end(), b.args.begin(), b.args.end());
  expect_bad_input(dir.run_limited(run), b);
  EXPECT_FALSE(fs::exists(dir / "out_run")) << "bad input must not create the output folder";
  EXPECT_FALSE(fs::exists(dir / "out")) << "bad input must not create out/";
}

INSTANTIATE_TEST_SUITE_P(Cli, CliBadInput, ::testing::ValuesIn(bad_inputs()),
                         [](const auto& info) { return info.param.name; });

TEST(CliBadInputSanity, TheBaseCasesAreValid) {
  TempDir dir;
  dir.write("tiny.toml", kTiny);
  dir.write("circle.toml", replace_once(kCircle, "radius = 0.005", "radius = 0.05"));
  const CmdResult a = dir.run({"check", "tiny.toml"});
  EXPECT_EQ(a.status, 0) << a;
  EXPECT_NE(a.out.find("100 fluid"), std::string::npos) << a;
  EXPECT_NE(a.out.find("240 wall"), std::string::npos) << a;
  const CmdResult b = dir.run({"check", "circle.toml"});
  EXPECT_EQ(b.status, 0) << b;
}

}  // namespace
