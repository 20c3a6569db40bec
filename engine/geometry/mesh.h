// Triangle meshes as the engine consumes them: indexed, closed, outward oriented.
#pragma once

#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace strata {

// An indexed triangle mesh in its own (object) coordinates, in scene units.
// Contract for meshes handed to sampling: every index < positions.size(), all coordinates
// finite, the surface closed and oriented with normals pointing out of the solid (counter-
// clockwise seen from outside). Readers and checks in engine/io and engine/geometry establish it.
struct TriangleMesh {
  std::vector<glm::dvec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;

  bool empty() const { return triangles.empty(); }
};

// Axis-aligned box; empty when min > max on any axis.
struct Bounds {
  glm::dvec3 min{std::numeric_limits<double>::infinity()};
  glm::dvec3 max{-std::numeric_limits<double>::infinity()};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  void include(const glm::dvec3& p);
  void include(const Bounds& b);
  Bounds intersected(const Bounds& b) const;
  glm::dvec3 size() const { return max - min; }
  glm::dvec3 center() const { return (min + max) * 0.5; }
  double longestSide() const { return std::max({size().x, size().y, size().z}); }
};

// Signed volume (sum of signed tetrahedra against the origin) and surface area of a mesh.
double signedVolume(const TriangleMesh& mesh);
double surfaceArea(const TriangleMesh& mesh);
Bounds meshBounds(const TriangleMesh& mesh);

}  // namespace strata
