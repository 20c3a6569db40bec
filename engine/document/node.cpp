#include "engine/document/node.h"

#include <algorithm>

#include "engine/document/expansion.h"

namespace strata {

int treeDepth(const NodePtr& root) {
  return measureExpansion(root).depth;
}

NodePtr findNode(const NodePtr& root, NodeId id) {
  if (!root) return nullptr;
  if (root->id == id) return root;
  for (const auto& c : root->children)
    if (NodePtr found = findNode(c, id)) return found;
  return nullptr;
}

NodeId maxNodeId(const NodePtr& root) {
  if (!root) return 0;
  NodeId m = root->id;
  for (const auto& c : root->children) m = std::max(m, maxNodeId(c));
  return m;
}

}  // namespace strata
