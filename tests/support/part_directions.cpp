#include "tests/support/part_directions.h"

namespace strata::test {
namespace {

struct Walk {
  const NodePtr& root;
  std::map<NodeId, std::set<int>>& out;

  // Signs of material added inside node's subtree, as the node is reached on this path: +1 grows
  // the result, -1 shrinks it, 0 either (under a shell).
  void children(const Node& node, int sign) {
    for (size_t i = 0; i < node.children.size(); ++i) {
      const NodePtr& child = node.children[i];
      if (!child->visible) continue;
      const bool cutter = node.kind == NodeKind::Difference && i > 0;
      // A shell is its children minus their inward offset: growing them moves both surfaces.
      const int inside = node.kind == NodeKind::Shell ? 0 : cutter ? -sign : sign;
      // The part itself: another operand of an intersection removes material.
      const int own = node.kind == NodeKind::Intersection ? -inside : inside;
      record(child->id, own);
      part(*child, inside);
    }
  }

  void part(const Node& node, int sign) {
    if (node.kind == NodeKind::Instance) {
      const NodePtr target = findNode(root, node.instanceOf);
      if (target) children(*target, sign);  // the template's own parts, as the instance uses them
      return;
    }
    children(node, sign);
  }

  void record(NodeId id, int sign) {
    if (sign == 0) {
      out[id].insert(+1);
      out[id].insert(-1);
    } else {
      out[id].insert(sign);
    }
  }
};

}  // namespace

std::map<NodeId, std::set<int>> partDirections(const NodePtr& root) {
  std::map<NodeId, std::set<int>> out;
  if (root && root->visible) Walk{root, out}.part(*root, +1);
  return out;
}

}  // namespace strata::test
