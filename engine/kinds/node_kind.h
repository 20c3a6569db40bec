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
  // Modifiers: operations whose children, united, are then offset by the node's amount
  // (node_kinds.h: Modifier).
  Offset,
  Shell,
  Round,
  Fillet,
  // Patterns: operations whose children, united, are repeated under placements in the node's
  // frame (patterns.h).
  Array,
  CircularArray,
  Mirror,
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

// What a modifier (an operation that unites its children and then changes the solid by a
// distance, `Node::amount`, in scene units) does; engine/ldi/offset_ldi.h computes it.
enum class Modifier : uint8_t {
  None,
  Offset,  // grown by amount (> 0) or shrunk (< 0): the Euclidean offset
  Shell,   // a wall of thickness amount (> 0) inside the surface: S minus offset(S, -amount)
  Round,   // convex edges rounded with radius amount (> 0): offset(offset(S, -r), r), an opening
  Fillet,  // concave edges and seams filled with radius amount (> 0): offset(offset(S, r), -r)
};

// What a pattern (an operation that repeats its children's union) places; patterns.h says how.
enum class Pattern : uint8_t {
  None,
  Array,     // copies along a grid of the node's frame (a linear array is a grid of one row)
  Circular,  // copies around an axis
  Mirror,    // a mirror image across a plane, with or without the original
};

}  // namespace strata
