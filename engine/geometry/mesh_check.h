// Topological and geometric checks of triangle meshes, and the repairs that are safe to make.
#pragma once

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "engine/geometry/mesh.h"
#include "engine/util/progress.h"

namespace strata {

// What a mesh is, measured. Edges are counted after welding identical positions.
struct MeshCheck {
  size_t vertices = 0;
  size_t triangles = 0;
  size_t boundaryEdges = 0;        // edges with one incident triangle
  size_t nonManifoldEdges = 0;     // edges with more than two incident triangles
  size_t misorientedEdges = 0;     // manifold edges whose two triangles traverse them the same way
  size_t degenerateTriangles = 0;  // zero area (repeated index or collinear corners)
  size_t nonFiniteCoordinates = 0;
  int components = 0;   // edge-connected components
  int genus = -1;       // for a closed oriented manifold: sum over components of
                        // (2 - chi_c) / 2; -1 when not defined
  double volume = 0.0;  // signed
  double area = 0.0;
  double smallestTriangleArea = 0.0;
  // The three above are measured about the centre of the triangles' bounding box, so a mesh far
  // from the origin loses no precision; a mesh more than kMaxMeasurableExtent across may measure
  // +-inf, one less than kMinMeasurableExtent across 0.

  bool closed() const { return boundaryEdges == 0; }
  bool manifold() const { return nonManifoldEdges == 0; }
  bool oriented() const { return misorientedEdges == 0; }
  bool watertight() const {
    return closed() && manifold() && oriented() && nonFiniteCoordinates == 0;
  }
};

// Measures `mesh`. With `progress`, checks for cancellation between its passes and in each chunk
// of the edge and component passes (throws Cancelled): a cancel waits at most for the pass
// running (the welding sort, the triangles' measures, the half-edges' sort; the whole check of
// 4.8 million triangles took 0.53 s on a 2-core machine).
MeshCheck checkMesh(const TriangleMesh& mesh, const Progress* progress = nullptr);

// checkMesh's triangle measures (degenerate triangles, area, smallest area, signed volume) for a
// check that never holds the mesh (engine/export/check_streamed.h): triangles fed one at a time
// in the mesh's order, summed as checkMesh sums them (in blocks of kMeasureBlock), so that the
// measures equal checkMesh's on the same triangles. (usedLo, usedHi): the box around the
// vertices the triangles use. finish() adds the degenerate count to *check and sets its area,
// volume and smallest triangle area. A run of the triangles may be measured apart (on another
// thread) and appended after the run before it, where that run ends on a block boundary: the
// sums stay checkMesh's. Not thread-safe.
constexpr size_t kMeasureBlock = 32768;
class TriangleMeasures {
 public:
  TriangleMeasures(const glm::dvec3& usedLo, const glm::dvec3& usedHi);
  ~TriangleMeasures();
  TriangleMeasures(TriangleMeasures&&) noexcept;
  TriangleMeasures& operator=(TriangleMeasures&&) noexcept;
  // `repeatedVertex`: two corners weld (checkMesh counts the triangle as degenerate).
  void add(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, bool repeatedVertex);
  // The triangles `later` measured, after this one's: throws strata::Error where this one's
  // count is not a multiple of kMeasureBlock (a block would be summed in two parts).
  void append(TriangleMeasures&& later);
  void finish(MeshCheck* check);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The bits of a coordinate, -0.0 as 0.0: two positions weld (checkMesh, prepareMesh) exactly
// when their coordinates' bits are equal.
inline uint64_t coordinateBits(double v) {
  if (v == 0.0) v = 0.0;
  uint64_t bits;
  std::memcpy(&bits, &v, sizeof(bits));
  return bits;
}

// The largest and smallest span of coordinates whose volumes (up to span^3) and areas a double
// holds without overflow or underflow: 2^340 (about 2.2e102) and 2^-340 (about 4.5e-103).
// prepareMesh's orientation, degeneracy and nesting tests run in a frame where they neither
// overflow nor underflow, whatever the (finite) coordinates.
constexpr double kMaxMeasurableExtent = 0x1p340;
constexpr double kMinMeasurableExtent = 0x1p-340;

// The largest side of the axis-aligned box around the positions (largestExtent) or around the
// vertices that the triangles use (largestUsedExtent: never larger, but slower), NaN
// coordinates left out: 0 when there are none, +inf when the side exceeds a double.
double largestExtent(const std::vector<glm::dvec3>& positions);
double largestUsedExtent(const TriangleMesh& mesh);

struct PrepareReport {
  size_t weldedVertices = 0;       // vertices merged into an identical one
  size_t removedDegenerate = 0;    // triangles removed (repeated index or zero area)
  size_t reorientedTriangles = 0;  // triangles flipped to agree with their neighbours
  // Closed shells flipped whole: one inside none (or inside an even number of others) that
  // pointed in, turned outward; one inside an odd number of others (a cavity, by the even-odd
  // nesting rule) that pointed out, turned inward.
  size_t shellsTurnedOutward = 0;
  size_t cavitiesTurnedInward = 0;
  size_t shells = 0;  // edge-connected shells (triangles joined across manifold edges)
  bool flippedInsideOut() const { return shellsTurnedOutward + cavitiesTurnedInward > 0; }
  size_t removedUnreferenced = 0;  // vertices no remaining triangle used, dropped
  MeshCheck check;                 // of the prepared mesh
};

// Welds identical positions, removes degenerate triangles, makes each connected shell's
// orientation consistent and its normals point out of the solid (shells nested inside other
// shells, i.e. cavities, point into the cavity). Never moves a vertex.
PrepareReport prepareMesh(TriangleMesh& mesh);

// Merges vertices with identical coordinates (-0.0 equals 0.0; non-finite positions are never
// merged) and drops vertices no triangle uses; keeps the first occurrence's order. Returns how
// many vertices were merged into another. Used by readers of unindexed formats (STL).
size_t weldIdenticalPositions(TriangleMesh& mesh);

}  // namespace strata
