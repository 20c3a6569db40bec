// The world bounds of a mesh placed by an affine transform: exactly, bit for bit, what
// including every transformed vertex gives (`transformedBounds`), but for a large mesh in about
// O(log n) a call instead of O(n). A tree of boxes over the mesh's vertices, built once per mesh
// and kept while the mesh lives, lets the search for each axis's two extremes skip every box
// that cannot hold one; only the vertices of the few boxes left are transformed, with the same
// arithmetic as the scan. Asked on every edit (a scene's bounds, the grid of each preview
// evaluation) and every frame of some panels, a scan of a million-vertex scan or of a pattern's
// thousand copies stalled them.
//
// Threads: any number of threads at once (the cache is locked; a tree is immutable once built).
#pragma once

#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>

#include "engine/geometry/mesh.h"

namespace strata {

// The bounds of {world * p : p in points}, by transforming every point (the reference).
Bounds transformedBounds(const std::vector<glm::dvec3>& points, const glm::dmat4& world);

// transformedBounds(mesh->positions, world), bit for bit, through the mesh's tree where it has
// enough vertices to be worth one (built once the mesh's bounds have been scanned 16 times, or by
// prepareMeshWorldBounds). Empty bounds for a null or empty mesh. The mesh must not change while
// any shared_ptr to it lives (meshes in nodes are immutable).
Bounds meshWorldBounds(const std::shared_ptr<const TriangleMesh>& mesh, const glm::dmat4& world);

// Builds the mesh's tree now (where a mesh is loaded, off the editor's UI thread), so that the
// first bounds asked for do not pay for it. Does nothing for small meshes or one already built.
void prepareMeshWorldBounds(const std::shared_ptr<const TriangleMesh>& mesh);

}  // namespace strata
