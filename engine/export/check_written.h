// The check after an export is written: is the file a closed, oriented 2-manifold, and does it
// hold exactly the mesh we meant to write?
//
// Two halves, each at memory speed: checkMesh (mesh_check.h) on the written mesh as its format
// stores it (storedMesh, mesh_writers.h: the positions the file holds), and the file read back
// as it lists its triangles (readMeshFileVerbatim, or in pieces where the format allows:
// visitFileTriangles, a binary STL never held whole) compared with that mesh by a fingerprint of
// every triangle's three corner positions (two independent 64-bit sums of a strong hash, so the
// order in which the format lists triangles does not matter). A file that differs (a writer
// bug, a truncated or altered file that still parses) is named in `fileDifference` and is then
// checked itself, read back as readMeshFileRaw reads it, so the report describes the file.
//
// Synchronous; any thread; parallel inside (parallel_for.h). `progress` is checked between the
// steps and receives stage "check" from 0 to 1.
#pragma once

#include <string>

#include "engine/geometry/mesh.h"
#include "engine/geometry/mesh_check.h"
#include "engine/util/progress.h"

namespace strata {

// The verdict: the file holds the mesh meant, a closed, manifold, consistently oriented mesh
// with positive volume, finite coordinates and no degenerate triangles.
inline bool writtenCheckPassed(const MeshCheck& c, const std::string& fileDifference) {
  return fileDifference.empty() && c.watertight() && c.volume > 0.0 && c.degenerateTriangles == 0;
}

struct WrittenCheck {
  MeshCheck check;             // of the file's mesh
  std::string fileDifference;  // "" when the file holds the mesh written; else what differs
  bool passed() const { return writtenCheckPassed(check, fileDifference); }
};

// Checks the file at `path`, just written from `written` (scene units, as given to
// writeMeshFile; taken by value and rounded in place: std::move it in where it is not needed
// after, so that the check holds no copy). Throws strata::Error when the file cannot be read or
// parsed, Cancelled.
WrittenCheck checkWrittenFile(const std::string& path, TriangleMesh written, Progress& progress);

// The fingerprint both halves compare: the triangle count, and two sums over triangles of
// different 64-bit hashes of the bits of their corners' coordinates in order (-0.0 as 0.0).
// Independent of the order of the triangles and of vertex indexing; any change to a
// corner's coordinate or to a triangle's winding changes it (but for a 2^-128 chance).
struct TriangleFingerprint {
  size_t triangles = 0;
  uint64_t sum = 0;
  uint64_t mixedSum = 0;
  bool operator==(const TriangleFingerprint& o) const {
    return triangles == o.triangles && sum == o.sum && mixedSum == o.mixedSum;
  }
};
TriangleFingerprint fingerprintTriangles(const TriangleMesh& mesh);

}  // namespace strata
