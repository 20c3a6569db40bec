#include "engine/document/measurement.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

#include "engine/document/commands.h"
#include "engine/kinds/primitives.h"

namespace strata {

glm::dmat4 parentWorldMatrix(const NodePtr& root, NodeId id) {
  std::vector<const Node*> path;
  glm::dmat4 m(1.0);
  if (!root || !pathToNode(root, id, &path)) return m;
  // A mirror that drops its original shows its children as their image.
  for (size_t i = 0; i + 1 < path.size(); ++i)
    m = m * path[i]->transform.matrix() *
        firstPlacement(patternOf(path[i]->kind), path[i]->pattern);
  return m;
}

glm::dmat4 nodeWorldMatrix(const NodePtr& root, NodeId id) {
  NodePtr node = findNode(root, id);
  const glm::dmat4 parent = parentWorldMatrix(root, id);
  return node ? parent * node->transform.matrix() : parent;
}

namespace {
bool invertible(const glm::dmat4& m) {
  const double det = glm::determinant(glm::dmat3(m));
  return std::isfinite(det) && std::abs(det) > 1e-300;
}
}  // namespace

MeasurePoint attachPoint(const NodePtr& root, NodeId node, const glm::dvec3& world) {
  MeasurePoint p;
  p.local = world;
  if (node == 0 || !findNode(root, node)) return p;
  const glm::dmat4 m = nodeWorldMatrix(root, node);
  if (!invertible(m)) return p;
  p.node = node;
  p.local = glm::dvec3(glm::inverse(m) * glm::dvec4(world, 1.0));
  return p;
}

glm::dvec3 pointInWorld(const NodePtr& root, const MeasurePoint& point) {
  if (point.node == 0) return point.local;
  return glm::dvec3(nodeWorldMatrix(root, point.node) * glm::dvec4(point.local, 1.0));
}

MeasureValues measureValues(const NodePtr& root, const Measurement& measurement) {
  MeasureValues v;
  const auto& pts = measurement.points;
  if (pts.size() < 2) return v;
  v.a = pointInWorld(root, pts[0]);
  v.b = pointInWorld(root, pts[1]);
  v.delta = v.b - v.a;
  v.distance = glm::length(v.delta);
  if (pts.size() >= 3) {
    v.c = pointInWorld(root, pts[2]);
    v.distance2 = glm::length(v.c - v.b);
    const glm::dvec3 u = v.a - v.b, w = v.c - v.b;
    const double lu = glm::length(u), lw = glm::length(w);
    if (lu > 0.0 && lw > 0.0) {
      // atan2 of the cross and dot products: accurate near 0 and 180 degrees.
      v.angleDegrees = glm::degrees(std::atan2(glm::length(glm::cross(u, w)), glm::dot(u, w)));
      v.hasAngle = true;
    }
  }
  return v;
}

std::vector<Measurement> pinPointsOfRemovedParts(const NodePtr& before, const NodePtr& after,
                                                 const std::vector<Measurement>& measurements) {
  std::vector<Measurement> out = measurements;
  for (Measurement& m : out)
    for (MeasurePoint& p : m.points)
      if (p.node != 0 && !findNode(after, p.node)) {
        p.local = pointInWorld(before, p);
        p.node = 0;
      }
  return out;
}

std::vector<Measurement> followResizedParts(const NodePtr& before, const NodePtr& after,
                                            const std::vector<Measurement>& measurements) {
  std::vector<Measurement> out = measurements;
  for (Measurement& m : out)
    for (MeasurePoint& p : m.points) {
      if (p.node == 0) continue;
      const NodePtr was = findNode(before, p.node), now = findNode(after, p.node);
      if (!was || !now || was->kind != now->kind || !isPrimitive(now->kind) ||
          was->params == now->params)
        continue;
      const Bounds a = primitiveWorldBounds(was->kind, was->params, glm::dmat4(1.0));
      const Bounds b = primitiveWorldBounds(now->kind, now->params, glm::dmat4(1.0));
      if (a.empty() || b.empty()) continue;
      for (int k = 0; k < 3; ++k) {
        const double from = a.max[k] - a.min[k];
        p.local[k] = from > 0.0
                         ? b.min[k] + (p.local[k] - a.min[k]) * ((b.max[k] - b.min[k]) / from)
                         : p.local[k] + (b.center()[k] - a.center()[k]);
      }
    }
  return out;
}

}  // namespace strata
