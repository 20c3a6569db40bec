// The document model: a CSG tree of immutable nodes.
//
// Nodes are shared immutable values (std::shared_ptr<const Node>): an edit builds new nodes
// along the path to the root and shares everything else, so a snapshot of the document is just
// a root pointer that any thread may read while the UI keeps editing.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/geometry/mesh.h"
#include "engine/geometry/transform.h"
#include "engine/kinds/node_kinds.h"
#include "engine/kinds/patterns.h"
#include "engine/kinds/primitive_params.h"

namespace strata {

using NodeId = uint32_t;  // unique within a document, never 0 for a real node

struct Node;
using NodePtr = std::shared_ptr<const Node>;

struct Node {
  NodeId id = 0;
  std::string name;
  NodeKind kind = NodeKind::Union;
  Transform transform;
  glm::vec3 color{0.8f, 0.8f, 0.8f};  // linear RGB in [0, 1]
  bool visible = true;                // hidden nodes take no part in evaluation

  PrimitiveParams params;  // primitives only
  // Modifiers (offset, shell, round, fillet): the distance, thickness or radius, scene units,
  // measured in the world (the node's own scale does not change it).
  double amount = 0.0;
  // Shells only: a part inside the shell (by id, in its subtree, not through instances) where
  // the wall opens. The wall follows the children as they would be without that part, so where
  // the part cuts them the cavity reaches the outside (a drain hole for a resin print, a hollow
  // pot's mouth). 0: a closed wall everywhere. A reference that no longer names a visible part
  // inside the shell leaves the wall closed (the inspector says so).
  NodeId opening = 0;
  // Patterns (array, circular array, mirror): what the copies are (patterns.h), in the node's
  // frame.
  PatternParams pattern;

  // Mesh leaves: the file's path (absolute in a Document; in a scene file relative to its
  // folder or absolute), the content hash of the file, and the loaded, checked mesh (shared,
  // immutable).
  std::string meshPath;
  std::string meshHash;
  std::shared_ptr<const TriangleMesh> mesh;
  // Accepted although it is not a closed oriented surface (the artist chose it on import; the
  // command line's --allow-open for every mesh): its inside is guessed where rays pass its holes.
  bool meshOpen = false;
  // A mesh leaf kept without its mesh (meshMissing): why, as loading found it, and whether it
  // was refused only for being open (it can be taken as open: acceptOpenMesh in
  // engine/io/document_files.h). Not saved.
  std::string meshProblem;
  bool meshRefusedAsOpen = false;

  NodeId instanceOf = 0;  // Instance leaves: the id of the referenced node

  std::vector<NodePtr> children;  // operations only, in order (order matters for Difference)
};

// A mesh leaf whose file could not be read when its scene was opened (MissingMeshes::Keep,
// engine/io/scene_file.h): it holds an empty mesh (no reader gives one), so nothing of it is
// evaluated.
inline bool meshMissing(const Node& node) {
  return node.kind == NodeKind::Mesh && node.mesh && node.mesh->triangles.empty();
}

// A node as messages name it: its kind as people read it and its name ("rounded box 'rim'"), or its
// kind and id where it has no name ("offset #1"), never an empty "offset ''".
std::string nodeLabel(const Node& node);
// A node as the editor's log names it: its name in quotes ("\"hub\""), or its label in quotes
// where it has none ("\"offset #1\"").
std::string quotedName(const Node& node);

// Depth of the tree (a leaf alone has depth 1), following instances.
int treeDepth(const NodePtr& root);
// Finds a node by id in the subtree (not following instances); nullptr when absent.
NodePtr findNode(const NodePtr& root, NodeId id);
// Largest id used in the subtree.
NodeId maxNodeId(const NodePtr& root);

// A shell's opening (Node::opening), when it names a visible part strictly inside the shell's
// own visible subtree (not through instances); nullptr otherwise (no opening, or a reference
// that no longer names such a part: the wall stays closed).
NodePtr shellOpening(const NodePtr& shell);
// What a shell's wall follows when it has an opening: a union of the shell's children (the
// shell's id, name and transform) with the opening part hidden; nullptr without an opening.
NodePtr withoutOpening(const NodePtr& shell);

}  // namespace strata
