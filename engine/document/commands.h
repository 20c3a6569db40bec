// Edits of the immutable CSG tree: pure functions from a root to a new root.
//
// Each edit copies the nodes on the path from the root to what it changes and shares every
// other subtree with the old tree, so the old root stays a valid, unchanged snapshot (the undo
// history keeps it; a worker thread may be evaluating it). An edit that would break the
// document's rules throws strata::Error with a sentence a person can read and changes nothing:
// a node dropped into its own subtree, the root deleted, a child given to a leaf, an instance
// cycle, a parameter out of range.
//
// Threads: any; the functions share no state.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/document/node.h"

namespace strata {

// A new primitive with default parameters, named after its kind and id ("sphere 7").
NodePtr makePrimitiveNode(NodeKind kind, NodeId id);
// A new operation over `children` (in order), named after its kind and id.
NodePtr makeOperationNode(NodeKind kind, NodeId id, std::vector<NodePtr> children);
// A mesh leaf holding a loaded, checked mesh; `meshPath` absolute (see Document).
NodePtr makeMeshNode(NodeId id, const std::string& name, std::shared_ptr<const TriangleMesh> mesh,
                     const std::string& meshPath, const std::string& meshHash,
                     bool meshOpen = false);

// A deep copy of `node` with ids counting up from `firstId` in pre-order (instances inside it
// that refer into it follow the copy).
NodePtr withFreshIds(const NodePtr& node, NodeId firstId);

// Where a node sits: its parent (null for the root) and its index among the parent's children.
struct NodeLocation {
  NodePtr parent;
  int index = -1;
};
// False when `id` is not in the tree.
bool locateNode(const NodePtr& root, NodeId id, NodeLocation* location);

// The nodes from `root` down to `id`, both included (tree edges only); false when absent.
bool pathToNode(const NodePtr& root, NodeId id, std::vector<const Node*>* path);

// True when `id` is `ancestor` itself or lies in its subtree (tree edges only).
bool isInSubtree(const NodePtr& root, NodeId ancestor, NodeId id);

// Ids of every node in depth-first pre-order (the order the outliner shows them).
std::vector<NodeId> treeOrder(const NodePtr& root);

// Throws strata::Error when a primitive's parameters or a transform would be refused by the
// scene file format (a length <= 0, minorRadius >= majorRadius, segments not 0 or 3..4096, a
// zero or non-finite scale component).
void validateParams(NodeKind kind, const PrimitiveParams& params);
void validateTransform(const Transform& transform);

// Throws strata::Error when an instance refers to a missing node or, directly or through other
// instances, to a node that contains it.
void checkInstances(const NodePtr& root);
// An instance that repeats node `id` (its first in tree order), or null: a change of the node's
// own transform moves that copy too.
const Node* instanceRepeating(const NodePtr& root, NodeId id);

// The tree with node `id` replaced by `change` applied to a copy of it.
NodePtr editNode(const NodePtr& root, NodeId id, const std::function<void(Node&)>& change);

// Inserts `child` (its ids must be new to the tree) under operation `parentId` before child
// `index`; index < 0 or past the end appends.
NodePtr insertChild(const NodePtr& root, NodeId parentId, int index, const NodePtr& child);

// Removes a node and its subtree. Refused for the root and for a subtree that an instance
// outside it refers to. The base of a difference with cutters leaves an empty base behind
// (removeKeepingRoles in roles.h): no cutter becomes the base.
NodePtr removeNode(const NodePtr& root, NodeId id);

// The name of a copy of a node named `name`: "<name> copy", or "<name> copy 2" and on where a
// node under `root` has that name already (three Ctrl+D of one part made three rows named alike).
std::string copyName(const NodePtr& root, const std::string& name);

// Adds a deep copy of node `id` that plays the original's role, leaving every other node's role
// as it was (placed onto the original with its role, roles.h): right after the original (a
// union's or intersection's child, a difference's cutter), or, for the base (first child) of a
// difference, beside the base in a new union that takes the base's place (a copy after the base
// would cut it away). Fresh ids count up
// from `firstId` (instances inside the copy that refer into the copied subtree follow the copy;
// the group, when made, takes the next id). The copy's name gets " copy" (" copy 2" and on where
// a node has that name). Sets *copyId to the
// copy's id. Refused for the root.
NodePtr duplicateNode(const NodePtr& root, NodeId id, NodeId firstId, NodeId* copyId);

// Moves node `id` under operation `parentId`, before the child that is at `index` now (index < 0
// or past the end appends). Refused when `parentId` lies in the moved node's own subtree (a
// node can never be dropped into itself), for the root, and when it would make an instance
// cycle.
NodePtr moveNode(const NodePtr& root, NodeId id, NodeId parentId, int index);

// A drop on empty space: moves node `id` to the top level. A union root receives it as its last
// child; any other root is wrapped, with the node, in a new union with id `unionId`.
NodePtr moveNodeToTop(const NodePtr& root, NodeId id, NodeId unionId);

// Groups the nodes `ids` under a new operation `kind` with id `groupId`, placed where the first
// of them (in tree order) was. Children keep tree order (for a difference, the first one is
// what the others are subtracted from); a selected node inside another selected node goes with
// its ancestor. Grouping the root alone wraps it.
NodePtr groupNodes(const NodePtr& root, const std::vector<NodeId>& ids, NodeKind kind,
                   NodeId groupId);

// Changes an operation's kind (union, intersection, difference); a default name ("difference 4")
// follows it ("intersection 4"), a chosen one stays. Refused for leaves.
NodePtr setOperationKind(const NodePtr& root, NodeId id, NodeKind kind);

// Rewrites relative mesh paths written against `fromDir` (empty: the current directory) as
// absolute, lexically normal paths.
NodePtr absoluteMeshPaths(const NodePtr& root, const std::string& fromDir);
// Rewrites absolute mesh paths as paths relative to `toDir` where the file is under it or under
// a folder beside it (a project's sibling folders: "../meshes/part.obj", the common folder not
// the root); others stay absolute.
NodePtr relativeMeshPaths(const NodePtr& root, const std::string& toDir);

}  // namespace strata
