// Connected components of a triangle mesh's vertices (vertices joined by a triangle).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/geometry/mesh.h"

namespace strata {

// Per vertex, its component's root: the smallest vertex index of the component (the same
// whatever the thread count). Vertices no triangle uses are their own roots. Parallel
// (parallelFor); O(vertices + triangles).
std::vector<uint32_t> vertexComponentRoots(const TriangleMesh& mesh);

}  // namespace strata
