// The level tree of a variable-resolution case: one level per [[refinement]] box plus level 0,
// each with its dp, h and region (vres/region.hpp). A box's parent is the smallest other box
// that contains it (level 0 when none does); dp_child = dp_parent / dp_ratio.
#pragma once

#include <vector>

#include "vrsph/setup/case_spec.hpp"
#include "vrsph/vres/region.hpp"

namespace vrsph {

template <int D>
struct LevelLayout {
  double dp = 0.0;
  double h = 0.0;
  LevelRegion<D> region;
};

// Levels in an order where every parent comes before its children (level 0 first). Throws
// std::invalid_argument naming the [[refinement]] entry when boxes overlap, nest too tightly
// for their buffers, or are too small for the parent's buffer.
template <int D>
std::vector<LevelLayout<D>> make_level_layout(const CaseSpec& spec);

}  // namespace vrsph
