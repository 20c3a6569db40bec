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

namespace strata {

enum class NodeKind : uint8_t {
  // Inner nodes (n-ary): the children, combined.
  Union,
  Intersection,
  Difference,  // first child minus all the others
  // Leaves: primitives, centred at the origin, axis along z.
  Box,       // size.x by size.y by size.z
  Sphere,    // radius
  Cylinder,  // radius, height
  Cone,      // radius (bottom, z = -height/2), topRadius (0 = pointed), height
  Torus,     // majorRadius (ring, in the xy plane), minorRadius (tube)
  Capsule,   // radius, height of the cylindrical part (total height + 2 radius)
  Mesh,      // an imported closed triangle mesh
  Instance,  // a reference to another node of the document (by id), with its own transform
};

bool isOperation(NodeKind kind);
bool isPrimitive(NodeKind kind);
// Lower-case name used in files and on the command line ("union", "box", ...).
const char* kindName(NodeKind kind);
// Inverse of kindName; returns false for unknown names.
bool kindFromName(const std::string& name, NodeKind* kind);

// Parameters of the primitive leaves; each kind reads the fields its comment above names.
// Lengths in scene units.
struct PrimitiveParams {
  glm::dvec3 size{1.0};
  double radius = 0.5;
  double topRadius = 0.0;
  double height = 1.0;
  double majorRadius = 1.0;
  double minorRadius = 0.25;
  // Tessellation level of detail: segments around the circumference; 0 = automatic, chosen
  // from the grid's cell size so that the chordal error stays below 1/50 of a cell.
  int segments = 0;

  bool operator==(const PrimitiveParams& o) const;
};

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

  // Mesh leaves: the file's path (absolute in a Document; in a scene file relative to its
  // folder or absolute), the content hash of the file, and the loaded, checked mesh (shared,
  // immutable).
  std::string meshPath;
  std::string meshHash;
  std::shared_ptr<const TriangleMesh> mesh;

  NodeId instanceOf = 0;  // Instance leaves: the id of the referenced node

  std::vector<NodePtr> children;  // operations only, in order (order matters for Difference)
};

// Depth of the tree (a leaf alone has depth 1), following instances.
int treeDepth(const NodePtr& root);
// Finds a node by id in the subtree (not following instances); nullptr when absent.
NodePtr findNode(const NodePtr& root, NodeId id);
// Largest id used in the subtree.
NodeId maxNodeId(const NodePtr& root);

}  // namespace strata
