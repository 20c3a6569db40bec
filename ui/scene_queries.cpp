#include "ui/scene_queries.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_set>

#include "engine/document/commands.h"
#include "engine/document/roles.h"
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

namespace {

bool quarterTurns(const Transform& t) {
  for (int a = 0; a < 3; ++a)
    if (std::fmod(std::fabs(t.rotateDegrees[a]), 90.0) != 0.0) return false;
  return true;
}

bool subtreeBoundsTight(const NodePtr& node, const NodePtr& root, int depth) {
  if (!node || !node->visible) return true;  // takes no part
  if (depth > 64 || !quarterTurns(node->transform)) return false;
  if (node->kind == NodeKind::Instance)
    return subtreeBoundsTight(findNode(root, node->instanceOf), root, depth + 1);
  switch (node->kind) {
    case NodeKind::Union:
    case NodeKind::Shell:
    case NodeKind::Array:
    case NodeKind::Mirror:
      break;
    case NodeKind::Offset:
      if (node->amount < 0.0) return false;
      break;
    default:
      if (isOperation(node->kind)) return false;  // a cut, an intersection, a round, a fillet...
      return true;                                // a leaf turned by quarter turns
  }
  for (const NodePtr& child : node->children)
    if (!subtreeBoundsTight(child, root, depth + 1)) return false;
  return true;
}

}  // namespace

bool selectionBoundsTight(const NodePtr& root, const std::vector<NodeId>& selection) {
  for (NodeId id : selection) {
    std::vector<const Node*> path;
    if (!pathToNode(root, id, &path)) continue;
    for (const Node* above : path)
      if (!quarterTurns(above->transform)) return false;
    if (!subtreeBoundsTight(findNode(root, id), root, 0)) return false;
  }
  return true;
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

void forEachVisibleLeaf(const NodePtr& root,
                        const std::function<void(const NodePtr&, const VisibleLeaf&)>& visit) {
  // One walk down the tree carrying the parent's world matrix and whether the parts below take
  // material away (a cutter's parity), as removesMaterial and parentWorldMatrix would find for
  // each leaf from the root: linear in the nodes (it was quadratic: each leaf looked up from the
  // root again).
  std::function<void(const NodePtr&, const glm::dmat4&, bool, int)> walk =
      [&](const NodePtr& node, const glm::dmat4& parent, bool removes, int depth) {
        if (!node || !node->visible || depth > 512) return;  // hidden: it and all below it
        if (!isOperation(node->kind)) {
          const Bounds b = nodeBounds(node, root, parent);
          if (!b.empty()) visit(node, VisibleLeaf{b, parent, removes});
          return;
        }
        // A mirror that drops its original shows its children as their image.
        const glm::dmat4 below = parent * node->transform.matrix() *
                                 firstPlacement(patternOf(node->kind), node->pattern);
        for (size_t c = 0; c < node->children.size(); ++c)
          walk(node->children[c], below,
               removes != (childRole(*node, static_cast<int>(c)) == ChildRole::Cut), depth + 1);
      };
  walk(root, glm::dmat4(1.0), false, 0);
}

namespace {

// Calls visit(leaf, its world box) for every visible leaf that adds material (removesMaterial
// false) and shows something (forEachVisibleLeaf).
void forEachAddingLeafBox(const NodePtr& root,
                          const std::function<void(const NodePtr&, const Bounds&)>& visit) {
  forEachVisibleLeaf(root, [&](const NodePtr& leaf, const VisibleLeaf& at) {
    if (!at.removes) visit(leaf, at.box);
  });
}

}  // namespace

std::optional<double> topOfPartsUnder(const NodePtr& root, glm::dvec2 xy) {
  std::optional<double> top;
  forEachAddingLeafBox(root, [&](const NodePtr&, const Bounds& b) {
    if (xy.x < b.min.x || xy.x > b.max.x || xy.y < b.min.y || xy.y > b.max.y) return;
    top = top ? std::max(*top, b.max.z) : b.max.z;
  });
  return top;
}

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
                                                              const Transform& primaryNow,
                                                              std::vector<NodeId>* sheared) {
  const NodePtr node = findNode(start, primary);
  if (!node) return {};
  const glm::dmat4 primaryParent = parentWorldMatrix(start, primary);
  const glm::dmat4 motion =
      primaryParent * primaryNow.matrix() * glm::inverse(primaryParent * node->transform.matrix());
  std::vector<NodeId> bent;
  std::vector<std::pair<NodeId, Transform>> out = movedSelection(start, selection, motion, &bent);
  const auto leftOut = [&](NodeId id) {
    return id == primary || isInSubtree(start, id, primary) || isInSubtree(start, primary, id);
  };
  out.erase(std::remove_if(
                out.begin(), out.end(),
                [&](const std::pair<NodeId, Transform>& moved) { return leftOut(moved.first); }),
            out.end());
  if (sheared)
    for (NodeId id : bent)
      if (!leftOut(id)) sheared->push_back(id);
  return out;
}

std::vector<NodeId> outermostSelected(const NodePtr& root, const std::vector<NodeId>& selection) {
  // One walk of the tree (tree edges), whatever the selection's size: it runs every frame.
  const std::unordered_set<NodeId> selected(selection.begin(), selection.end());
  std::unordered_set<NodeId> outer;
  std::vector<std::pair<const Node*, bool>> stack;  // node, whether a selected node holds it
  if (root) stack.push_back({root.get(), false});
  while (!stack.empty()) {
    const auto [node, held] = stack.back();
    stack.pop_back();
    const bool here = selected.count(node->id) > 0;
    if (here && !held) outer.insert(node->id);
    for (const NodePtr& c : node->children) stack.push_back({c.get(), held || here});
  }
  std::vector<NodeId> out;
  for (NodeId id : selection)
    if (outer.erase(id)) out.push_back(id);  // in the selection's order, each once
  return out;
}

std::vector<std::pair<NodeId, Transform>> movedSelection(const NodePtr& start,
                                                         const std::vector<NodeId>& selection,
                                                         const glm::dmat4& motion,
                                                         std::vector<NodeId>* sheared) {
  std::vector<std::pair<NodeId, Transform>> out;
  for (NodeId id : outermostSelected(start, selection)) {
    const NodePtr node = findNode(start, id);
    if (!node) continue;
    const glm::dmat4 parent = parentWorldMatrix(start, id);
    const glm::dmat4 world = motion * parent * node->transform.matrix();
    bool exact = true;
    out.emplace_back(id, transformNear(glm::inverse(parent) * world, node->transform, &exact));
    if (!exact && sheared) sheared->push_back(id);
  }
  return out;
}

size_t independentSelectionCount(const NodePtr& root, const std::vector<NodeId>& selection) {
  return outermostSelected(root, selection).size();
}

NodeId selectedHolder(const NodePtr& root, const std::vector<NodeId>& selection, NodeId id) {
  std::vector<const Node*> path;  // from the root to `id`
  if (!pathToNode(root, id, &path)) return id;
  for (const Node* n : path)
    if (std::find(selection.begin(), selection.end(), n->id) != selection.end()) return n->id;
  return id;
}

double groundGridStep(const Bounds& scene, double emptySpan) {
  const glm::dvec3 size = scene.empty() ? glm::dvec3(emptySpan) : scene.size();
  return niceLength(std::max({size.x, size.y, size.z, 1e-9}) / 8.0);
}

glm::dvec3 ownBottom(const NodePtr& node, const NodePtr& root) {
  auto own = std::make_shared<Node>(*node);
  own->transform = Transform();
  const Bounds b = nodeBounds(own, root, glm::dmat4(1.0));
  return b.empty() ? glm::dvec3(0.0) : glm::dvec3(b.center().x, b.center().y, b.min.z);
}

Transform keptResting(const NodePtr& before, const NodePtr& after, NodeId id, Rest* rest) {
  if (rest) *rest = Rest();
  const NodePtr node = findNode(after, id), was = findNode(before, id);
  if (!node || !was) return Transform();
  const Bounds wasBox = selectionBounds(before, {id}), nowBox = selectionBounds(after, {id});
  if (wasBox.empty() || nowBox.empty()) return node->transform;
  const double size = std::max(wasBox.longestSide(), nowBox.longestSide());
  const glm::dmat4 parent = parentWorldMatrix(after, id);
  Transform t = node->transform;
  if (std::fabs(wasBox.min.z) <= 1e-6 * size) {  // on the ground
    if (rest) rest->onGround = true;
    if (nowBox.min.z == wasBox.min.z) return t;
    // The world's z in the parent's frame: the part's translation moves along it.
    t.translate += glm::dvec3(glm::inverse(parent) * glm::dvec4(0.0, 0.0, -nowBox.min.z, 0.0));
    if (rest) rest->moved = true;
    return t;
  }
  if (isOperation(node->kind) || removesMaterial(before, id)) return t;
  // Mirrored (a scale that changed sign): the bottom of its own box is now its top.
  if (glm::any(glm::lessThanEqual(was->transform.scale * node->transform.scale, glm::dvec3(0.0))))
    return t;
  // On another part: the bottom of its own box lies in the box of a visible part that adds
  // material (a part dropped on a surface turned its own z to the surface's normal and set that
  // bottom on it).
  const glm::dvec3 bottomWas = glm::dvec3(parentWorldMatrix(before, id) * was->transform.matrix() *
                                          glm::dvec4(ownBottom(was, before), 1.0));
  // A ten-thousandth of the larger of the two: a point picked on a surface carries the depth
  // buffer's precision (a block dropped on a plate's top at 8 stood at 8.00002, and resized it
  // did not count as resting there: an artist's test).
  NodeId on = 0;
  forEachAddingLeafBox(before, [&](const NodePtr& leaf, const Bounds& b) {
    if (on || leaf->id == id || isInSubtree(before, leaf->id, id)) return;
    const double tolerance = 1e-4 * std::max(size, b.longestSide());
    for (int a = 0; a < 3; ++a)
      if (bottomWas[a] < b.min[a] - tolerance || bottomWas[a] > b.max[a] + tolerance) return;
    on = leaf->id;
  });
  if (!on) return t;
  if (rest) rest->on = on;
  const glm::dvec3 bottomNow =
      glm::dvec3(parent * node->transform.matrix() * glm::dvec4(ownBottom(node, after), 1.0));
  const glm::dvec3 back = bottomWas - bottomNow;
  if (glm::length(back) <= 1e-12 * size) return t;
  t.translate += glm::dvec3(glm::inverse(parent) * glm::dvec4(back, 0.0));
  if (rest) rest->moved = true;
  return t;
}

PatternParams mirrorPlaneAt(const NodePtr& root, NodeId id, MirrorPlaneAt where) {
  const NodePtr node = findNode(root, id);
  if (!node) return PatternParams();
  PatternParams p = node->pattern;
  if (patternOf(node->kind) != Pattern::Mirror) return p;
  const int a = std::clamp(p.axis, 0, 2);
  if (where == MirrorPlaneAt::Origin) {
    p.center[a] = 0.0;
    return p;
  }
  // The children's placed results in the mirror's own frame (the frame its placements use).
  Bounds parts;
  for (const NodePtr& child : node->children)
    parts.include(nodeBounds(child, root, glm::dmat4(1.0)));
  if (parts.empty()) return p;
  p.center[a] = where == MirrorPlaneAt::PartsLowSide    ? parts.min[a]
                : where == MirrorPlaneAt::PartsHighSide ? parts.max[a]
                                                        : parts.center()[a];
  return p;
}

std::optional<CircularAxisPlace> circularAxisThroughNeighbours(const NodePtr& root, NodeId id) {
  const NodePtr node = findNode(root, id);
  NodeLocation where;
  if (!node || patternOf(node->kind) != Pattern::Circular || !locateNode(root, id, &where) ||
      !where.parent)
    return std::nullopt;
  const Node& parent = *where.parent;
  const ChildRole role = childRole(parent, where.index);
  std::vector<NodePtr> neighbours;
  if (role == ChildRole::Cut || role == ChildRole::Intersect)
    neighbours.push_back(parent.children.front());
  else
    for (const NodePtr& sibling : parent.children)
      if (sibling.get() != node.get()) neighbours.push_back(sibling);
  // Their boxes in the array's own frame: they sit in the parent's frame, the array's own
  // transform between the two.
  const glm::dmat4 intoArray = glm::inverse(node->transform.matrix());
  Bounds box;
  std::vector<const Node*> shown;
  for (const NodePtr& n : neighbours) {
    const Bounds b = nodeBounds(n, root, intoArray);
    if (b.empty()) continue;
    box.include(b);
    shown.push_back(n.get());
  }
  if (box.empty()) return std::nullopt;
  CircularAxisPlace place;
  place.params = node->pattern;
  const int a = std::clamp(place.params.axis, 0, 2);
  for (int k = 0; k < 3; ++k)
    if (k != a) place.params.center[k] = box.center()[k];
  // The parts' middle in the array's frame, and its distance from each axis.
  Bounds parts;
  for (const NodePtr& child : node->children)
    parts.include(nodeBounds(child, root, glm::dmat4(1.0)));
  if (!parts.empty()) {
    const auto radius = [&](const glm::dvec3& centre) {
      glm::dvec3 d = parts.center() - centre;
      d[a] = 0.0;
      return glm::length(d);
    };
    place.radiusBefore = radius(node->pattern.center);
    place.radiusAfter = radius(place.params.center);
  }
  place.around = nodeLabel(*shown.front());
  if (shown.size() > 1) place.around += " and " + std::to_string(shown.size() - 1) + " more";
  return place;
}

FaceSnap snappedToBoxFace(const NodePtr& root, NodeId leaf, const glm::dvec3& point,
                          const glm::dvec3& normal) {
  const FaceSnap asPicked{point, normal};
  const double length = glm::length(normal);
  if (!(length > 0.0)) return asPicked;
  int axis = -1;
  for (int a = 0; a < 3; ++a)
    if (std::fabs(normal[a]) / length > std::cos(glm::radians(2.0))) axis = a;
  if (axis < 0 || !findNode(root, leaf)) return asPicked;
  const Bounds box = selectionBounds(root, {leaf});
  if (box.empty()) return asPicked;
  const bool outward = (normal[axis] > 0.0) != removesMaterial(root, leaf);
  const double face = outward ? box.max[axis] : box.min[axis];
  if (!(std::fabs(point[axis] - face) <= 1e-4 * box.longestSide())) return asPicked;
  FaceSnap snapped = asPicked;
  snapped.point[axis] = face;
  snapped.normal = glm::dvec3(0.0);
  snapped.normal[axis] = normal[axis] > 0.0 ? 1.0 : -1.0;
  return snapped;
}

double niceLength(double approximate) {
  if (!(approximate > 0) || !std::isfinite(approximate)) return 1.0;
  double p = std::pow(10.0, std::floor(std::log10(approximate)));
  double m = approximate / p;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

}  // namespace strata::ui
