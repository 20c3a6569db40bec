#include "engine/geometry/mesh.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace strata {

void Bounds::include(const glm::dvec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

void Bounds::include(const Bounds& b) {
  if (b.empty()) return;
  include(b.min);
  include(b.max);
}

Bounds Bounds::intersected(const Bounds& b) const {
  Bounds r;
  r.min = glm::max(min, b.min);
  r.max = glm::min(max, b.max);
  return r;
}

double signedVolume(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3& a = mesh.positions[t[0]];
    const glm::dvec3& b = mesh.positions[t[1]];
    const glm::dvec3& c = mesh.positions[t[2]];
    sum += glm::dot(a, glm::cross(b, c));
  }
  return sum / 6.0;
}

double surfaceArea(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3& a = mesh.positions[t[0]];
    const glm::dvec3& b = mesh.positions[t[1]];
    const glm::dvec3& c = mesh.positions[t[2]];
    sum += glm::length(glm::cross(b - a, c - a));
  }
  return sum * 0.5;
}

Bounds meshBounds(const TriangleMesh& mesh) {
  Bounds b;
  for (const auto& p : mesh.positions) b.include(p);
  return b;
}

}  // namespace strata
