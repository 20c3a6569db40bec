// The kinds of node a CSG tree holds. What each kind is (its name, role, icon, the Boolean it
// applies, its scene-file fields) is described once, in node_kinds.h; primitives in
// primitives.h. Values are in-memory only (files use names), so new kinds may go anywhere.
#pragma once

#include <cstdint>

namespace strata {

enum class NodeKind : uint8_t {
  // Operations (n-ary): the children, combined.
  Union,
  Intersection,
  Difference,  // first child minus all the others
  // Primitive leaves (primitives.h), centred at the origin, axis along z.
  Box,
  Sphere,
  Cylinder,
  Cone,
  Torus,
  Capsule,
  RoundedBox,
  // Other leaves.
  Mesh,      // an imported closed triangle mesh
  Instance,  // a reference to another node of the document (by id), with its own transform
};

}  // namespace strata
