// The set-up guards (CONTRACT.md "Refused at set-up"): blocks outside the domain, overlapping or
// empty fluid blocks, counts and memory beyond the machine or --max-particles, walls thinner
// than the kernel support, refinement boxes outside the default domain, a first time step that
// cannot advance the clock, outputs at every step, integers and names out of range, values that
// would throw the fluid out at the first step. Each goes through `vrsph check` and `vrsph run`
// (CliBadInput, test_cli_bad_input.cpp) under a 4 GiB address-space limit, so a guard that let a
// huge case through would fail here with std::bad_alloc instead of filling the machine.
// Also: the default domain gives a free body room to deform, and says how to set it.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli_bad_input.hpp"
#include "cli_cases.hpp"
#include "cli_util.hpp"

namespace {

using namespace vrsph_cli;
using namespace vrsph_cli_cases;

// kTiny with a [domain] around its tank (walls reach -0.08 m; the fluid is at 0.04..0.4 m).
const std::string kTinyDomain = kTiny + "\n[domain]\nmin = [-0.2, -0.2]\nmax = [1.2, 1.5]\n";

// kTiny with a second fluid block.
std::string tiny_with_block(const std::string& block) {
  return kTiny + "\n[[fluid_block]]\n" + block + "\n";
}

std::string tiny_with(const std::string& tables) { return kTiny + "\n" + tables + "\n"; }

std::vector<BadInput> geometry_guards() {
  std::vector<BadInput> v;
  v.push_back({"fluid_block_partly_outside_domain",
               kTinyDomain,
               "",
               {"--set", "fluid_block.0.max=[1.3, 0.4]"},
               {"fluid_block.0.max", "[1.3, 0.4]", "outside the domain", "dropped"}});
  v.push_back({"fluid_block_wholly_outside_domain",
               kTinyDomain,
               "",
               {"--set", "fluid_block.0.min=[2.0, 2.0]", "--set", "fluid_block.0.max=[2.3, 2.3]"},
               {"fluid_block.0.max", "[2.3, 2.3]", "outside the domain"}});
  v.push_back({"circle_outside_domain",
               replace_once(kCircle, "radius = 0.005", "radius = 0.05") +
                   "\n[domain]\nmin = [-0.04, -0.1]\nmax = [0.1, 0.1]\n",
               "",
               {},
               {"fluid_block.0.center", "outside the domain", "domain.min = [-0.04, -0.1]"}});
  v.push_back({"wall_layers_outside_domain",
               replace_once(kTinyDomain, "min = [-0.2, -0.2]", "min = [-0.05, -0.2]"),
               "",
               {},
               {"wall_block.0.min", "the tank's 3 layers", "x = -0.08", "outside the domain"}});
  v.push_back({"overlapping_fluid_boxes",
               tiny_with_block("shape = \"box\"\nmin = [0.2, 0.2]\nmax = [0.6, 0.6]"),
               "",
               {},
               {"fluid_block.1.min", "[0.2, 0.2]", "overlaps fluid_block.0"}});
  v.push_back({"lattice_boxes_sharing_a_face",
               tiny_with_block("shape = \"box\"\nmin = [0.4, 0.04]\nmax = [0.6, 0.4]"),
               "",
               {},
               {"fluid_block.1.min", "overlaps fluid_block.0", "share a face"}});
  v.push_back({"circle_overlapping_box",
               tiny_with_block("shape = \"circle\"\ncenter = [0.5, 0.3]\nradius = 0.15"),
               "",
               {},
               {"fluid_block.1.center", "[0.5, 0.3]", "overlaps fluid_block.0"}});
  v.push_back({"no_fluid_particle",
               replace_once(kTiny, "max = [0.4, 0.4]", "max = [0.4, 0.07]\nfill = \"cells\""),
               "",
               {},
               {"fluid_block.0.max", "[0.4, 0.07]", "no particle", "no fluid particle"}});
  v.push_back({"tank_thinner_than_the_support",
               replace_once(kTiny, "layers = 3", "layers = 2"),
               "",
               {},
               {"wall_block.0.layers", "2", "thinner than the kernel support", "layers >= 3"}});
  v.push_back({"box_wall_thinner_than_the_support",
               tiny_with("[[wall_block]]\nshape = \"box\"\nmin = [0.5, 0.0]\nmax = [0.55, 0.5]"),
               "",
               {},
               {"wall_block.1.max", "[0.55, 0.5]", "thinner than the kernel support"}});
  v.push_back({"refinement_outside_default_domain",
               tiny_with("[[refinement]]\nmin = [3.0, 0.0]\nmax = [3.5, 0.5]"),
               "",
               {},
               {"refinement.0.max", "[3.5, 0.5]", "inside the domain", "without [domain]"}});
  return v;
}

std::vector<BadInput> size_guards() {
  const std::string big_box = tiny_with("[[refinement]]\nmin = [0.02, 0.02]\nmax = [0.95, 0.95]");
  std::vector<BadInput> v;
  v.push_back({"memory_beyond_the_machine",
               kTiny,
               "",
               {"--set", "resolution.dp=1e-5"},
               {"resolution.dp", "1e-05", "1.3e+09 particles",
                "fluid_block.0, a box of 0.36 x "
                "0.36 m",
                "MemAvailable"}});
  v.push_back({"max_particles_option",
               kTiny,
               "",
               {"--max-particles", "300"},
               {"resolution.dp", "0.04", "about 340 particles", "--max-particles = 300"}});
  v.push_back({"more_than_a_level_can_index",
               kTiny,
               "",
               {"--set", "resolution.dp=1e-7"},
               {"resolution.dp", "1e-07", "2^32 - 1"}});
  v.push_back({"dp_ratio_drives_the_count",
               big_box,
               "",
               {"--set", "refinement.0.dp_ratio=1000", "--max-particles", "1000000"},
               {"refinement.0.dp_ratio", "1000", "level 1: dp / 1000", "--max-particles"}});
  v.push_back({"wall_layers_drive_the_count",
               kTiny,
               "",
               {"--set", "wall_block.0.layers=1000", "--max-particles", "100000"},
               {"wall_block.0.layers", "1000", "a tank of 1 x 1 m with 1000 layers"}});
  v.push_back({"domain_with_too_many_cells",
               replace_once(kTinyDomain, "max = [1.2, 1.5]", "max = [1e7, 1e7]"),
               "",
               {},
               {"domain.max", "2^40"}});
  v.push_back({"layers_overflow",
               kTiny,
               "",
               {"--set", "wall_block.0.layers=2147483647"},
               {"wall_block.0.layers", "2147483647", "[1, 1000]"}});
  v.push_back({"layers_beyond_int",
               kTiny,
               "",
               {"--set", "wall_block.0.layers=3000000000"},
               {"wall_block.0.layers", "3000000000", "out of range"}});
  v.push_back({"dp_ratio_overflow",
               big_box,
               "",
               {"--set", "refinement.0.dp_ratio=2147483647"},
               {"refinement.0.dp_ratio", "2147483647", "[2, 1000]"}});
  return v;
}

std::vector<BadInput> time_guards() {
  std::vector<BadInput> v;
  v.push_back({"denormal_dp",
               kTiny,
               "",
               {"--set", "resolution.dp=1e-320"},
               {"resolution.dp", "1e-320", "first time step", "advance the clock"}});
  v.push_back({"absurd_sound_speed",
               kTiny,
               "",
               {"--set", "eos.sound_speed=1e300"},
               {"eos.sound_speed", "1e+300", "first time step"}});
  v.push_back({"infinite_sound_speed",
               kTiny,
               "",
               {"--set", "eos.max_speed=1e300", "--set", "eos.sound_speed_factor=1e300"},
               {"eos.max_speed", "first time step", "inf"}});
  v.push_back({"output_every_step",
               kTiny,
               "",
               {"--set", "output.interval=1e-6"},
               {"output.interval", "1e-06", "every step"}});
  v.push_back({"gravity_throws_the_fluid_out",
               kTiny,
               "",
               {"--set", "fluid.gravity=[0, -1e9]", "--set", "eos.sound_speed=10"},
               {"fluid.gravity", "[0, -1000000000]", "first step", "out of the domain"}});
  v.push_back({"pressure_throws_the_block_apart",
               kTiny,
               "",
               {"--set", "fluid_block.0.pressure=1e12"},
               {"fluid_block.0.pressure", "initial density", "first step"}});
  return v;
}

std::vector<BadInput> name_guards() {
  std::vector<BadInput> v;
  v.push_back({"case_name_too_long",
               kTiny,
               "",
               {"--set", "case.name=" + std::string(256, 'x')},
               {"case.name", "256 bytes", "at most 255"}});
  v.push_back({"case_name_bad_character",
               kTiny,
               "",
               {"--set", "case.name=\"tiny:1\""},
               {"case.name", "tiny:1", "folder name"}});
  v.push_back({"case_name_like_an_option",
               kTiny,
               "",
               {"--set", "case.name=\"-tiny\""},
               {"case.name", "-tiny", "not starting with"}});
  const std::string line = "[output]\ninterval = 0.001\n[[output.line]]\nname = \"" +
                           std::string(231, 'l') + "\"\nfrom = [0.1, 0.1]\nto = [0.2, 0.2]";
  v.push_back({"line_name_too_long",
               tiny_with(line),
               "",
               {},
               {"output.line.0.name", "231 bytes", "at most 223", "_interp"}});
  v.push_back({"line_name_bad_character",
               tiny_with(line),
               "",
               {"--set", "output.line.0.name=a.b"},
               {"output.line.0.name", "a.b", "[A-Za-z0-9_-]+"}});
  return v;
}

std::vector<BadInput> guard_inputs() {
  std::vector<BadInput> v = geometry_guards();
  for (auto* list : {size_guards, time_guards, name_guards}) {
    for (auto& b : list()) v.push_back(std::move(b));
  }
  return v;
}

INSTANTIATE_TEST_SUITE_P(Guards, CliBadInput, ::testing::ValuesIn(guard_inputs()),
                         [](const auto& info) { return info.param.name; });

// The limits of the guards themselves: a case just inside them is accepted, and check prints
// the estimate.
TEST(CliSetupGuards, CasesJustInsideTheGuardsAreValid) {
  TempDir dir;
  dir.write("tiny.toml", kTiny);
  dir.write("gap.toml", tiny_with_block("shape = \"box\"\nmin = [0.44, 0.04]\nmax = [0.6, 0.4]"));
  dir.write("dom.toml", kTinyDomain);
  const CmdResult a = dir.run({"check", "tiny.toml", "--max-particles", "340"});
  EXPECT_EQ(a.status, 0) << a;
  EXPECT_NE(a.out.find("estimate before filling: about 340 particles"), std::string::npos) << a;
  EXPECT_NE(a.out.find("MiB available"), std::string::npos) << a;
  const CmdResult b = dir.run({"check", "gap.toml"});  // one dp apart: no overlap
  EXPECT_EQ(b.status, 0) << b;
  const CmdResult c = dir.run({"check", "dom.toml"});
  EXPECT_EQ(c.status, 0) << c;
  // Two drops side by side (droplet_coalescence_2d) touch but do not overlap.
  const CmdResult d = dir.run({"check", (kCases / "droplet_coalescence_2d.toml").string()});
  EXPECT_EQ(d.status, 0) << d;
  // A thin tank is accepted when the block asks for it (the DualSPHysics replica in 3D).
  dir.write("thin.toml", replace_once(kTiny, "layers = 3", "layers = 2\nthin = true"));
  const CmdResult e = dir.run({"check", "thin.toml"});
  EXPECT_EQ(e.status, 0) << e;
  const CmdResult f = dir.run({"check", (kCases / "bench_dam_break_3d.toml").string()});
  EXPECT_EQ(f.status, 0) << f;
}

// ---------------------------------------------------------------------------------------------
// The default domain: room for a free body to deform, and a pointer to [domain] when too small.

// A 4 x 3 mm rectangle of water, surface tension on, no gravity, no walls, no [domain]: it
// relaxes towards a circle of the same area and overshoots. Under the earlier margin
// (max(0.1 x extent, 4h)) it left the domain: at dp = 1e-4, 1% of it by 2.70 ms; at this
// coarser dp, with max_lost_fraction = 0, its first particles at 3.26 ms.
const std::string kRectangle = R"([case]
name = "rectangle"
dimension = 2
end_time = 0.0034

[fluid]
surface_tension = 0.0728

[eos]
max_speed = 0.5

[resolution]
dp = 1.25e-4

[[fluid_block]]
shape = "box"
min = [0.0, 0.0]
max = [0.004, 0.003]

[domain]
max_lost_fraction = 0.0

[output]
interval = 0.0017
formats = ["csv"]
)";

// The numbers of "domain [a, b] .. [c, d] m" in `vrsph check`'s report.
std::vector<double> domain_of(const std::string& out) {
  std::vector<double> v;
  const auto at = out.find("domain [");
  if (at == std::string::npos) return v;
  std::string text = out.substr(at + 7, out.find(" m,", at) - at - 7);
  for (char& c : text) {
    if (c == '[' || c == ']' || c == ',') c = ' ';
  }
  std::istringstream in(text);
  for (std::string w; in >> w;) {
    if (w != "..") v.push_back(std::stod(w));
  }
  return v;
}

TEST(CliDefaultDomain, RoomForAFreeBodyToDeform) {
  TempDir dir;
  dir.write("rect.toml", kRectangle);
  const CmdResult c = dir.run({"check", "rect.toml"});
  ASSERT_EQ(c.status, 0) << c;
  const std::vector<double> d = domain_of(c.out);
  ASSERT_EQ(d.size(), 4u) << c;
  // The body's nodes span [0, 4] x [0, 3] mm; the margin is at least its largest extent, 4 mm,
  // on every side (the earlier one was 0.52 mm).
  EXPECT_LE(d[0], -0.004 + 1e-9) << c;
  EXPECT_LE(d[1], -0.004 + 1e-9) << c;
  EXPECT_GE(d[2], 0.008 - 1e-9) << c;
  EXPECT_GE(d[3], 0.007 - 1e-9) << c;
  const CmdResult r = dir.run({"run", "rect.toml", "--out", "run", "--quiet", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r;
  const auto series = read_lines(dir / "run" / "series.csv");
  ASSERT_GE(series.size(), 3u);
  EXPECT_EQ(std::stod(split_csv(series.back())[0]), 0.0034);
  EXPECT_EQ(split_csv(series.back())[3], split_csv(series[1])[3]) << "no fluid particle lost";
}

// A drop thrown sideways leaves the default domain: the diagnosis says that [domain] sets it;
// with [domain] given it does not.
TEST(CliDefaultDomain, LeavingItPointsToTheDomainTable) {
  TempDir dir;
  const std::string thrown =
      replace_once(replace_once(kCircle, "radius = 0.005", "radius = 0.05\nvelocity = [10.0, 0.0]"),
                   "max_speed = 1.0", "max_speed = 10.0");
  dir.write("thrown.toml", replace_once(thrown, "end_time = 0.001", "end_time = 0.05"));
  dir.write("boxed.toml", replace_once(thrown, "end_time = 0.001", "end_time = 0.05") +
                              "\n[domain]\nmin = [-0.1, -0.1]\nmax = [0.1, 0.1]\n");
  const CmdResult a = dir.run({"run", "thrown.toml", "--out", "a", "--quiet", "--threads", "1"});
  EXPECT_EQ(a.status, 2) << a;
  EXPECT_NE(a.err.find("left the domain"), std::string::npos) << a;
  EXPECT_NE(a.err.find("default domain"), std::string::npos) << a;
  EXPECT_NE(a.err.find("[domain] min and max set it"), std::string::npos) << a;
  const CmdResult b = dir.run({"run", "boxed.toml", "--out", "b", "--quiet", "--threads", "1"});
  EXPECT_EQ(b.status, 2) << b;
  EXPECT_NE(b.err.find("left the domain"), std::string::npos) << b;
  EXPECT_EQ(b.err.find("default domain"), std::string::npos) << b;
}

}  // namespace
