// Shared invariant checks for meshes produced by the exporter.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/geometry/mesh_check.h"

namespace strata::test {

// Every edge shared by exactly two faces, consistent orientation, positive volume, no
// degenerate triangles, finite coordinates.
inline ::testing::AssertionResult isWatertight(const TriangleMesh& mesh) {
  MeshCheck c = checkMesh(mesh);
  if (c.triangles == 0) return ::testing::AssertionFailure() << "no triangles";
  if (!c.closed()) return ::testing::AssertionFailure() << c.boundaryEdges << " boundary edges";
  if (!c.manifold())
    return ::testing::AssertionFailure() << c.nonManifoldEdges << " non-manifold edges";
  if (!c.oriented())
    return ::testing::AssertionFailure() << c.misorientedEdges << " misoriented edges";
  if (c.nonFiniteCoordinates)
    return ::testing::AssertionFailure() << c.nonFiniteCoordinates << " non-finite coordinates";
  if (c.degenerateTriangles)
    return ::testing::AssertionFailure() << c.degenerateTriangles << " degenerate triangles";
  if (!(c.volume > 0.0)) return ::testing::AssertionFailure() << "volume " << c.volume;
  return ::testing::AssertionSuccess();
}

}  // namespace strata::test
