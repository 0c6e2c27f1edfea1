// Tiny cases and text helpers shared by the command-line tests (test_cli*.cpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace vrsph_cli_cases {

// A small valid case: 100 fluid particles in a 1 m tank (340 particles in all).
inline const std::string kTiny = R"([case]
name = "tiny"
dimension = 2
end_time = 0.005

[fluid]
gravity = [0.0, -9.81]

[resolution]
dp = 0.04
h_over_dp = 1.3

[numerics]
viscosity = { model = "artificial", alpha = 0.01 }

[[fluid_block]]
shape = "box"
min = [0.04, 0.04]
max = [0.4, 0.4]

[[wall_block]]
shape = "tank"
min = [0.0, 0.0]
max = [1.0, 1.0]
layers = 3
)";

// A circle of fluid, for radius checks.
inline const std::string kCircle = R"([case]
name = "circle"
dimension = 2
end_time = 0.001

[eos]
max_speed = 1.0

[resolution]
dp = 0.01

[[fluid_block]]
shape = "circle"
center = [0.0, 0.0]
radius = 0.005
)";

inline std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "test set-up: '" << from << "' not in the case text";
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

// 1-based number of the line of `text` that contains `needle`.
inline int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

}  // namespace vrsph_cli_cases
