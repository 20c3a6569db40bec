#include "engine/document/commands.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "engine/document/measurement.h"
#include "engine/document/roles.h"
#include "engine/kinds/primitives.h"
#include "engine/util/error.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

std::string nameWithId(const Node& node) {
  std::string name = node.name.empty() ? std::string(kindName(node.kind)) : "\"" + node.name + "\"";
  return name + " (id " + std::to_string(node.id) + ")";
}

const Node& requireNode(const NodePtr& root, NodeId id) {
  NodePtr node = findNode(root, id);
  if (!node) throw Error("there is no node with id " + std::to_string(id));
  return *node;
}

// Replaces the node `id` by change(node) (nullptr removes it) and copies its ancestors. Returns
// false when `id` is not in the subtree of `node`.
bool rewrite(const NodePtr& node, NodeId id, const std::function<NodePtr(const NodePtr&)>& change,
             NodePtr* out) {
  if (node->id == id) {
    *out = change(node);
    return true;
  }
  for (size_t i = 0; i < node->children.size(); ++i) {
    NodePtr replaced;
    if (!rewrite(node->children[i], id, change, &replaced)) continue;
    auto copy = std::make_shared<Node>(*node);
    if (replaced)
      copy->children[i] = replaced;
    else
      copy->children.erase(copy->children.begin() + static_cast<std::ptrdiff_t>(i));
    *out = copy;
    return true;
  }
  return false;
}

NodePtr rewriteOrThrow(const NodePtr& root, NodeId id,
                       const std::function<NodePtr(const NodePtr&)>& change) {
  NodePtr out;
  if (!rewrite(root, id, change, &out))
    throw Error("there is no node with id " + std::to_string(id));
  return out;
}

// Removes a non-root node without checking instances (the node is being moved, not deleted).
NodePtr detach(const NodePtr& root, NodeId id) {
  if (root->id == id) throw Error("the root node " + nameWithId(*root) + " cannot be moved");
  return rewriteOrThrow(root, id, [](const NodePtr&) { return NodePtr(); });
}

void collectIds(const NodePtr& node, std::vector<NodeId>* ids) {
  ids->push_back(node->id);
  for (const auto& c : node->children) collectIds(c, ids);
}

void indexNodes(const NodePtr& node, std::unordered_map<NodeId, const Node*>* byId) {
  (*byId)[node->id] = node.get();
  for (const auto& c : node->children) indexNodes(c, byId);
}

// Instances outside the subtree of `subtree` that refer into it.
const Node* outsideReference(const NodePtr& node, const std::unordered_set<NodeId>& inside) {
  if (inside.count(node->id)) return nullptr;
  if (node->kind == NodeKind::Instance && inside.count(node->instanceOf)) return node.get();
  for (const auto& c : node->children)
    if (const Node* found = outsideReference(c, inside)) return found;
  return nullptr;
}

}  // namespace

const Node* instanceRepeating(const NodePtr& root, NodeId id) {
  return outsideReference(root, {id});
}

namespace {

NodePtr copyWithFreshIds(const NodePtr& node, NodeId* next,
                         std::unordered_map<NodeId, NodeId>* mapping) {
  auto copy = std::make_shared<Node>(*node);
  copy->id = (*next)++;
  (*mapping)[node->id] = copy->id;
  for (auto& c : copy->children) c = copyWithFreshIds(c, next, mapping);
  return copy;
}

NodePtr remapReferences(const NodePtr& node, const std::unordered_map<NodeId, NodeId>& mapping) {
  auto copy = std::make_shared<Node>(*node);
  if (copy->kind == NodeKind::Instance) {
    auto it = mapping.find(copy->instanceOf);
    if (it != mapping.end()) copy->instanceOf = it->second;
  }
  if (copy->opening != 0) {  // a shell's opening names a part of the copy too
    auto it = mapping.find(copy->opening);
    if (it != mapping.end()) copy->opening = it->second;
  }
  for (auto& c : copy->children) c = remapReferences(c, mapping);
  return copy;
}

}  // namespace

NodePtr makePrimitiveNode(NodeKind kind, NodeId id) {
  if (!isPrimitive(kind)) throw Error(std::string("\"") + kindName(kind) + "\" is not a primitive");
  auto node = std::make_shared<Node>();
  node->id = id;
  node->kind = kind;
  node->name = std::string(primitiveInfo(kind)->label) + " " + std::to_string(id);
  node->params = primitiveInfo(kind)->defaults;
  return node;
}

NodePtr makeOperationNode(NodeKind kind, NodeId id, std::vector<NodePtr> children) {
  if (!isOperation(kind))
    throw Error(std::string("\"") + kindName(kind) + "\" is not an operation");
  auto node = std::make_shared<Node>();
  node->id = id;
  node->kind = kind;
  // For people: "circular array 23", not the file's "circularArray 23".
  node->name = std::string(kindLabel(kind)) + " " + std::to_string(id);
  node->amount = nodeKindInfo(kind).defaultAmount;
  node->children = std::move(children);
  return node;
}

NodePtr makeMeshNode(NodeId id, const std::string& name, std::shared_ptr<const TriangleMesh> mesh,
                     const std::string& meshPath, const std::string& meshHash, bool meshOpen) {
  auto node = std::make_shared<Node>();
  node->id = id;
  node->kind = NodeKind::Mesh;
  node->name = name;
  node->mesh = std::move(mesh);
  node->meshPath = meshPath;
  node->meshHash = meshHash;
  node->meshOpen = meshOpen;
  return node;
}

NodePtr withFreshIds(const NodePtr& node, NodeId firstId) {
  NodeId next = firstId;
  std::unordered_map<NodeId, NodeId> mapping;
  return remapReferences(copyWithFreshIds(node, &next, &mapping), mapping);
}

bool locateNode(const NodePtr& root, NodeId id, NodeLocation* location) {
  if (!root) return false;
  if (root->id == id) {
    *location = NodeLocation{};
    return true;
  }
  for (size_t i = 0; i < root->children.size(); ++i) {
    if (root->children[i]->id == id) {
      *location = NodeLocation{root, static_cast<int>(i)};
      return true;
    }
    if (locateNode(root->children[i], id, location)) return true;
  }
  return false;
}

bool pathToNode(const NodePtr& root, NodeId id, std::vector<const Node*>* path) {
  path->push_back(root.get());
  if (root->id == id) return true;
  for (const auto& c : root->children)
    if (pathToNode(c, id, path)) return true;
  path->pop_back();
  return false;
}

bool isInSubtree(const NodePtr& root, NodeId ancestor, NodeId id) {
  NodePtr top = findNode(root, ancestor);
  return top && findNode(top, id) != nullptr;
}

std::vector<NodeId> treeOrder(const NodePtr& root) {
  std::vector<NodeId> ids;
  if (root) collectIds(root, &ids);
  return ids;
}

void validateParams(NodeKind kind, const PrimitiveParams& p) {
  validatePrimitiveParams(kind, p);
}

void validateTransform(const Transform& t) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(t.translate[i]) || !std::isfinite(t.rotateDegrees[i]))
      throw Error("a transform must be finite");
    if (!(t.scale[i] != 0) || !std::isfinite(t.scale[i]))
      throw Error("every scale component must be a nonzero number");
  }
}

void checkInstances(const NodePtr& root) {
  std::unordered_map<NodeId, const Node*> byId;
  indexNodes(root, &byId);
  // Depth-first search over tree and instance edges; a node met again while still on the
  // search path closes a cycle (which must pass through an instance edge).
  enum Mark : uint8_t { Unseen, OnPath, Done };
  std::unordered_map<const Node*, Mark> marks;
  std::function<void(const Node*)> visit = [&](const Node* node) {
    marks[node] = OnPath;
    std::vector<const Node*> next;
    for (const auto& c : node->children) next.push_back(c.get());
    if (node->kind == NodeKind::Instance) {
      auto it = byId.find(node->instanceOf);
      if (it == byId.end())
        throw Error("instance " + nameWithId(*node) + " refers to node " +
                    std::to_string(node->instanceOf) + ", which does not exist");
      next.push_back(it->second);
    }
    for (const Node* n : next) {
      Mark m = marks.count(n) ? marks[n] : Unseen;
      if (m == OnPath)
        throw Error("instance cycle through " + nameWithId(*n) +
                    " (an instance may not refer to a node that contains it)");
      if (m == Unseen) visit(n);
    }
    marks[node] = Done;
  };
  visit(root.get());
}

NodePtr editNode(const NodePtr& root, NodeId id, const std::function<void(Node&)>& change) {
  return rewriteOrThrow(root, id, [&](const NodePtr& node) {
    auto copy = std::make_shared<Node>(*node);
    change(*copy);
    copy->id = node->id;  // an edit never renumbers
    return NodePtr(copy);
  });
}

NodePtr insertChild(const NodePtr& root, NodeId parentId, int index, const NodePtr& child) {
  const Node& parent = requireNode(root, parentId);
  if (!isOperation(parent.kind))
    throw Error(nameWithId(parent) + " is a " + kindName(parent.kind) +
                " and cannot have children; add to an operation");
  std::vector<NodeId> childIds;
  collectIds(child, &childIds);
  for (NodeId id : childIds)
    if (id == 0 || findNode(root, id))
      throw Error("node id " + std::to_string(id) + " is already used in the document");
  return rewriteOrThrow(root, parentId, [&](const NodePtr& node) {
    auto copy = std::make_shared<Node>(*node);
    auto at = (index < 0 || index >= static_cast<int>(copy->children.size()))
                  ? copy->children.end()
                  : copy->children.begin() + index;
    copy->children.insert(at, child);
    return NodePtr(copy);
  });
}

NodePtr removeNode(const NodePtr& root, NodeId id) {
  const Node& node = requireNode(root, id);
  if (root->id == id) throw Error("the root node " + nameWithId(node) + " cannot be deleted");
  std::vector<NodeId> ids;
  collectIds(findNode(root, id), &ids);
  std::unordered_set<NodeId> inside(ids.begin(), ids.end());
  if (const Node* user = outsideReference(root, inside))
    throw Error("cannot delete " + nameWithId(node) + ": instance " + nameWithId(*user) +
                " refers to it; delete or re-point the instance first");
  return removeKeepingRoles(root, id, maxNodeId(root) + 1);
}

std::string copyName(const NodePtr& root, const std::string& name) {
  // A copy of a copy is another copy of the same part ("x copy 2", not "x copy copy").
  std::string stem = name;
  const size_t at = stem.rfind(" copy");
  if (at != std::string::npos) {
    const std::string rest = stem.substr(at + 5);
    const bool number = rest.size() > 1 && rest[0] == ' ' &&
                        rest.find_first_not_of("0123456789", 1) == std::string::npos;
    if (rest.empty() || number) stem.resize(at);
  }
  if (stem == "copy") stem.clear();
  const std::string base = stem.empty() ? "copy" : stem + " copy";
  std::unordered_set<std::string> taken;
  std::vector<const Node*> stack{root.get()};
  while (!stack.empty()) {
    const Node* at = stack.back();
    stack.pop_back();
    taken.insert(at->name);
    for (const NodePtr& c : at->children) stack.push_back(c.get());
  }
  std::string named = base;
  for (int k = 2; taken.count(named); ++k) named = base + " " + std::to_string(k);
  return named;
}

NodePtr duplicateNode(const NodePtr& root, NodeId id, NodeId firstId, NodeId* copyId) {
  NodePtr node = findNode(root, id);
  if (!node) throw Error("there is no node with id " + std::to_string(id));
  if (root->id == id)
    throw Error("the root node cannot be duplicated; group it first (it then has a parent)");
  if (firstId <= maxNodeId(root)) throw Error("duplicate: new ids must be unused");
  NodePtr copy = withFreshIds(node, firstId);
  auto named = std::make_shared<Node>(*copy);
  named->name = copyName(root, node->name);
  if (copyId) *copyId = named->id;
  // The copy plays the original's role: placed onto the original with that role's mode, it lands
  // beside it, or (the base of a difference) unites with it in a union in the base's place; the
  // copy of a modifier or a pattern is not put inside the original.
  const ChildRole role = roleOf(root, id);
  const PlaceMode mode = role == ChildRole::Cut         ? PlaceMode::Cut
                         : role == ChildRole::Intersect ? PlaceMode::Intersect
                                                        : PlaceMode::Add;
  return placePart(root, planPlacement(root, id, mode, IntoUniting::No), named,
                   maxNodeId(named) + 1);
}

NodePtr moveNode(const NodePtr& root, NodeId id, NodeId parentId, int index) {
  const Node& node = requireNode(root, id);
  const Node& parent = requireNode(root, parentId);
  if (root->id == id) throw Error("the root node " + nameWithId(node) + " cannot be moved");
  if (isInSubtree(root, id, parentId))
    throw Error(
        "cannot move " + nameWithId(node) + " into " +
        (parentId == id ? std::string("itself") : nameWithId(parent) + ", which lies inside it"));
  if (!isOperation(parent.kind))
    throw Error(nameWithId(parent) + " is a " + kindName(parent.kind) +
                " and cannot have children");
  NodeId before = 0;
  if (index >= 0 && index < static_cast<int>(parent.children.size()))
    before = parent.children[static_cast<size_t>(index)]->id;
  if (before == id) return root;  // dropped in front of itself: nothing moves
  NodePtr moved = findNode(root, id);
  NodePtr without = detach(root, id);
  int at = -1;
  if (before != 0) {
    const Node& newParent = requireNode(without, parentId);
    for (size_t i = 0; i < newParent.children.size(); ++i)
      if (newParent.children[i]->id == before) at = static_cast<int>(i);
  }
  NodePtr result = rewriteOrThrow(without, parentId, [&](const NodePtr& p) {
    auto copy = std::make_shared<Node>(*p);
    auto pos = at < 0 ? copy->children.end() : copy->children.begin() + at;
    copy->children.insert(pos, moved);
    return NodePtr(copy);
  });
  checkInstances(result);
  return result;
}

NodePtr moveNodeToTop(const NodePtr& root, NodeId id, NodeId unionId) {
  const Node& node = requireNode(root, id);
  if (root->id == id) throw Error(nameWithId(node) + " is already the root");
  if (root->kind == NodeKind::Union) return moveNode(root, id, root->id, -1);
  if (findNode(root, unionId)) throw Error("moveNodeToTop: the new union's id is in use");
  NodePtr moved = findNode(root, id);
  NodePtr rest = detach(root, id);
  NodePtr top = makeOperationNode(NodeKind::Union, unionId, {rest, moved});
  auto named = std::make_shared<Node>(*top);
  named->name = "scene";
  checkInstances(named);
  return named;
}

namespace {

// Members of a group from different parents all go where the first one is: each must do there
// what it did. Relative to the lowest operation above all their parents (the place they share),
// each member must do the same thing through the child of that place that holds it, with only
// unions it adds to in between (a union's parts do to its parent what the union does). A hole
// inside a cutter grouped with a part of the base was moved into the base and became a peg
// (an artist's test); a part added beside a difference grouped with one of its base's parts
// would be cut by its cutters.
void checkGroupKeepsContexts(const NodePtr& root, const std::vector<NodeId>& members) {
  if (members.size() < 2) return;
  std::vector<std::vector<const Node*>> paths(members.size());
  for (size_t m = 0; m < members.size(); ++m)
    if (!pathToNode(root, members[m], &paths[m]) || paths[m].size() < 2) return;
  // The place: the deepest node on every member's path above the member itself.
  size_t place = 0;
  for (;; ++place) {
    bool shared = true;
    for (const auto& path : paths)
      shared = shared && place + 1 < path.size() - 1 && path[place + 1] == paths[0][place + 1];
    if (!shared) break;
  }
  const auto indexIn = [](const Node& parent, const Node* child) {
    for (size_t i = 0; i < parent.children.size(); ++i)
      if (parent.children[i].get() == child) return int(i);
    return -1;
  };
  const auto through = [&](size_t m) {
    return childRole(*paths[m][place], indexIn(*paths[m][place], paths[m][place + 1]));
  };
  // "\"hole\" lies in \"bolt holes\", which cuts", or "\"hole\" cuts" where it is the holder.
  const auto whatItDoes = [&](size_t m) {
    const Node& holder = *paths[m][place + 1];
    return &holder == paths[m].back()
               ? nameWithId(holder) + " " + rolePhrase(through(m))
               : nameWithId(*paths[m].back()) + " lies in " + nameWithId(holder) + ", which " +
                     rolePhrase(through(m));
  };
  const Node& at = *paths[0][place];
  const ChildRole role = through(0);
  bool sameParent = true;
  for (const auto& path : paths)
    sameParent = sameParent && path[path.size() - 2] == paths[0][paths[0].size() - 2];
  for (size_t m = 0; m < members.size(); ++m) {
    const auto& path = paths[m];
    const Node& member = *path.back();
    if (through(m) != role)
      throw Error(whatItDoes(m) + " in " + nameWithId(at) + ", and " + whatItDoes(0) +
                  " there: a group plays one role, so one of them would no longer do what it "
                  "did. Group parts that do the same (or move them first)");
    // Parts leave their holders, or (the first's) receive the others: an instance of a holder
    // would then show them moved too (a bore grouped out of the union an instance repeats).
    if (!sameParent)
      for (size_t k = place + 1; k + 1 < path.size(); ++k)
        if (const Node* user = instanceRepeating(root, path[k]->id))
          throw Error(nameWithId(member) + " lies in " + nameWithId(*path[k]) +
                      ", which instance " + nameWithId(*user) +
                      " repeats: a group with parts from elsewhere would change the instance "
                      "too. Group parts within " +
                      nameWithId(*path[k]) + " alone, or move them first");
    for (size_t k = place + 1; k + 1 < path.size(); ++k)
      if (path[k]->kind != NodeKind::Union)
        throw Error(nameWithId(member) + " lies in " + nameWithId(*path[k]) + " (a " +
                    kindName(path[k]->kind) + ") within " + nameWithId(at) +
                    ": a group with parts outside it would take it out, and it would no longer "
                    "do what it did. Group parts within " +
                    nameWithId(*path[k]) + " alone, or move it first");
  }
}

}  // namespace

NodePtr groupNodes(const NodePtr& root, const std::vector<NodeId>& ids, NodeKind kind,
                   NodeId groupId) {
  if (!isOperation(kind)) throw Error("a group must be a union, intersection or difference");
  if (ids.empty()) throw Error("nothing selected to group");
  if (findNode(root, groupId)) throw Error("group: the new node's id is in use");
  std::unordered_set<NodeId> selected;
  for (NodeId id : ids) {
    requireNode(root, id);
    selected.insert(id);
  }
  if (selected.count(root->id)) {
    if (selected.size() != 1)
      throw Error("the root cannot be grouped with other nodes; group its children instead");
    return makeOperationNode(kind, groupId, {root});
  }
  // Tree order, dropping nodes that lie inside another selected node.
  std::vector<NodeId> order;
  for (NodeId id : treeOrder(root)) {
    if (!selected.count(id)) continue;
    bool nested = false;
    for (NodeId other : selected)
      if (other != id && isInSubtree(root, other, id)) nested = true;
    if (!nested) order.push_back(id);
  }
  // A group takes one role in its parent: members that do different things (the base and a
  // cutter, a part that adds and one that cuts) would change what some of them do.
  checkGroupKeepsContexts(root, order);
  // A member from another parent keeps its place in the world: its transform in the first
  // member's parent (where the group goes, itself unmoved) is what its own parent's made of it.
  std::vector<NodePtr> members;
  const glm::dmat4 groupParent = parentWorldMatrix(root, order[0]);
  for (NodeId id : order) {
    NodePtr member = findNode(root, id);
    const glm::dmat4 ownParent = parentWorldMatrix(root, id);
    if (ownParent != groupParent) {
      // An instance repeats the part with its own transform: a new one would move the copy too
      // (the cross bore grouped with a bolt hole took its y-bore along: an artist's re-test).
      if (const Node* user = instanceRepeating(root, id))
        throw Error(nameWithId(*member) + " is repeated by instance " + nameWithId(*user) +
                    ": in a group there it would get another move, turn or scale, and the "
                    "instance would move with it. Group it with parts of its own place, or "
                    "group the parts around it");
      bool exact = false;
      const Transform t =
          transformNear(glm::inverse(groupParent) * ownParent * member->transform.matrix(),
                        member->transform, &exact);
      if (!exact)
        throw Error(nameWithId(*member) + " is turned and stretched where " +
                    nameWithId(requireNode(root, order[0])) +
                    " is not: no move, turn and scale keeps its shape in a group there. Group "
                    "parts of one place, or move it first");
      auto moved = std::make_shared<Node>(*member);
      moved->transform = t;
      member = moved;
    }
    members.push_back(member);
  }
  NodePtr group = makeOperationNode(kind, groupId, members);
  NodePtr result = root;
  for (size_t i = 1; i < order.size(); ++i) result = detach(result, order[i]);
  result = rewriteOrThrow(result, order[0], [&](const NodePtr&) { return group; });
  checkInstances(result);  // grouping moves nodes: an instance may now lie inside its original
  return result;
}

NodePtr setOperationKind(const NodePtr& root, NodeId id, NodeKind kind) {
  const Node& node = requireNode(root, id);
  if (!isOperation(node.kind))
    throw Error(nameWithId(node) + " is a " + kindName(node.kind) + ", not an operation");
  if (!isOperation(kind))
    throw Error(std::string("\"") + kindName(kind) + "\" is not an operation");
  if (node.kind == kind) return root;
  // A name Strata gave ("difference 4") follows the kind ("intersection 4"); a name the artist
  // chose stays.
  // (Earlier builds named it by the file's word: "circularArray 4" is Strata's too.)
  const std::string number = " " + std::to_string(id);
  const bool defaultName =
      node.name == kindLabel(node.kind) + number || node.name == kindName(node.kind) + number;
  return editNode(root, id, [&](Node& n) {
    n.kind = kind;
    // A modifier's amount: kept between modifiers, the kind's default when it becomes one.
    if (modifierOf(kind) != Modifier::None && modifierOf(node.kind) == Modifier::None)
      n.amount = nodeKindInfo(kind).defaultAmount;
    if (defaultName) n.name = kindLabel(kind) + number;
  });
}

namespace {
// Copies the tree with every mesh path replaced by newPath(path); shares unchanged subtrees.
NodePtr rewriteMeshPaths(const NodePtr& node,
                         const std::function<std::string(const fs::path&)>& newPath) {
  NodePtr out = node;
  if (node->kind == NodeKind::Mesh && !node->meshPath.empty()) {
    std::string rewritten = newPath(fs::path(node->meshPath));
    if (rewritten != node->meshPath) {
      auto copy = std::make_shared<Node>(*node);
      copy->meshPath = rewritten;
      out = copy;
    }
  }
  std::vector<NodePtr> children;
  bool changed = false;
  for (const auto& c : node->children) {
    children.push_back(rewriteMeshPaths(c, newPath));
    changed = changed || children.back() != c;
  }
  if (!changed) return out;
  auto copy = std::make_shared<Node>(*out);
  copy->children = std::move(children);
  return copy;
}

fs::path absoluteFolder(const std::string& dir) {
  std::error_code ec;
  fs::path folder =
      fs::absolute(dir.empty() ? fs::path(".") : fs::path(dir), ec).lexically_normal();
  return folder.has_filename() ? folder : folder.parent_path();  // no trailing separator
}
}  // namespace

NodePtr absoluteMeshPaths(const NodePtr& root, const std::string& fromDir) {
  if (!root) return root;
  fs::path from = absoluteFolder(fromDir);
  return rewriteMeshPaths(root, [&](const fs::path& path) {
    return (path.is_absolute() ? path : from / path).lexically_normal().generic_string();
  });
}

NodePtr relativeMeshPaths(const NodePtr& root, const std::string& toDir) {
  if (!root) return root;
  fs::path to = absoluteFolder(toDir);
  size_t toDepth = 0;  // the folder's components below the root
  for (const fs::path& part : to.relative_path()) toDepth += part.empty() ? 0 : 1;
  return rewriteMeshPaths(root, [&](const fs::path& path) {
    if (path.is_relative()) return path.generic_string();
    const fs::path relative = path.lexically_normal().lexically_relative(to);
    if (relative.empty()) return path.generic_string();
    size_t up = 0;  // leading ".."
    for (const fs::path& part : relative) {
      if (part != "..") break;
      ++up;
    }
    // Relative within the folder, or in a folder beside it (a project's scenes/ and meshes/,
    // below a common folder that is not the root): such a project moves or is shared whole.
    // Farther (a home folder's Downloads from its Desktop) stays absolute: a scene moved on its
    // own still finds it.
    return up == 0 || (up == 1 && up < toDepth) ? relative.generic_string() : path.generic_string();
  });
}

}  // namespace strata
