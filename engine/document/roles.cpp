#include "engine/document/roles.h"

#include <algorithm>
#include <unordered_set>

#include "engine/document/commands.h"
#include "engine/document/measurement.h"
#include "engine/util/error.h"

namespace strata {
namespace {

std::string quoted(const Node& node) {
  return "\"" + (node.name.empty() ? std::string(kindName(node.kind)) : node.name) + "\"";
}

ChildRole roleForMode(PlaceMode mode) {
  switch (mode) {
    case PlaceMode::Cut:
      return ChildRole::Cut;
    case PlaceMode::Intersect:
      return ChildRole::Intersect;
    default:
      return ChildRole::Add;
  }
}

// What a part placed with `mode` does to `what`, for people.
std::string verbPhrase(PlaceMode mode, const Node& what) {
  switch (mode) {
    case PlaceMode::Cut:
      return "cuts from " + quoted(what);
    case PlaceMode::Intersect:
      return "intersects " + quoted(what);
    default:
      return "adds to " + quoted(what);
  }
}

}  // namespace

ChildRole childRole(const Node& parent, int index) {
  switch (nodeKindInfo(parent.kind).rayOp) {
    case RayOp::Difference:
      return index == 0 ? ChildRole::Base : ChildRole::Cut;
    case RayOp::Intersection:
      return ChildRole::Intersect;
    default:
      return ChildRole::Add;
  }
}

ChildRole roleOf(const NodePtr& root, NodeId id) {
  NodeLocation where;
  if (!locateNode(root, id, &where)) throw Error("there is no node with id " + std::to_string(id));
  if (!where.parent) return ChildRole::Root;
  return childRole(*where.parent, where.index);
}

const char* roleWord(ChildRole role) {
  switch (role) {
    case ChildRole::Root:
      return "root";
    case ChildRole::Base:
      return "base";
    case ChildRole::Cut:
      return "cuts";
    case ChildRole::Intersect:
      return "intersects";
    default:
      return "adds";
  }
}

const char* rolePhrase(ChildRole role) {
  switch (role) {
    case ChildRole::Root:
      return "is the root";
    case ChildRole::Base:
      return "is the base";
    default:
      return roleWord(role);
  }
}

bool removesMaterial(const NodePtr& root, NodeId id) {
  std::vector<const Node*> path;
  if (!pathToNode(root, id, &path)) return false;
  bool removes = false;
  for (size_t i = 1; i < path.size(); ++i) {
    const Node& parent = *path[i - 1];
    for (size_t c = 0; c < parent.children.size(); ++c)
      if (parent.children[c].get() == path[i] &&
          childRole(parent, static_cast<int>(c)) == ChildRole::Cut)
        removes = !removes;
  }
  return removes;
}

namespace {

bool ghostRole(ChildRole role) {
  return role == ChildRole::Cut || role == ChildRole::Intersect;
}

void collectCandidates(const NodePtr& node, std::vector<NodeId>* out) {
  for (size_t i = 0; i < node->children.size(); ++i) {
    const NodePtr& child = node->children[i];
    if (!child->visible) continue;
    if (ghostRole(childRole(*node, static_cast<int>(i)))) out->push_back(child->id);
    collectCandidates(child, out);
  }
}

}  // namespace

std::vector<NodeId> ghostCandidates(const NodePtr& root) {
  std::vector<NodeId> out;
  if (root && root->visible) collectCandidates(root, &out);
  return out;
}

std::vector<NodeId> ghostsOf(const NodePtr& root, const std::vector<NodeId>& selection, bool all) {
  const std::vector<NodeId> candidates = ghostCandidates(root);
  if (all || selection.empty()) return all ? candidates : std::vector<NodeId>{};
  std::unordered_set<NodeId> wanted;
  for (NodeId id : selection) {
    std::vector<const Node*> path;
    if (!pathToNode(root, id, &path)) continue;
    // Along the path: what acts on the part the path runs through.
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      const Node& parent = *path[i];
      for (size_t c = 0; c < parent.children.size(); ++c) {
        const Node* child = parent.children[c].get();
        if (child == path[i + 1]) continue;
        const ChildRole role = childRole(parent, static_cast<int>(c));
        const ChildRole through = [&] {
          for (size_t k = 0; k < parent.children.size(); ++k)
            if (parent.children[k].get() == path[i + 1])
              return childRole(parent, static_cast<int>(k));
          return ChildRole::Add;
        }();
        if ((role == ChildRole::Cut && through == ChildRole::Base) ||
            (role == ChildRole::Intersect && through == ChildRole::Intersect))
          wanted.insert(child->id);
      }
    }
    // The node, the parts holding it that cut or intersect (a leaf inside a cutter shows the
    // whole cutter), and what inside it cuts or intersects.
    for (const Node* onPath : path) wanted.insert(onPath->id);
    for (NodeId inside : treeOrder(findNode(root, id))) wanted.insert(inside);
  }
  std::vector<NodeId> out;
  for (NodeId id : candidates)
    if (wanted.count(id)) out.push_back(id);
  return out;
}

const char* placeModeName(PlaceMode mode) {
  switch (mode) {
    case PlaceMode::Cut:
      return "cut";
    case PlaceMode::Intersect:
      return "intersect";
    default:
      return "add";
  }
}

std::string roleChangesOfKind(const Node& op, NodeKind kind) {
  Node changed = op;
  changed.kind = kind;
  // Children grouped by the role they would take, those whose role changes only.
  std::vector<std::string> byRole[5];
  const int count = int(op.children.size());
  for (int i = 0; i < count; ++i) {
    const ChildRole before = childRole(op, i), after = childRole(changed, i);
    if (before != after) byRole[int(after)].push_back(quoted(*op.children[size_t(i)]));
  }
  const auto listed = [](const std::vector<std::string>& names) {
    std::string text;
    for (size_t i = 0; i < names.size(); ++i)
      text += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return text;
  };
  std::string sentence;
  const auto add = [&](ChildRole role, const char* single, const char* plural) {
    const std::vector<std::string>& names = byRole[int(role)];
    if (names.empty()) return;
    sentence += (sentence.empty() ? "" : "; ") + listed(names) + " " +
                (names.size() == 1 ? single : plural);
  };
  add(ChildRole::Base, "becomes the base", "become the base");
  add(ChildRole::Add, "will add", "will add");
  add(ChildRole::Cut, "will cut", "will cut");
  add(ChildRole::Intersect, "will intersect", "will intersect");
  return sentence;
}

PlaceMode modeKeepingRole(ChildRole role) {
  switch (role) {
    case ChildRole::Cut:
      return PlaceMode::Cut;
    case ChildRole::Intersect:
      return PlaceMode::Intersect;
    default:
      return PlaceMode::Add;
  }
}

PlaceMode modeKeepingEffect(const NodePtr& root, NodeId target, PlaceMode kept, bool removes) {
  if (kept == PlaceMode::Intersect) return kept;
  for (const PlaceMode mode : {kept, PlaceMode::Add, PlaceMode::Cut}) {
    try {
      if (planPlacement(root, target, mode).removesMaterial == removes) return mode;
    } catch (const Error&) {
      return kept;
    }
  }
  return kept;
}

std::string instancesChangedNote(const NodePtr& before, const NodePtr& after, NodeId moved) {
  std::string note;
  int named = 0, more = 0;
  std::vector<const Node*> stack{after.get()};
  while (!stack.empty()) {
    const Node* node = stack.back();
    stack.pop_back();
    for (const NodePtr& c : node->children) stack.push_back(c.get());
    if (node->kind != NodeKind::Instance || node->id == moved) continue;
    const NodeId part = node->instanceOf;
    const NodePtr was = findNode(before, part), now = findNode(after, part);
    if (!was || !now) continue;
    const bool changed = part == moved
                             ? !(was->transform == now->transform)
                             : isInSubtree(before, part, moved) != isInSubtree(after, part, moved);
    if (!changed) continue;
    if (named++ < 2)
      note += std::string(named == 1 ? "; " : ", ") + quoted(*node) + " (an instance of " +
              quoted(*now) + ")";
    else
      ++more;
  }
  if (named == 0) return "";
  if (more > 0) note += " and " + std::to_string(more) + " more";
  return note + (named + more == 1 ? " changes with it" : " change with it");
}

std::string leavesNote(const NodePtr& before, const NodePtr& after, NodeId moved) {
  NodeLocation was;
  if (!locateNode(before, moved, &was) || !was.parent) return "";
  const Node& parent = *was.parent;
  const NodePtr left = findNode(after, parent.id);
  if (!left) return "";
  // Still a child of its parent, or inside a new operation that took a sibling's place there
  // (wrapped with it): it acts there as before, or its role's change is said. Inside a child
  // that was there before (the cutter of a plate dropped into the plate's body), or out of it,
  // it no longer does what it did.
  std::vector<const Node*> path;
  pathToNode(after, moved, &path);
  const auto at =
      std::find_if(path.begin(), path.end(), [&](const Node* n) { return n->id == parent.id; });
  if (at != path.end() && at + 1 != path.end() &&
      ((*(at + 1))->id == moved || !findNode(before, (*(at + 1))->id)))
    return "";
  std::string note;
  switch (childRole(parent, was.index)) {
    case ChildRole::Base:
      note = "; it is no longer the base of " + quoted(parent) +
             (parent.children.size() > 1 ? ", whose cutters then cut nothing" : "");
      break;
    case ChildRole::Cut:
      note = "; it no longer cuts " + quoted(*parent.children.front());
      break;
    case ChildRole::Intersect:
      note = "; it no longer intersects the rest of " + quoted(parent);
      break;
    default:
      note = "; it no longer adds to " + quoted(parent);
      break;
  }
  if (patternOf(parent.kind) != Pattern::None) note += ", nor is repeated by it";
  if (left->children.empty()) note += "; " + quoted(parent) + " is left empty";
  return note;
}

NodeKind operationKindFor(PlaceMode mode) {
  const RayOp wanted = mode == PlaceMode::Cut         ? RayOp::Difference
                       : mode == PlaceMode::Intersect ? RayOp::Intersection
                                                      : RayOp::Union;
  for (const NodeKindInfo& info : nodeKindTable())
    if (info.role == KindRole::Operation && info.rayOp == wanted) return info.kind;
  throw Error("no operation kind applies the Boolean for \"" + std::string(placeModeName(mode)) +
              "\"");
}

PlacePlan planPlacement(const NodePtr& root, NodeId target, PlaceMode mode, IntoUniting into) {
  NodeLocation where;
  if (!locateNode(root, target, &where))
    throw Error("there is no node with id " + std::to_string(target));
  const NodePtr node = findNode(root, target);
  const NodeKind kind = operationKindFor(mode);
  const bool targetRemoves = removesMaterial(root, target);
  PlacePlan plan;
  bool ownCut = false;  // the part's own role is a cutter's
  const bool joinsUniting = into == IntoUniting::Yes && mode == PlaceMode::Add &&
                            isOperation(node->kind) && unitesItsChildren(*node);
  if (joinsUniting && !node->children.empty()) {
    // 1. Into a modifier or a pattern: it joins the children that it changes or repeats.
    plan.parent = target;
    plan.sentence = std::string("joins what ") + quoted(*node) +
                    (patternOf(node->kind) != Pattern::None ? " repeats" : " changes") +
                    " (it becomes one of its parts)";
    plan.removesMaterial = targetRemoves;
  } else if (isOperation(node->kind) && (node->kind == kind || node->children.empty())) {
    // 1. Into an operation of the mode's Boolean, or into an empty operation of any.
    plan.parent = target;
    if (node->children.empty() && nodeKindInfo(node->kind).rayOp == RayOp::Difference)
      plan.sentence = "becomes the base of " + quoted(*node);
    else if (node->children.empty())
      plan.sentence = "fills the empty " + quoted(*node);
    else
      plan.sentence = verbPhrase(mode, *node);
    // A later child of a difference (it has children: it is the mode's) cuts.
    ownCut = mode == PlaceMode::Cut && !node->children.empty();
    plan.removesMaterial = targetRemoves != ownCut;
  } else if (where.parent && childRole(*where.parent, where.index) == roleForMode(mode)) {
    // 2. Beside a target that already plays the mode's role: what it does.
    plan.parent = where.parent->id;
    plan.index = where.index + 1;
    plan.sentence = verbPhrase(mode, *where.parent);
    ownCut = mode == PlaceMode::Cut;
    plan.removesMaterial = targetRemoves;
  } else {
    // 3. A new operation in the target's place (what the target did), the part its second child.
    plan.wrapped = target;
    plan.wrapKind = kind;
    plan.sentence = verbPhrase(mode, *node) + " (a new " + kindName(kind) + " takes its place)";
    ownCut = mode == PlaceMode::Cut;
    plan.removesMaterial = targetRemoves != ownCut;
  }
  // Inside a cutter (an odd number of cutters above it) a part's material goes the other way
  // than its own role says: the sentence says so.
  if (plan.removesMaterial != ownCut)
    plan.sentence += ownCut ? ", inside a cutter: where it lies that cutter cuts nothing, so "
                              "the material there stays (it adds none of its own)"
                            : ", inside a cutter: it takes material away (a hole, not a solid)";
  return plan;
}

NodePtr placePart(const NodePtr& root, const PlacePlan& plan, const NodePtr& part, NodeId groupId) {
  if (plan.wrapped == 0) return insertChild(root, plan.parent, plan.index, part);
  if (findNode(root, groupId) || findNode(part, groupId))
    throw Error("place: the new operation's id is in use");
  NodeLocation where;
  if (!locateNode(root, plan.wrapped, &where))
    throw Error("there is no node with id " + std::to_string(plan.wrapped));
  NodePtr wrapped = findNode(root, plan.wrapped);
  NodePtr group = makeOperationNode(plan.wrapKind, groupId, {wrapped, part});
  if (!where.parent) return group;
  return editNode(root, where.parent->id,
                  [&](Node& parent) { parent.children[static_cast<size_t>(where.index)] = group; });
}

NodePtr removeKeepingRoles(const NodePtr& root, NodeId id, NodeId placeholderId) {
  NodeLocation where;
  if (!locateNode(root, id, &where)) throw Error("there is no node with id " + std::to_string(id));
  if (!where.parent) throw Error("the root cannot be removed");
  const bool baseWithCutters =
      childRole(*where.parent, where.index) == ChildRole::Base && where.parent->children.size() > 1;
  return editNode(root, where.parent->id, [&](Node& parent) {
    auto at = parent.children.begin() + where.index;
    if (!baseWithCutters) {
      parent.children.erase(at);
      return;
    }
    auto placeholder =
        std::make_shared<Node>(*makeOperationNode(NodeKind::Union, placeholderId, {}));
    placeholder->name = "empty base";
    *at = placeholder;
  });
}

NodePtr movePart(const NodePtr& root, NodeId id, NodeId target, PlaceMode mode, NodeId groupId) {
  NodePtr moved = findNode(root, id);
  NodePtr goal = findNode(root, target);
  if (!moved) throw Error("there is no node with id " + std::to_string(id));
  if (!goal) throw Error("there is no node with id " + std::to_string(target));
  if (root->id == id) throw Error("the root " + quoted(*moved) + " cannot be moved");
  if (isInSubtree(root, id, target))
    throw Error("cannot move " + quoted(*moved) + " onto " +
                (target == id ? std::string("itself") : quoted(*goal) + ", which lies inside it"));
  // The placeholder (when one is needed) and the wrapping operation take two fresh ids.
  NodePtr without = removeKeepingRoles(root, id, groupId + 1);
  NodePtr result = placePart(without, planPlacement(without, target, mode), moved, groupId);
  checkInstances(result);
  // It stays where it was in the world: its transform in its new parent is what its old parent
  // made of it (a part dragged out of a moved group jumped by the group's move).
  const glm::dmat4 oldParent = parentWorldMatrix(root, id);
  const glm::dmat4 newParent = parentWorldMatrix(result, id);
  if (newParent != oldParent) {
    bool exact = false;
    const Transform t = transformNear(
        glm::inverse(newParent) * oldParent * moved->transform.matrix(), moved->transform, &exact);
    if (!exact)
      throw Error(quoted(*moved) + " is turned where " + quoted(*goal) +
                  " is stretched (or the reverse): no move, turn and scale keeps its shape "
                  "there. Move it onto a part that is not stretched, or undo the stretch first");
    result = editNode(result, id, [&](Node& n) { n.transform = t; });
  }
  return result;
}

bool unitesItsChildren(const Node& op) {
  return modifierOf(op.kind) != Modifier::None || patternOf(op.kind) != Pattern::None;
}

NodePtr changeRole(const NodePtr& root, NodeId id, PlaceMode mode, NodeId groupId) {
  NodeLocation where;
  if (!locateNode(root, id, &where)) throw Error("there is no node with id " + std::to_string(id));
  if (!where.parent || mode == PlaceMode::Add || !unitesItsChildren(*where.parent))
    return movePart(root, id, where.parent ? where.parent->id : id, mode, groupId);
  const Node& parent = *where.parent;
  const NodePtr part = parent.children[size_t(where.index)];
  if (parent.children.size() < 2)
    throw Error(quoted(*part) + " is all that " + quoted(parent) + " holds: there is nothing in " +
                "it to " + placeModeName(mode) + ". Drag it onto the part it should act on");
  if (findNode(root, groupId) || findNode(root, groupId + 1))
    throw Error("role: the new operation's id is in use");
  std::vector<NodePtr> siblings;
  for (const NodePtr& child : parent.children)
    if (child->id != id) siblings.push_back(child);
  const NodePtr acted = siblings.size() == 1
                            ? siblings.front()
                            : makeOperationNode(NodeKind::Union, groupId + 1, std::move(siblings));
  const NodePtr op = makeOperationNode(operationKindFor(mode), groupId, {acted, part});
  NodePtr result = editNode(root, parent.id, [&](Node& n) { n.children = {op}; });
  checkInstances(result);
  return result;
}

}  // namespace strata
