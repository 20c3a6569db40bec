#include "ui/scene_queries.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "engine/document/commands.h"
#include "engine/eval/evaluator.h"

namespace strata::ui {
namespace {

Bounds computeSceneBounds(const NodePtr& root);

}  // namespace

Bounds selectionBounds(const NodePtr& root, const std::vector<NodeId>& selection) {
  Bounds b;
  for (NodeId id : selection) {
    NodePtr node = findNode(root, id);
    if (!node) continue;
    Bounds nb = nodeBounds(node, root, parentWorldMatrix(root, id));
    if (nb.empty() && !node->visible) {
      // A hidden node: show where it would be.
      auto shown = std::make_shared<Node>(*node);
      shown->visible = true;
      nb = nodeBounds(shown, root, parentWorldMatrix(root, id));
    }
    b.include(nb);
  }
  return b;
}

Bounds sceneBounds(const NodePtr& root) {
  if (!root) return Bounds();
  // Asked several times a frame; the tree is immutable, so remember the last answer.
  thread_local std::weak_ptr<const Node> lastRoot;
  thread_local Bounds lastBounds;
  if (lastRoot.lock() == root) return lastBounds;
  Bounds b = computeSceneBounds(root);
  lastRoot = root;
  lastBounds = b;
  return b;
}

namespace {
Bounds computeSceneBounds(const NodePtr& root) {
  Bounds b = nodeBounds(root, root, glm::dmat4(1.0));
  if (!b.empty()) return b;
  for (NodeId id : treeOrder(root)) {
    NodePtr node = findNode(root, id);
    if (node && !isOperation(node->kind) && node->visible)
      b.include(nodeBounds(node, root, parentWorldMatrix(root, id)));
  }
  return b;
}
}  // namespace

LeafStyleTable leafStyles(const NodePtr& root, const std::vector<NodeId>& selection) {
  LeafStyleTable table;
  if (!root) return table;
  const size_t size = size_t(maxNodeId(root)) + 1;
  table.color.assign(size, glm::vec3(0.8f));
  table.selected.assign(size, 0);
  std::function<void(const NodePtr&, bool, int)> visit = [&](const NodePtr& node, bool selected,
                                                             int depth) {
    if (!node || depth > 512) return;
    selected =
        selected || std::find(selection.begin(), selection.end(), node->id) != selection.end();
    table.color[node->id] = node->color;
    if (selected) table.selected[node->id] = 1;
    if (node->kind == NodeKind::Instance && selected)
      visit(findNode(root, node->instanceOf), true, depth + 1);
    for (const auto& c : node->children) visit(c, selected, depth + 1);
  };
  visit(root, false, 0);
  return table;
}

std::vector<std::pair<NodeId, Transform>> followingTransforms(const NodePtr& start,
                                                              const std::vector<NodeId>& selection,
                                                              NodeId primary,
                                                              const Transform& primaryNow) {
  const NodePtr node = findNode(start, primary);
  if (!node) return {};
  const glm::dmat4 primaryParent = parentWorldMatrix(start, primary);
  const glm::dmat4 motion =
      primaryParent * primaryNow.matrix() * glm::inverse(primaryParent * node->transform.matrix());
  std::vector<std::pair<NodeId, Transform>> out = movedSelection(start, selection, motion);
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&](const std::pair<NodeId, Transform>& moved) {
                             const NodeId id = moved.first;
                             return id == primary || isInSubtree(start, id, primary) ||
                                    isInSubtree(start, primary, id);
                           }),
            out.end());
  return out;
}

namespace {
bool insideAnotherSelected(const NodePtr& root, const std::vector<NodeId>& selection, NodeId id) {
  for (NodeId other : selection)
    if (other != id && isInSubtree(root, other, id)) return true;
  return false;
}
}  // namespace

std::vector<std::pair<NodeId, Transform>> movedSelection(const NodePtr& start,
                                                         const std::vector<NodeId>& selection,
                                                         const glm::dmat4& motion,
                                                         std::vector<NodeId>* sheared) {
  std::vector<std::pair<NodeId, Transform>> out;
  for (NodeId id : selection) {
    const NodePtr node = findNode(start, id);
    if (!node || insideAnotherSelected(start, selection, id)) continue;
    const glm::dmat4 parent = parentWorldMatrix(start, id);
    const glm::dmat4 world = motion * parent * node->transform.matrix();
    bool exact = true;
    out.emplace_back(id, transformNear(glm::inverse(parent) * world, node->transform, &exact));
    if (!exact && sheared) sheared->push_back(id);
  }
  return out;
}

size_t independentSelectionCount(const NodePtr& root, const std::vector<NodeId>& selection) {
  size_t count = 0;
  for (NodeId id : selection)
    if (findNode(root, id) && !insideAnotherSelected(root, selection, id)) ++count;
  return count;
}

std::vector<NodeId> outermostSelected(const NodePtr& root, const std::vector<NodeId>& selection) {
  std::vector<NodeId> out;
  for (NodeId id : selection)
    if (findNode(root, id) && !insideAnotherSelected(root, selection, id)) out.push_back(id);
  return out;
}

NodeId selectedHolder(const NodePtr& root, const std::vector<NodeId>& selection, NodeId id) {
  NodeId holder = id;
  for (NodeId other : selection)
    if (other != holder && isInSubtree(root, other, holder)) holder = other;
  // A holder found later may hold an earlier one: settle on the outermost.
  for (bool changed = true; changed;) {
    changed = false;
    for (NodeId other : selection)
      if (other != holder && isInSubtree(root, other, holder)) {
        holder = other;
        changed = true;
      }
  }
  return holder;
}

double groundGridStep(const Bounds& scene) {
  const glm::dvec3 size = scene.empty() ? glm::dvec3(10.0) : scene.size();
  return niceLength(std::max({size.x, size.y, size.z, 1e-9}) / 8.0);
}

const char* unitSymbol(const std::string& unit) {
  if (unit == "millimetre" || unit == "millimeter") return "mm";
  if (unit == "centimetre" || unit == "centimeter") return "cm";
  if (unit == "metre" || unit == "meter") return "m";
  if (unit == "inch") return "in";
  return unit.c_str();
}

double niceLength(double approximate) {
  if (!(approximate > 0) || !std::isfinite(approximate)) return 1.0;
  double p = std::pow(10.0, std::floor(std::log10(approximate)));
  double m = approximate / p;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

}  // namespace strata::ui
