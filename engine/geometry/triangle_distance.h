// The squared distance from a point to a triangle (its closest point, Ericson, "Real-Time
// Collision Detection", 5.1.5, by Voronoi regions), robust for degenerate triangles: a triangle
// with no area is measured as its three edges. Units are the caller's.
//
// Pure, header-only, any thread.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>

namespace strata {

inline double pointSegmentDistanceSquared(const glm::dvec3& p, const glm::dvec3& a,
                                          const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double length2 = glm::dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  const glm::dvec3 d = p - (a + t * ab);
  return glm::dot(d, d);
}

inline double pointTriangleDistanceSquared(const glm::dvec3& p, const glm::dvec3& a,
                                           const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const glm::dvec3 n = glm::cross(ab, ac);
  const double n2 = glm::dot(n, n);
  const double scale = std::max(glm::dot(ab, ab), glm::dot(ac, ac));
  if (!(n2 > 1e-24 * scale * scale))  // no area to speak of: the nearest of its edges
    return std::min({pointSegmentDistanceSquared(p, a, b), pointSegmentDistanceSquared(p, b, c),
                     pointSegmentDistanceSquared(p, c, a)});
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  auto squared = [&](const glm::dvec3& q) { return glm::dot(p - q, p - q); };
  if (d1 <= 0.0 && d2 <= 0.0) return squared(a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return squared(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return squared(a + ab * (d1 / (d1 - d3)));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return squared(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return squared(a + ac * (d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return squared(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  // Inside the face: the distance to its plane.
  const double along = glm::dot(ap, n);
  return along * along / n2;
}

}  // namespace strata
