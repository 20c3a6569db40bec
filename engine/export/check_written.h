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
// The half that needs no file can start before the file is written (MeantMeshCheck), so that
// it runs beside the write (whose end waits on the disk); checkWrittenFile then reads the file
// back and compares.
//
// Any thread; parallel inside (parallel_for.h). `progress` is checked between the steps and
// receives stage "check" from 0 to 1 (from the calling thread only).
#pragma once

#include <memory>
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
// The fingerprint of the triangles the file at `path` lists, read back as
// readMeshFileVerbatim reads it: in pieces where the format allows (visitFileTriangles: a
// binary STL never held whole), else whole.
TriangleFingerprint fingerprintFile(const std::string& path, const Progress& progress);
// What a file's fingerprint `found` says against the one `expected` of the triangles written, a
// line naming `path` ("" when they are equal).
std::string fingerprintDifference(const std::string& path, const TriangleFingerprint& found,
                                  const TriangleFingerprint& expected);
// Adds one triangle (its corners as the file stores them) to *f.
void addToFingerprint(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      TriangleFingerprint* f);

// The half of the check that needs no file, on a thread of its own from construction: the
// mesh as the format of `path` will store it (storedMesh) measured by checkMesh and
// fingerprinted. `written`: the mesh about to be written (scene units), read by that thread
// until released() and then no more, so it must live until then; `progress`: cancels it (with
// its own cancel(): the destructor's, which then waits for the thread).
class MeantMeshCheck {
 public:
  MeantMeshCheck(const std::string& path, const TriangleMesh& written, const Progress& progress);
  ~MeantMeshCheck();
  MeantMeshCheck(const MeantMeshCheck&) = delete;
  MeantMeshCheck& operator=(const MeantMeshCheck&) = delete;

  // Waits until the thread has its own copy of `written` (the caller may then free it).
  void released();
  // Waits for the measures; rethrows what stopped them (Cancelled included).
  void wait(MeshCheck* check, TriangleFingerprint* fingerprint);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Checks the file at `path`, just written from the mesh `meant` measures: reads it back and
// compares. Throws strata::Error when the file cannot be read or parsed, Cancelled.
WrittenCheck checkWrittenFile(const std::string& path, MeantMeshCheck& meant, Progress& progress);
// The same in one call, from the mesh written (scene units, as given to writeMeshFile).
WrittenCheck checkWrittenFile(const std::string& path, const TriangleMesh& written,
                              Progress& progress);

}  // namespace strata
