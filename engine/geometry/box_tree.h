// A static tree of axis-aligned boxes for "which boxes contain this point" queries: built once
// in O(n log n) by median splits, queried in O(log n + hits) for boxes that do not pile up.
// Used where a loop over all pairs would be quadratic (shell nesting in prepareMesh).
//
// Threads: immutable after construction; queries may run on any number of threads at once.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/geometry/mesh.h"

namespace strata {

class BoxTree {
 public:
  // boxes[i] is item i; empty boxes are never reported.
  explicit BoxTree(const std::vector<Bounds>& boxes);

  // Calls visit(i) for every item whose box contains p (boundary included), in no set order.
  template <typename Visit>
  void forEachContaining(const glm::dvec3& p, Visit&& visit) const {
    if (nodes_.empty()) return;
    // Median splits keep the tree balanced: depth <= log2(items) + 1, and the stack holds at
    // most one pending sibling per level.
    uint32_t stack[80];
    int size = 0;
    stack[size++] = 0;
    while (size > 0) {
      const Node& node = nodes_[stack[--size]];
      if (!contains(node.box, p)) continue;
      if (node.count > 0) {
        for (uint32_t k = node.first; k < node.first + node.count; ++k)
          if (contains(boxes_[items_[k]], p)) visit(items_[k]);
      } else {
        stack[size++] = node.first;
        stack[size++] = node.first + 1;
      }
    }
  }

  static bool contains(const Bounds& b, const glm::dvec3& p) {
    return p.x >= b.min.x && p.y >= b.min.y && p.z >= b.min.z && p.x <= b.max.x && p.y <= b.max.y &&
           p.z <= b.max.z;
  }

 private:
  // An inner node (count == 0) has its children at first and first + 1; a leaf holds
  // items_[first .. first + count).
  struct Node {
    Bounds box;
    uint32_t first = 0;
    uint32_t count = 0;
  };
  std::vector<Bounds> boxes_;
  std::vector<uint32_t> items_;
  std::vector<Node> nodes_;
};

}  // namespace strata
