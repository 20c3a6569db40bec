// checkWrittenFile: the check after an export, on the mesh as its format stores it, and the
// file compared with that mesh by a fingerprint of its triangles. It must pass every format's
// own file (whatever order the format lists triangles in) and catch a file that does not hold
// what was written: a changed coordinate, a flipped winding, a missing triangle.
#include "engine/export/check_written.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "tests/support/fresh_path.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

// Outward, counter-clockwise seen from outside.
const uint32_t kCubeTriangles[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                        {0, 1, 5}, {0, 5, 4}, {3, 7, 6}, {3, 6, 2},
                                        {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};

// A cube of side `size` at `at`, triangles tagged `leaf`.
void addCube(ExportMesh& em, glm::dvec3 at, double size, uint32_t leaf) {
  const uint32_t base = uint32_t(em.mesh.positions.size());
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c == 1 || c == 2 || c == 5 || c == 6) ? 1 : 0,
                            (c == 2 || c == 3 || c == 6 || c == 7) ? 1 : 0, c >= 4 ? 1 : 0);
    em.mesh.positions.push_back(at + size * corner);
  }
  for (const auto& t : kCubeTriangles) {
    em.mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    em.triangleLeaf.push_back(leaf);
  }
}

// Three cubes of two leaves, interleaved so that OBJ (grouped by leaf) reorders the triangles;
// coordinates that float32 and %.9g round (0.1, 1/3).
ExportMesh threeCubes() {
  ExportMesh em;
  addCube(em, {0.1, 0.1, 0.1}, 1.0 / 3.0, 1);
  addCube(em, {2.1, 0.1, 0.1}, 0.7, 2);
  addCube(em, {4.1, 0.3, -0.1}, 1.1, 1);
  em.leaves[1] = {"one", {1.0f, 0.0f, 0.0f}};
  em.leaves[2] = {"two", {0.0f, 1.0f, 0.0f}};
  return em;
}

std::string freshPath(const std::string& name) {
  return test::freshPath("strata_check_written", name);
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void putBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST(CheckWritten, EveryFormatsOwnFilePassesAndMeasuresAsTheFileReadBack) {
  const ExportMesh em = threeCubes();
  for (const char* ext : {"stl", "obj", "ply", "3mf"}) {
    SCOPED_TRACE(ext);
    const std::string path = freshPath(std::string("cubes.") + ext);
    writeMeshFile(path, em);
    Progress progress;
    const WrittenCheck c = checkWrittenFile(path, em.mesh, progress);
    EXPECT_EQ(c.fileDifference, "");
    EXPECT_TRUE(c.passed());
    // The same measures as checking the file itself, read back as it says.
    const MeshCheck file = checkMesh(readMeshFileRaw(path));
    EXPECT_EQ(c.check.triangles, file.triangles);
    EXPECT_EQ(c.check.components, 3);
    EXPECT_EQ(c.check.components, file.components);
    EXPECT_EQ(c.check.genus, file.genus);
    EXPECT_NEAR(c.check.volume, file.volume, 1e-12 * std::abs(file.volume));
    EXPECT_NEAR(c.check.area, file.area, 1e-12 * file.area);
  }
}

// Binary STL: facet f's vertex v's coordinate k is the float at 84 + 50 f + 12 + 12 v + 4 k.
size_t stlCoordinate(size_t facet, int vertex, int axis) {
  return 84 + 50 * facet + 12 + 12 * size_t(vertex) + 4 * size_t(axis);
}

TEST(CheckWritten, CatchesAFileWhoseCoordinateChanged) {
  const ExportMesh em = threeCubes();
  const std::string path = freshPath("moved.stl");
  writeMeshFile(path, em);
  std::string bytes = fileBytes(path);
  float value;
  std::memcpy(&value, &bytes[stlCoordinate(5, 1, 2)], 4);
  value = std::nextafter(value, 10.0f);  // one float step: still parses, still plausible
  std::memcpy(&bytes[stlCoordinate(5, 1, 2)], &value, 4);
  putBytes(path, bytes);
  Progress progress;
  const WrittenCheck c = checkWrittenFile(path, em.mesh, progress);
  EXPECT_NE(c.fileDifference.find(path), std::string::npos) << c.fileDifference;
  EXPECT_NE(c.fileDifference.find("not those written"), std::string::npos) << c.fileDifference;
  EXPECT_FALSE(c.passed());
  EXPECT_FALSE(c.check.closed());  // the report describes the file: the moved corner tore it
}

TEST(CheckWritten, CatchesAFlippedWindingAndAMissingTriangle) {
  const ExportMesh em = threeCubes();
  {
    const std::string path = freshPath("flipped.stl");
    writeMeshFile(path, em);
    std::string bytes = fileBytes(path);
    std::string corner1 = bytes.substr(stlCoordinate(7, 1, 0), 12);
    bytes.replace(stlCoordinate(7, 1, 0), 12, bytes.substr(stlCoordinate(7, 2, 0), 12));
    bytes.replace(stlCoordinate(7, 2, 0), 12, corner1);
    putBytes(path, bytes);
    Progress progress;
    const WrittenCheck c = checkWrittenFile(path, em.mesh, progress);
    EXPECT_NE(c.fileDifference, "");
    EXPECT_FALSE(c.passed());
    EXPECT_FALSE(c.check.oriented());
  }
  {
    const std::string path = freshPath("short.obj");
    writeMeshFile(path, em);
    std::string text = fileBytes(path);
    const size_t lastFace = text.rfind("\nf ");
    ASSERT_NE(lastFace, std::string::npos);
    text.erase(lastFace + 1, text.find('\n', lastFace + 1) - lastFace);
    putBytes(path, text);
    Progress progress;
    const WrittenCheck c = checkWrittenFile(path, em.mesh, progress);
    EXPECT_NE(c.fileDifference.find("holds 35 triangles, not the 36 written"), std::string::npos)
        << c.fileDifference;
    EXPECT_FALSE(c.passed());
    EXPECT_FALSE(c.check.closed());
  }
}

TEST(CheckWritten, TheFingerprintIgnoresOrderAndIndexingButNotWinding) {
  const TriangleMesh mesh = threeCubes().mesh;
  const TriangleFingerprint f = fingerprintTriangles(mesh);
  EXPECT_EQ(f.triangles, 36u);
  TriangleMesh reordered = mesh;
  std::reverse(reordered.triangles.begin(), reordered.triangles.end());
  EXPECT_TRUE(fingerprintTriangles(reordered) == f);
  TriangleMesh unindexed;  // every corner its own vertex, as a binary STL lists them
  for (const auto& t : mesh.triangles) {
    const uint32_t base = uint32_t(unindexed.positions.size());
    for (uint32_t v : t) unindexed.positions.push_back(mesh.positions[v]);
    unindexed.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_TRUE(fingerprintTriangles(unindexed) == f);
  TriangleMesh flipped = mesh;
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  EXPECT_FALSE(fingerprintTriangles(flipped) == f);
  TriangleMesh rotated = mesh;  // the same triangle and winding, from another corner
  rotated.triangles[3] = {mesh.triangles[3][1], mesh.triangles[3][2], mesh.triangles[3][0]};
  EXPECT_FALSE(fingerprintTriangles(rotated) == f);  // writers never rotate: a change is a change
}

TEST(CheckWritten, ACancelledCheckThrows) {
  const ExportMesh em = threeCubes();
  const std::string path = freshPath("cancel.ply");
  writeMeshFile(path, em);
  Progress progress;
  progress.cancel();
  EXPECT_THROW(checkWrittenFile(path, em.mesh, progress), Cancelled);
}

// The read-back half honours cancel too: between reading the file and parsing it.
TEST(CheckWritten, ACancelledReadBackThrows) {
  const ExportMesh em = threeCubes();
  const std::string path = freshPath("cancel-read.stl");
  writeMeshFile(path, em);
  Progress running;
  EXPECT_EQ(readMeshFileVerbatim(path, nullptr, &running).triangles.size(),
            em.mesh.triangles.size());
  Progress cancelled;
  cancelled.cancel();
  EXPECT_THROW(readMeshFileVerbatim(path, nullptr, &cancelled), Cancelled);
}

// The check reads back a file Strata wrote: no input limit refuses it, whatever the format
// (an export may hold more triangles than an input is allowed).
TEST(CheckWritten, NoInputLimitRefusesOurOwnFile) {
  const ExportMesh em = threeCubes();
  setMaxInputTriangles(10);  // fewer than the 36 written
  for (const char* ext : {"stl", "obj", "ply", "3mf"}) {
    SCOPED_TRACE(ext);
    const std::string path = freshPath(std::string("limit.") + ext);
    writeMeshFile(path, em);
    Progress progress;
    EXPECT_TRUE(checkWrittenFile(path, em.mesh, progress).passed());
    EXPECT_THROW(readMeshFile(path), Error);  // as an input, the limit holds
  }
  setMaxInputTriangles(kDefaultMaxInputTriangles);
}

// A child Progress stops with its parent, and alone; its own cancel leaves the parent running.
TEST(CheckWritten, ProgressChildrenCancelWithTheirParent) {
  Progress parent;
  Progress child(&parent);
  EXPECT_FALSE(child.cancelled());
  parent.cancel();
  EXPECT_TRUE(child.cancelled());
  EXPECT_THROW(child.check(), Cancelled);
  Progress other;
  Progress alone(&other);
  alone.cancel();
  EXPECT_TRUE(alone.cancelled());
  EXPECT_FALSE(other.cancelled());
}

// The half that needs no file, started before the write: measures what the one-call check
// measures, stops with the caller's cancel, and may be dropped unfinished (its destructor stops
// and waits for its thread) while the mesh it reads is still alive.
TEST(CheckWritten, TheMeantMeshCheckBesideTheWrite) {
  const ExportMesh em = threeCubes();
  const std::string path = freshPath("beside.stl");
  Progress progress;
  {
    MeantMeshCheck meant(path, em.mesh, progress);
    meant.released();
    writeMeshFile(path, em);
    const WrittenCheck c = checkWrittenFile(path, meant, progress);
    const WrittenCheck once = checkWrittenFile(path, em.mesh, progress);
    EXPECT_TRUE(c.passed());
    EXPECT_EQ(c.check.triangles, once.check.triangles);
    EXPECT_EQ(c.check.volume, once.check.volume);
    EXPECT_EQ(c.check.genus, once.check.genus);
  }
  {
    Progress cancelled;
    cancelled.cancel();
    MeantMeshCheck meant(path, em.mesh, cancelled);
    MeshCheck check;
    TriangleFingerprint fingerprint;
    EXPECT_THROW(meant.wait(&check, &fingerprint), Cancelled);
  }
  for (int k = 0; k < 20; ++k) {
    Progress running;
    MeantMeshCheck dropped(path, em.mesh, running);  // destroyed at once, finished or not
  }
}

}  // namespace
}  // namespace strata
