#include "engine/document/node.h"

#include <algorithm>

#include "engine/document/expansion.h"

namespace strata {

std::string nodeLabel(const Node& node) {
  const std::string kind = kindLabel(node.kind);
  if (node.name.empty()) return kind + " #" + std::to_string(node.id);
  return kind + " '" + node.name + "'";
}

std::string quotedName(const Node& node) {
  return "\"" + (node.name.empty() ? nodeLabel(node) : node.name) + "\"";
}

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

namespace {

// The visible node `id` strictly below `node`, through visible nodes only.
NodePtr findVisibleBelow(const NodePtr& node, NodeId id) {
  for (const auto& c : node->children) {
    if (!c->visible) continue;
    if (c->id == id) return c;
    if (NodePtr found = findVisibleBelow(c, id)) return found;
  }
  return nullptr;
}

// `node` with the node `id` below it hidden (the path to it copied, the rest shared).
NodePtr hiding(const NodePtr& node, NodeId id) {
  for (size_t i = 0; i < node->children.size(); ++i) {
    const NodePtr& c = node->children[i];
    NodePtr replaced;
    if (c->id == id) {
      auto hidden = std::make_shared<Node>(*c);
      hidden->visible = false;
      replaced = hidden;
    } else if (findNode(c, id)) {
      replaced = hiding(c, id);
    } else {
      continue;
    }
    auto copy = std::make_shared<Node>(*node);
    copy->children[i] = replaced;
    return copy;
  }
  return node;
}

}  // namespace

NodePtr shellOpening(const NodePtr& shell) {
  if (!shell || shell->kind != NodeKind::Shell || shell->opening == 0) return nullptr;
  return findVisibleBelow(shell, shell->opening);
}

NodePtr withoutOpening(const NodePtr& shell) {
  if (!shellOpening(shell)) return nullptr;
  auto wall = std::make_shared<Node>(*hiding(shell, shell->opening));
  wall->kind = NodeKind::Union;
  wall->opening = 0;
  wall->amount = 0.0;
  wall->id = 0;  // not the shell: what the editor keeps by id is the shell's own result
  wall->name = shell->name + " (without its opening)";
  return wall;
}

NodeId maxNodeId(const NodePtr& root) {
  if (!root) return 0;
  NodeId m = root->id;
  for (const auto& c : root->children) m = std::max(m, maxNodeId(c));
  return m;
}

}  // namespace strata
