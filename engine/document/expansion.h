// What evaluating a tree will visit, counted before it is performed. Instances expand their
// target once per reference, so a small file can describe an exponential tree (an instance of
// a union of two instances of ..., doubled forty times): every walk that follows instances
// must first ask measureExpansion, which costs O(nodes) however large the expansion is.
//
// Threads: any; reads an immutable tree.
#pragma once

#include <cstdint>
#include <string>

#include "engine/document/node.h"

namespace strata {

struct TreeExpansion {
  // Saturate at kSaturated (about 1.8e19) instead of overflowing.
  uint64_t leaves = 0;         // leaf visits of an evaluation (visible leaves, through instances)
  uint64_t nodes = 0;          // node visits of an evaluation (operations included)
  uint64_t modifiers = 0;      // visits of modifier nodes (offset, shell, round...), in nodes too
  int depth = 0;               // longest root-to-leaf path through instances (a leaf alone: 1)
  bool missingTarget = false;  // an instance refers to no node of the tree
  bool cycle = false;          // an instance refers to one of its ancestors
};
constexpr uint64_t kSaturated = ~uint64_t(0);

// Counts what an evaluation of `root` visits, following visibility as the evaluator does
// (hidden nodes count only when reached through an instance). Iterative, memoised per node.
TreeExpansion measureExpansion(const NodePtr& root);

// Throws strata::Error when the expansion exceeds `maxLeaves` visible leaves or kMaxTreeDepth
// levels, or has an instance cycle or a missing target. The message names the count and how to
// raise the limit (`--max-leaves`, or the scene's "maxLeaves" setting). Returns the measure.
TreeExpansion checkExpansion(const NodePtr& root, uint64_t maxLeaves);

// Text for a count that may be saturated: "12,345" or "more than 10^19".
std::string countText(uint64_t count);

}  // namespace strata
