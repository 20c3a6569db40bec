#include "engine/ldi/grid_mesh.h"

#include <climits>

#include <algorithm>

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

RayWindow meshRayWindow(const GridMesh& mesh, const Grid& grid, int axis) {
  if (mesh.positions.empty() || mesh.triangles.empty()) return RayWindow{};
  const int ua = grid.uAxis(axis), va = grid.vAxis(axis);
  int64_t umin = INT64_MAX, umax = INT64_MIN, vmin = INT64_MAX, vmax = INT64_MIN;
  for (const glm::dvec3& p : mesh.positions) {
    const int64_t u = int64_t(llrint(p[ua] * double(kSubcell)));
    const int64_t v = int64_t(llrint(p[va] * double(kSubcell)));
    umin = std::min(umin, u);
    umax = std::max(umax, u);
    vmin = std::min(vmin, v);
    vmax = std::max(vmax, v);
  }
  const int64_t r0 = std::max<int64_t>(0, ceilDiv(umin, kSubcell) - grid.first[ua]);
  const int64_t r1 =
      std::min<int64_t>(grid.raysU(axis) - 1, floorDiv(umax, kSubcell) - grid.first[ua]);
  const int64_t s0 = std::max<int64_t>(0, ceilDiv(vmin, kSubcell) - grid.first[va]);
  const int64_t s1 =
      std::min<int64_t>(grid.raysV(axis) - 1, floorDiv(vmax, kSubcell) - grid.first[va]);
  if (r0 > r1 || s0 > s1) return RayWindow{};
  return RayWindow{int(r0), int(s0), int(r1 - r0 + 1), int(s1 - s0 + 1)};
}

}  // namespace strata
