#include "engine/document/node.h"

#include <algorithm>

namespace strata {
namespace {
struct KindName {
  NodeKind kind;
  const char* name;
};
constexpr KindName kKindNames[] = {
    {NodeKind::Union, "union"},
    {NodeKind::Intersection, "intersection"},
    {NodeKind::Difference, "difference"},
    {NodeKind::Box, "box"},
    {NodeKind::Sphere, "sphere"},
    {NodeKind::Cylinder, "cylinder"},
    {NodeKind::Cone, "cone"},
    {NodeKind::Torus, "torus"},
    {NodeKind::Capsule, "capsule"},
    {NodeKind::Mesh, "mesh"},
    {NodeKind::Instance, "instance"},
};

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

bool isOperation(NodeKind kind) {
  return kind == NodeKind::Union || kind == NodeKind::Intersection || kind == NodeKind::Difference;
}

bool isPrimitive(NodeKind kind) {
  return !isOperation(kind) && kind != NodeKind::Mesh && kind != NodeKind::Instance;
}

const char* kindName(NodeKind kind) {
  for (const auto& k : kKindNames)
    if (k.kind == kind) return k.name;
  return "unknown";
}

bool kindFromName(const std::string& name, NodeKind* kind) {
  for (const auto& k : kKindNames) {
    if (name == k.name) {
      *kind = k.kind;
      return true;
    }
  }
  return false;
}

bool PrimitiveParams::operator==(const PrimitiveParams& o) const {
  return size == o.size && radius == o.radius && topRadius == o.topRadius && height == o.height &&
         majorRadius == o.majorRadius && minorRadius == o.minorRadius && segments == o.segments;
}

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
