// Measurements an artist places on the scene: the distance between two points, and with a third
// the angle at the second. They belong to the document (saved in the scene, one undo step each)
// and follow the parts they lie on: a point is kept in the frame of the leaf it was placed on, so
// moving, turning or scaling that part (or any node above it) carries the point along.
//
// Units: scene units and degrees. Threads: pure functions over immutable trees.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

#include "engine/document/node.h"

namespace strata {

struct MeasurePoint {
  NodeId node = 0;        // the part (a leaf) it lies on; 0: fixed in the world
  glm::dvec3 local{0.0};  // in that part's own frame; the world position when node == 0
  bool operator==(const MeasurePoint& o) const { return node == o.node && local == o.local; }
};

struct Measurement {
  std::vector<MeasurePoint> points;  // 2: a distance; 3: also the angle at the second point
  bool operator==(const Measurement& o) const { return points == o.points; }
};

// What a measurement shows now.
struct MeasureValues {
  glm::dvec3 a{0.0}, b{0.0}, c{0.0};  // its points in the world (c only with three)
  double distance = 0.0;              // |b - a|
  glm::dvec3 delta{0.0};              // b - a
  double distance2 = 0.0;             // |c - b| with three points
  double angleDegrees = 0.0;          // between a - b and c - b, with three points
  bool hasAngle = false;
};

// Object-to-world matrix of the node's parent (the identity for the root or a missing node),
// through the patterns above it as they show it first (patterns.h: firstPlacement).
glm::dmat4 parentWorldMatrix(const NodePtr& root, NodeId id);
// Object-to-world matrix of the node itself (its parent's times its own transform).
glm::dmat4 nodeWorldMatrix(const NodePtr& root, NodeId id);

// A point at `world` kept on `node` (in its frame); a point fixed in the world when the node is
// not in the tree or its frame cannot be inverted.
MeasurePoint attachPoint(const NodePtr& root, NodeId node, const glm::dvec3& world);
// Where the point is now.
glm::dvec3 pointInWorld(const NodePtr& root, const MeasurePoint& point);
MeasureValues measureValues(const NodePtr& root, const Measurement& measurement);

// The measurements of `before` with every point whose part is not in `after` fixed in the world
// where it was: a deleted part leaves its measurements where they were.
std::vector<Measurement> pinPointsOfRemovedParts(const NodePtr& before, const NodePtr& after,
                                                 const std::vector<Measurement>& measurements);

// The measurements of `before` with every point on a primitive whose parameters changed in
// `after` (a size, a radius typed) moved with its surface: its position in the part's own box,
// as a fraction along each axis, kept (a corner stays the corner). A point is kept in its part's
// frame, which a size typed does not change: a plate made 100 long kept its 140 mm measurement
// with its ends in the air, where a scale carried them along (an artist's test).
std::vector<Measurement> followResizedParts(const NodePtr& before, const NodePtr& after,
                                            const std::vector<Measurement>& measurements);

}  // namespace strata
