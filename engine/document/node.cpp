#include "engine/document/node.h"

#include <algorithm>

namespace strata {
namespace {
int depthOf(const NodePtr& node, const NodePtr& root, int guard) {
  if (!node || guard > 100000) return 0;
  if (node->kind == NodeKind::Instance) {
    NodePtr target = findNode(root, node->instanceOf);
    return target ? depthOf(target, root, guard + 1) : 1;
  }
  int deepest = 0;
  for (const auto& c : node->children) deepest = std::max(deepest, depthOf(c, root, guard + 1));
  return deepest + 1;
}
}  // namespace

int treeDepth(const NodePtr& root) {
  return depthOf(root, root, 0);
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
