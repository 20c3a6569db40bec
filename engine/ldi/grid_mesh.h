// A mesh placed on the grid: what sampling consumes, on either backend. The transform to grid
// units and the face normals are computed once, here, on the host, so the CPU backend and the
// CUDA backend start from the very same numbers.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

#include "engine/geometry/mesh.h"
#include "engine/ldi/grid.h"
#include "engine/ldi/ldi.h"

namespace strata {

struct GridMesh {
  std::vector<glm::dvec3> positions;               // global grid units: (world - origin) / h
  std::vector<std::array<uint32_t, 3>> triangles;  // wound outward (mirrors already undone)
  std::vector<glm::dvec3> normals;  // per triangle, unit, outward; zero for degenerate ones
};

// Places `mesh` by `objectToWorld` on `grid`. A mirroring matrix reverses the winding so the
// normals stay outward. Throws strata::Error for non-finite or absurdly distant vertices.
GridMesh toGridUnits(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid);

// The rays along `axis` that any triangle of `mesh` may hit: from the box of all its vertices,
// snapped and clamped exactly as projectTriangle snaps and clamps each triangle's corners, so
// every triangle's candidate rays lie inside. O(vertices).
RayWindow meshRayWindow(const GridMesh& mesh, const Grid& grid, int axis);

}  // namespace strata
