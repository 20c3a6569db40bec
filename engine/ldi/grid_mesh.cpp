#include "engine/ldi/grid_mesh.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <string>
#include <utility>

#include "engine/geometry/transform.h"
#include "engine/ldi/shared_math.h"
#include "engine/util/error.h"

namespace strata {

GridMesh toGridUnits(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid) {
  GridMesh g;
  g.positions.resize(mesh.positions.size());
  const double limit = double(kMaxLatticeCoord / kSubcell) * 0.5;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    glm::dvec3 w = glm::dvec3(objectToWorld * glm::dvec4(mesh.positions[i], 1.0));
    glm::dvec3 q = (w - grid.origin) / grid.h;
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(q[a]) || std::fabs(q[a]) > limit)
        throw Error("vertex " + std::to_string(i) +
                    " lies at a non-finite or absurd distance from the grid after its transform");
    }
    g.positions[i] = q;
  }
  const bool flip = mirrors(objectToWorld);
  g.triangles = mesh.triangles;
  g.normals.resize(mesh.triangles.size());
  for (size_t t = 0; t < g.triangles.size(); ++t) {
    auto& tri = g.triangles[t];
    if (flip) std::swap(tri[1], tri[2]);
    glm::dvec3 n = glm::cross(g.positions[tri[1]] - g.positions[tri[0]],
                              g.positions[tri[2]] - g.positions[tri[0]]);
    double len = glm::length(n);
    g.normals[t] = len > 0.0 ? n / len : glm::dvec3(0.0);
  }
  return g;
}

}  // namespace strata
