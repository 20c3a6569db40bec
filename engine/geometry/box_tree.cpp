#include "engine/geometry/box_tree.h"

#include <algorithm>

namespace strata {
namespace {
constexpr uint32_t kLeafSize = 4;
}

BoxTree::BoxTree(const std::vector<Bounds>& boxes) : boxes_(boxes) {
  for (uint32_t i = 0; i < boxes_.size(); ++i)
    if (!boxes_[i].empty()) items_.push_back(i);
  if (items_.empty()) return;
  // Iterative build: each work item is a node to fill with items_[begin .. end).
  struct Work {
    uint32_t node, begin, end;
  };
  nodes_.reserve(2 * items_.size() / kLeafSize + 2);
  nodes_.emplace_back();
  std::vector<Work> work{{0, 0, uint32_t(items_.size())}};
  while (!work.empty()) {
    const Work w = work.back();
    work.pop_back();
    Bounds box, centres;
    for (uint32_t k = w.begin; k < w.end; ++k) {
      box.include(boxes_[items_[k]]);
      centres.include(boxes_[items_[k]].center());
    }
    nodes_[w.node].box = box;
    const glm::dvec3 spread = centres.size();
    if (w.end - w.begin <= kLeafSize || (spread.x <= 0.0 && spread.y <= 0.0 && spread.z <= 0.0)) {
      // Few items, or all centred on one point (no split separates them): a leaf.
      nodes_[w.node].first = w.begin;
      nodes_[w.node].count = w.end - w.begin;
      continue;
    }
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0
                     : spread.y >= spread.z                       ? 1
                                                                  : 2;
    const uint32_t mid = w.begin + (w.end - w.begin) / 2;
    std::nth_element(items_.begin() + w.begin, items_.begin() + mid, items_.begin() + w.end,
                     [&](uint32_t a, uint32_t b) {
                       return boxes_[a].center()[axis] < boxes_[b].center()[axis];
                     });
    const uint32_t children = uint32_t(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[w.node].first = children;
    nodes_[w.node].count = 0;
    work.push_back({children, w.begin, mid});
    work.push_back({children + 1, mid, w.end});
  }
}

}  // namespace strata
