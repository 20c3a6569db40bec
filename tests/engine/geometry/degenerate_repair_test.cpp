#include "engine/geometry/degenerate_repair.h"

#include <gtest/gtest.h>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_writers.h"

namespace strata {
namespace {

// Reverses every triangle when the mesh's signed volume is negative (so that the tests need not
// get each hand-made winding right).
void orientOutward(TriangleMesh& mesh) {
  if (signedVolume(mesh) >= 0.0) return;
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
}

// A tetrahedron A C D E with B, the midpoint of A-C, inserted on the face A C E's side: the face
// becomes (A, B, E) and (B, C, E), and (A, C, B) closes the gap: a closed mesh with one triangle
// whose corners lie on one line.
TriangleMesh tetrahedronWithFlatTriangle() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 2, 0}, {1, 1, 2}};  // A B C D E
  const uint32_t A = 0, B = 1, C = 2, D = 3, E = 4;
  m.triangles = {{A, D, C}, {A, B, E}, {B, C, E}, {A, C, B}, {A, E, D}, {C, D, E}};
  return m;
}

// An octahedron around (10, 10, 10) with its edge from the top to the first equator vertex
// split at a point `offset` of the way from the top.
TriangleMesh octahedronWithSplitEdge(double offset) {
  TriangleMesh m;
  m.positions = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  for (auto& p : m.positions) p += glm::dvec3(10.0);
  m.triangles = {{0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 2},
                 {1, 3, 2}, {1, 4, 3}, {1, 5, 4}, {1, 2, 5}};
  // Split edge 0 - 2 (triangles (0, 2, 3) and (0, 5, 2)) at m.
  const uint32_t split = uint32_t(m.positions.size());
  m.positions.push_back(m.positions[0] + offset * (m.positions[2] - m.positions[0]));
  m.triangles[0] = {0, split, 3};
  m.triangles.push_back({split, 2, 3});
  m.triangles[3] = {0, 5, split};
  m.triangles.push_back({split, 5, 2});
  return m;
}

TEST(DegenerateRepair, FlipsACollinearTriangleWithItsNeighbour) {
  TriangleMesh mesh = tetrahedronWithFlatTriangle();
  orientOutward(mesh);
  const MeshCheck before = checkMesh(mesh);
  ASSERT_TRUE(before.watertight());
  ASSERT_EQ(before.degenerateTriangles, 1u);
  std::vector<uint32_t> data = {10, 11, 12, 13, 14, 15};
  const DegenerateRepair r = repairDegenerateTriangles(&mesh, nullptr, &data);
  EXPECT_EQ(r.flipped, 1u);
  EXPECT_EQ(r.collapsed, 0u);
  EXPECT_EQ(r.left, 0u);
  const MeshCheck after = checkMesh(mesh);
  EXPECT_TRUE(after.watertight());
  EXPECT_EQ(after.degenerateTriangles, 0u);
  EXPECT_EQ(after.triangles, before.triangles);
  EXPECT_EQ(after.genus, 0);
  EXPECT_DOUBLE_EQ(after.volume, before.volume);  // the same surface
  EXPECT_EQ(data, (std::vector<uint32_t>{10, 11, 12, 13, 14, 15}));
}

TEST(DegenerateRepair, CollapsesAnEdgeWhoseEndsAreStoredAtOnePoint) {
  // 1e-12 apart near 10: distinct doubles, one float32.
  TriangleMesh mesh = octahedronWithSplitEdge(1e-12);
  orientOutward(mesh);
  ASSERT_TRUE(checkMesh(mesh).watertight());
  ASSERT_EQ(checkMesh(mesh).degenerateTriangles, 0u);
  const StoredCoordinate stl = storedCoordinate("part.stl");
  ASSERT_EQ(checkMesh(storedMesh("part.stl", mesh)).degenerateTriangles, 2u);
  std::vector<uint32_t> data(mesh.triangles.size());
  for (size_t i = 0; i < data.size(); ++i) data[i] = uint32_t(i);
  const DegenerateRepair r = repairDegenerateTriangles(&mesh, stl, &data);
  EXPECT_EQ(r.collapsed, 1u);
  EXPECT_EQ(r.left, 0u);
  ASSERT_EQ(mesh.triangles.size(), 8u);
  ASSERT_EQ(data.size(), 8u);
  const MeshCheck stored = checkMesh(storedMesh("part.stl", mesh));
  EXPECT_TRUE(stored.watertight());
  EXPECT_EQ(stored.degenerateTriangles, 0u);
  EXPECT_EQ(stored.genus, 0);
  EXPECT_NEAR(stored.volume, 4.0 / 3.0, 1e-6);
  // The data followed its triangles: the two removed are gone, the rest in order.
  for (size_t i = 0; i + 1 < data.size(); ++i) EXPECT_LT(data[i], data[i + 1]);
}

TEST(DegenerateRepair, LeavesGoodMeshesAsTheyAre) {
  TriangleMesh mesh = octahedronWithSplitEdge(0.5);
  orientOutward(mesh);
  const TriangleMesh before = mesh;
  for (const char* path : {"a.ply", "a.stl", "a.obj"}) {
    const DegenerateRepair r = repairDegenerateTriangles(&mesh, storedCoordinate(path));
    EXPECT_EQ(r.flipped + r.rotated + r.collapsed + r.left, 0u) << path;
    EXPECT_EQ(mesh.triangles, before.triangles) << path;
  }
  // The split octahedron at 1e-12 is good in doubles: nothing to repair there.
  TriangleMesh fine = octahedronWithSplitEdge(1e-12);
  const DegenerateRepair r = repairDegenerateTriangles(&fine, nullptr);
  EXPECT_EQ(r.collapsed + r.left, 0u);
}

TEST(DegenerateRepair, CountsWhatItCannotRepair) {
  // A triangle with one index twice can be neither flipped nor collapsed: left and counted.
  TriangleMesh mesh = tetrahedronWithFlatTriangle();
  mesh.triangles[3] = {0, 0, 2};
  const DegenerateRepair r = repairDegenerateTriangles(&mesh, nullptr);
  EXPECT_EQ(r.left, 1u);
  EXPECT_EQ(r.flipped + r.collapsed, 0u);
}

// storedFlawed (the streamed export's test of each triangle) says of every triangle of a mesh what
// checkMesh counts of the mesh as stored: coincident corners after rounding, collinear ones, good
// ones; with and without a rounding.
TEST(DegenerateRepair, StoredFlawedAgreesWithTheStoredMeshsCheck) {
  const StoredCoordinate stl = storedCoordinate("part.stl");
  for (const double split : {1e-12, 0.5}) {
    const TriangleMesh mesh = octahedronWithSplitEdge(split);
    for (const StoredCoordinate stored : {stl, StoredCoordinate(nullptr)}) {
      size_t flawed = 0;
      for (const auto& t : mesh.triangles)
        flawed +=
            storedFlawed(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], stored);
      const size_t expected = stored ? checkMesh(storedMesh("part.stl", mesh)).degenerateTriangles
                                     : checkMesh(mesh).degenerateTriangles;
      EXPECT_EQ(flawed, expected) << "split " << split << (stored ? ", float32" : ", double");
    }
  }
  const TriangleMesh flat = tetrahedronWithFlatTriangle();
  size_t flawed = 0;
  for (const auto& t : flat.triangles)
    flawed +=
        storedFlawed(flat.positions[t[0]], flat.positions[t[1]], flat.positions[t[2]], nullptr);
  EXPECT_EQ(flawed, checkMesh(flat).degenerateTriangles);
  EXPECT_GT(flawed, 0u);
  EXPECT_TRUE(storedFlawed(glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0), nullptr));
}

}  // namespace
}  // namespace strata
