#include "vrsph/vres/levels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "vrsph/core/to_vec.hpp"

namespace vrsph {
namespace {

template <int D>
Box<D> box_of(const RefinementBox& r) {
  return Box<D>{to_vec<D>(r.min), to_vec<D>(r.max)};
}

template <int D>
double volume(const Box<D>& b) {
  double v = 1.0;
  for (int k = 0; k < D; ++k) v *= b.hi[k] - b.lo[k];
  return v;
}

std::invalid_argument refinement_error(std::size_t i, const char* key, const std::string& why) {
  return std::invalid_argument(fmt::format("refinement.{}.{}: {}", i, key, why));
}

}  // namespace

namespace {

// Parent box of each box: the smallest other box containing it (-1: level 0). Refuses boxes that
// overlap without nesting, and repeated boxes.
template <int D>
std::vector<int> parent_boxes(const std::vector<RefinementBox>& refs) {
  const std::size_t nb = refs.size();
  std::vector<int> parent_box(nb, -1);
  for (std::size_t i = 0; i < nb; ++i) {
    const Box<D> bi = box_of<D>(refs[i]);
    for (std::size_t j = 0; j < nb; ++j) {
      if (i == j) continue;
      const Box<D> bj = box_of<D>(refs[j]);
      if (bj.contains_box(bi) && !(bi.contains_box(bj))) {
        const int p = parent_box[i];
        if (p < 0 || volume(bj) < volume(box_of<D>(refs[static_cast<std::size_t>(p)])))
          parent_box[i] = static_cast<int>(j);
      } else if (bi.overlaps(bj) && !bi.contains_box(bj)) {
        throw refinement_error(
            i, "min",
            fmt::format("box overlaps refinement.{} without containing it or lying inside it", j));
      } else if (bi.contains_box(bj) && bj.contains_box(bi)) {
        throw refinement_error(i, "min", fmt::format("box repeats refinement.{}", j));
      }
    }
  }
  return parent_box;
}

// Level index of each box (1, 2, ...): depth-first order, so parents come first.
std::vector<int> box_levels(const std::vector<int>& parent_box, std::vector<std::size_t>& order) {
  const std::size_t nb = parent_box.size();
  std::vector<int> depth(nb, 0);
  for (std::size_t i = 0; i < nb; ++i)
    for (int p = parent_box[i]; p >= 0; p = parent_box[static_cast<std::size_t>(p)]) ++depth[i];
  order.resize(nb);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
  std::vector<int> level_of_box(nb);
  for (std::size_t k = 0; k < nb; ++k) level_of_box[order[k]] = static_cast<int>(k) + 1;
  return level_of_box;
}

// Thickness of a level's buffer shell of box `ref`: buffer_width x h, or with buffer_rounding =
// "whole_dp" that thickness rounded up to a whole number of the level's dp, as DualSPHysics
// lays its buffers (at h = 1.3 dp: 4h = 5.2 dp -> 6 dp, 2h = 2.6 dp -> 3 dp). A width within
// 1e-9 dp of a whole number is that number (4h at h = 1.25 dp is 5 dp, not 6).
inline double shell_width(const RefinementBox& ref, double h, double dp) {
  const double w = ref.buffer_width * h;
  if (ref.buffer_rounding == BufferRounding::none) return w;
  return std::ceil(w / dp - 1e-9) * dp;
}

// Child level L of parent P from box i: dp, h, region, and the parent's record of the child.
// The child's shell and the kernel support around it must lie in the parent's fluid, and the
// parent's shell must fit inside the box.
template <int D>
void add_child_level(const CaseSpec& spec, std::size_t i, int lv, int pl, LevelLayout<D>& L,
                     LevelLayout<D>& P) {
  const RefinementBox& ref = spec.refinements[i];
  L.dp = P.dp / ref.dp_ratio;
  L.h = spec.h_over_dp * L.dp;
  L.region.parent = pl;
  L.region.has_box = true;
  L.region.box = box_of<D>(ref);
  L.region.width = shell_width(ref, L.h, L.dp);
  const double w_parent = shell_width(ref, P.h, P.dp);
  P.region.children.push_back({lv, L.region.box, w_parent});
  const Box<D> shell = L.region.box.grown(L.region.width + 2.0 * L.h);
  if (P.region.has_box && !P.region.box.contains_box(shell)) {
    throw refinement_error(i, "min",
                           fmt::format("box with its buffer ({:g} m) does not fit inside its "
                                       "parent box",
                                       L.region.width + 2 * L.h));
  }
  for (int a = 0; a < D; ++a) {
    const double side = L.region.box.hi[a] - L.region.box.lo[a];
    if (side < 2.0 * w_parent + 2.0 * P.h) {
      throw refinement_error(i, "max",
                             fmt::format("box side {:g} m along axis {} is smaller than the "
                                         "parent's two buffers and support "
                                         "({:g} m): enlarge the box or lower buffer_width",
                                         side, a, 2.0 * w_parent + 2.0 * P.h));
    }
  }
}

}  // namespace

template <int D>
std::vector<LevelLayout<D>> make_level_layout(const CaseSpec& spec) {
  const std::size_t nb = spec.refinements.size();
  const std::vector<int> parent_box = parent_boxes<D>(spec.refinements);
  std::vector<std::size_t> order;
  const std::vector<int> level_of_box = box_levels(parent_box, order);
  std::vector<LevelLayout<D>> levels(nb + 1);
  levels[0].dp = spec.dp;
  levels[0].h = spec.h_over_dp * spec.dp;
  for (std::size_t k = 0; k < nb; ++k) {
    const std::size_t i = order[k];
    const int lv = level_of_box[i];
    const int pl = parent_box[i] < 0 ? 0 : level_of_box[static_cast<std::size_t>(parent_box[i])];
    add_child_level<D>(spec, i, lv, pl, levels[static_cast<std::size_t>(lv)],
                       levels[static_cast<std::size_t>(pl)]);
  }
  // Sibling boxes: their shells (with support) must not meet.
  for (std::size_t i = 0; i < nb; ++i)
    for (std::size_t j = i + 1; j < nb; ++j) {
      if (parent_box[i] != parent_box[j]) continue;
      const auto& Li = levels[static_cast<std::size_t>(level_of_box[i])];
      const auto& Lj = levels[static_cast<std::size_t>(level_of_box[j])];
      if (Li.region.box.grown(Li.region.width + 2 * Li.h)
              .overlaps(Lj.region.box.grown(Lj.region.width + 2 * Lj.h)))
        throw refinement_error(
            j, "min",
            fmt::format("box and its buffer come within 2h of refinement.{} (same parent level)",
                        i));
    }
  return levels;
}

template std::vector<LevelLayout<2>> make_level_layout<2>(const CaseSpec&);
template std::vector<LevelLayout<3>> make_level_layout<3>(const CaseSpec&);

}  // namespace vrsph
