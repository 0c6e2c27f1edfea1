// The case-file layer on bad input: one-line errors for every class of bad input, --set overrides
// and their errors, and loading a case file (docs/cases.md and the README).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "case_parser_fixtures.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace vrsph {
namespace {

using namespace case_fixtures;

TEST(CaseParser, UnknownKeyNamesKeyAndLine) {
  const std::string msg = error_of(edited("dp = 1e-4", "dp = 1e-4\nfoo = 1"));
  expect_contains(msg, {"test.toml:8: ", "resolution.foo = 1", "unknown key"});
  expect_contains(error_of(std::string(kMinimal) + "[numerics]\nshifting = { modle = \"lind\" }\n"),
                  {"test.toml:13: ", "numerics.shifting.modle", "unknown key"});
  expect_contains(error_of(std::string(kMinimal) + "[bogus]\nx = 1\n"),
                  {"test.toml:12", "bogus", "unknown key"});
}

TEST(CaseParser, WrongTypes) {
  expect_contains(error_of(edited("dp = 1e-4", "dp = \"abc\"")),
                  {"test.toml:7: ", "resolution.dp = \"abc\"", "must be a number"});
  expect_contains(error_of(edited("dimension = 2", "dimension = 2.5")),
                  {"case.dimension = 2.5", "must be an integer"});
  expect_contains(error_of(edited("dimension = 2", "dimension = 2.0")),
                  {"case.dimension", "must be an integer"});
  expect_contains(error_of(std::string(kMinimal) + "[numerics]\nhydrostatic_initial_density = 1\n"),
                  {"numerics.hydrostatic_initial_density = 1", "true or false"});
  expect_contains(error_of(std::string(kMinimal) + "[[refinement]]\nmin = [0, 0]\nmax = [1, 1]\n"
                                                   "dp_ratio = 2.0\n"),
                  {"refinement.0.dp_ratio = 2", "must be an integer"});
}

TEST(CaseParser, ImpossibleValues) {
  const std::string m = kMinimal;
  expect_contains(error_of(edited("dp = 1e-4", "dp = -1")),
                  {"test.toml:7: resolution.dp = -1: must be > 0"});
  expect_contains(error_of(edited("dp = 1e-4", "dp = 0.0")), {"resolution.dp", "must be > 0"});
  expect_contains(error_of(edited("radius = 0.002", "radius = 5e-5")),
                  {"test.toml:11: ", "fluid_block.0.radius = 5e-05", "must be >= resolution.dp"});
  expect_contains(error_of(edited("end_time = 0.2", "end_time = 0")), {"case.end_time", "> 0"});
  expect_contains(error_of(edited("dimension = 2", "dimension = 4")), {"case.dimension", "2 or 3"});
  expect_contains(error_of(m + "[numerics]\ncfl = 1.5\n"), {"numerics.cfl = 1.5", "(0, 1]"});
  expect_contains(error_of(m + "[numerics]\nsurface_tension = { refresh = \"sometimes\" }\n"),
                  {"numerics.surface_tension.refresh", "sometimes", "every_step", "capillary"});
  expect_contains(error_of(m + "[numerics]\nsurface_tension = { refresh_interval = 0 }\n"),
                  {"numerics.surface_tension.refresh_interval = 0", "(0, 8]"});
  expect_contains(error_of(m + "[fluid]\ndensity = -3\n"), {"fluid.density", "> 0"});
  expect_contains(error_of(m + "[fluid]\nkinematic_viscosity = -1e-6\n"),
                  {"fluid.kinematic_viscosity", ">= 0"});
  expect_contains(error_of(m + "[eos]\ngamma = 0\n"), {"eos.gamma", "> 0"});
  expect_contains(error_of(m + "[output]\ninterval = -0.1\n"), {"output.interval", ">= 0"});
  expect_contains(error_of(m + "[domain]\nmax_lost_fraction = 2\n"),
                  {"domain.max_lost_fraction", "[0, 1]"});
  expect_contains(error_of(m + "[[wall_block]]\nshape = \"tank\"\nmin = [0, 0]\nmax = [1, 1]\n"
                               "layers = 0\n"),
                  {"wall_block.0.layers = 0", "must be in [1, 1000]"});
  expect_contains(error_of(m + "[[wall_block]]\nshape = \"box\"\nmin = [0, 1]\nmax = [1, 1]\n"),
                  {"wall_block.0.max = [1, 1]", "must be > min"});
  expect_contains(error_of(m + "[[refinement]]\nmin = [0, 0]\nmax = [1, 1]\ndp_ratio = 1\n"),
                  {"refinement.0.dp_ratio = 1", "must be in [2, 1000]"});
  expect_contains(error_of(m + "[[refinement]]\nmin = [0, 0]\nmax = [1, 1]\nbuffer_width = 0\n"),
                  {"refinement.0.buffer_width", "> 0"});
  expect_contains(
      error_of(m + "[[refinement]]\nmin = [0, 0]\nmax = [1, 1]\nbuffer_rounding = \"up\"\n"),
      {"refinement.0.buffer_rounding", "up", "whole_dp"});
  expect_contains(error_of(m + "[numerics]\nstart_damping_time = -1\n"),
                  {"numerics.start_damping_time = -1", ">= 0"});
  expect_contains(error_of(m + "[numerics]\nstart_damping_tau = 0\n"),
                  {"numerics.start_damping_tau = 0", "> 0"});
  expect_contains(error_of(m + "[numerics]\nvres_buffer_fill_min = 0.5\n"),
                  {"numerics.vres_buffer_fill_min = 0.5", "[0, 0.5)", "free surface"});
}

TEST(CaseParser, MissingRequiredKeys) {
  expect_contains(error_of(edited("end_time = 0.2\n", "")),
                  {"case.end_time", "required key is missing"});
  expect_contains(error_of(edited("dp = 1e-4\n", "")), {"resolution.dp", "required"});
  expect_contains(error_of(edited("name = \"droplet\"\n", "")), {"case.name", "required"});
  const std::string no_block =
      std::string(kMinimal).substr(0, std::string(kMinimal).find("[[fluid_block]]"));
  expect_contains(error_of(no_block), {"test.toml: fluid_block", "at least one [[fluid_block]]"});
  expect_contains(error_of(edited("radius = 0.002\n", "")), {"fluid_block.0.radius", "required"});
}

TEST(CaseParser, BadEnumsAndShapes) {
  const std::string m = kMinimal;
  expect_contains(
      error_of(m + "[numerics]\nviscosity = { model = \"foo\" }\n"),
      {"test.toml:13: ", "numerics.viscosity.model = \"foo\"", "\"laminar\"", "\"artificial\""});
  expect_contains(error_of(m + "[output]\nformats = [\"vtp\", \"png\"]\n"),
                  {"output.formats", "\"vtp\" or \"csv\""});
  expect_contains(error_of(m + "[output]\nprecision = \"single\"\n"),
                  {"test.toml:13: ", "output.precision = \"single\"",
                   "must be one of \"double\", \"float32\""});
  expect_contains(
      error_of(m + "[output]\ncompression = \"gzip\"\n"),
      {"test.toml:13: ", "output.compression = \"gzip\"", "must be one of \"none\", \"zlib\""});
  expect_contains(error_of(m + "[output]\nprecision = 32\n"), {"output.precision = 32", "string"});
  expect_contains(error_of(edited("\"circle\"", "\"sphere\"")),
                  {"fluid_block.0.shape = \"sphere\"", "2D"});
  expect_contains(error_of(edited("radius = 0.002", "radius = 0.002\nfill = \"rings\"",
                                  edited("dimension = 2", "dimension = 3",
                                         edited("shape = \"circle\"\ncenter = [0.0, 0.0]",
                                                "shape = \"sphere\"\ncenter = [0.0, 0.0, 0.0]")))),
                  {"fluid_block.0.fill = \"rings\"", "circle"});
  expect_contains(error_of(m + "[[fluid_block]]\nshape = \"box\"\nmin = [0, 0]\nmax = [1, 1]\n"
                               "fill = \"rings\"\n"),
                  {"fluid_block.1.fill", "circle"});
  expect_contains(error_of(edited("radius = 0.002", "radius = 0.002\nfill = \"cells\"")),
                  {"fluid_block.0.fill = \"cells\"", "box"});
  expect_contains(error_of(m + "[[output.line]]\nname = \"a b\"\nfrom = [0, 0]\nto = [1, 0]\n"),
                  {"output.line.0.name = \"a b\"", "[A-Za-z0-9_-]+"});
  expect_contains(
      error_of(m + "[[output.line]]\nname = \"d_interp\"\nfrom = [0, 0]\nto = [1, 0]\n"),
      {"output.line.0.name = \"d_interp\"", "_interp"});
  const std::string probe = "[[output.probe]]\nname = \"c\"\nposition = [0, 0]\n";
  expect_contains(error_of(m + probe + probe), {"output.probe.1.name = \"c\"", "duplicate"});
  expect_contains(error_of(m + "[[output.probe]]\nname = \"c/d\"\nposition = [0, 0]\n"),
                  {"output.probe.0.name", "[A-Za-z0-9_-]+"});
  expect_contains(error_of(m + "[[output.probe]]\nname = \"c\"\nposition = [0, 0, 0]\n"),
                  {"output.probe.0.position", "array of 2 numbers"});
  expect_contains(error_of(m + "[[output.probe]]\nposition = [0, 0]\n"),
                  {"output.probe.0.name", "missing"});
}

TEST(CaseParser, WrongVectorLength) {
  expect_contains(error_of(std::string(kMinimal) + "[fluid]\ngravity = [0, 0, -9.81]\n"),
                  {"test.toml:13: ", "fluid.gravity = [0, 0, -9.81]", "array of 2 numbers"});
  expect_contains(error_of(edited("center = [0.0, 0.0]", "center = [0.0]")),
                  {"fluid_block.0.center", "array of 2 numbers"});
  expect_contains(error_of(edited("center = [0.0, 0.0]", "center = [0.0, \"y\"]")),
                  {"fluid_block.0.center", "array of 2 numbers"});
}

TEST(CaseParser, RefinementOutsideDomain) {
  const std::string text = std::string(kMinimal) +
                           "[domain]\nmin = [-0.004, -0.004]\nmax = [0.004, 0.004]\n"
                           "[[refinement]]\nmin = [0.0, -0.003]\nmax = [0.005, 0.003]\n";
  expect_contains(error_of(text),
                  {"test.toml:17: ", "refinement.0.max = [0.005, 0.003]", "inside the domain"});
  expect_contains(error_of(std::string(kMinimal) + "[domain]\nmin = [-0.004, -0.004]\n"),
                  {"domain.max", "required when domain.min"});
}

TEST(CaseOverride, ScalarArrayElementInlineTableAndBareWord) {
  const std::string text = std::string(kMinimal) + "[numerics]\nshifting = { model = \"lind\" }\n";
  const CaseSpec s = parse_text(
      text, {"resolution.dp=5e-5", " case.end_time = 0.01 ", "fluid_block.0.radius=0.001",
             "numerics.shifting.model=skillen", "numerics.shifting.surface_threshold=1.2",
             "fluid.gravity=[0, -9.81]", "case.name=other_name", "output.formats=[\"csv\"]",
             "numerics.hydrostatic_initial_density=false"});
  EXPECT_DOUBLE_EQ(s.dp, 5e-5);
  EXPECT_DOUBLE_EQ(s.end_time, 0.01);
  EXPECT_DOUBLE_EQ(s.fluid_blocks[0].radius, 0.001);
  EXPECT_EQ(s.numerics.shifting.model, ShiftingModel::skillen);
  EXPECT_DOUBLE_EQ(s.numerics.shifting.coefficient, 2.0);  // the skillen default
  EXPECT_DOUBLE_EQ(s.numerics.shifting.surface_threshold, 1.2);
  EXPECT_EQ(s.fluid.gravity, (Vec3d{0, -9.81, 0}));
  EXPECT_EQ(s.name, "other_name");
  EXPECT_FALSE(s.write_vtp);
  EXPECT_FALSE(s.numerics.hydrostatic_initial_density);
  // Missing intermediate tables are created; array elements can be replaced by index.
  const CaseSpec t = parse_text(kMinimal, {"numerics.viscosity.model=artificial",
                                           "fluid_block.0.center.1=0.5", "case.name=\"quoted\""});
  EXPECT_EQ(t.numerics.viscosity.model, ViscosityModel::artificial);
  EXPECT_DOUBLE_EQ(t.fluid_blocks[0].center[1], 0.5);
  EXPECT_EQ(t.name, "quoted");
}

TEST(CaseOverride, ErrorsSayTheyCameFromSet) {
  expect_contains(error_of(kMinimal, {"numerics.foo=1"}), {"--set numerics.foo = 1: unknown key"});
  expect_contains(error_of(kMinimal, {"resolution.dp=-1"}),
                  {"--set resolution.dp = -1: must be > 0"});
  expect_contains(error_of(kMinimal, {"numerics.shifting.model=bogus"}),
                  {"--set numerics.shifting.model = \"bogus\"", "must be one of"});
  expect_contains(error_of(kMinimal, {"output.compression=lz4"}),
                  {"--set output.compression = \"lz4\"", "must be one of \"none\", \"zlib\""});
  expect_contains(error_of(kMinimal, {"fluid_block.1.radius=0.001"}),
                  {"--set fluid_block.1.radius", "out of range"});
  expect_contains(error_of(kMinimal, {"wall_block.0.layers=2"}), {"wall_block", "does not exist"});
  expect_contains(error_of(kMinimal, {"case.name.x=1"}), {"case.name", "not a table"});
  expect_contains(error_of(kMinimal, {"resolution.dp"}), {"--set resolution.dp", "KEY=VALUE"});
  expect_contains(error_of(kMinimal, {"resolution..dp=1"}), {"empty key segment"});
}

TEST(CaseLoad, MissingFileAndSyntaxError) {
  try {
    load_case_table("/nonexistent/case.toml");
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    expect_contains(e.what(), {"/nonexistent/case.toml", "cannot open"});
  }
  const auto path = std::filesystem::temp_directory_path() / "vrsph_case_parser_syntax.toml";
  std::ofstream(path) << "[case]\nname = \"x\"\ndimension = = 2\n";
  try {
    load_case_table(path.string());
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    expect_contains(e.what(), {path.string() + ":3:", "TOML syntax error"});
  }
  std::ofstream(path) << kMinimal;
  const CaseSpec s = parse_case(load_case_table(path.string()), path.string());
  EXPECT_EQ(s.name, "droplet");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace vrsph
