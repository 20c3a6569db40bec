// dropUnresolvedSpecks: closed components the grid does not resolve (sides no node is sure of,
// or within one cell) are left out of an export; everything a cell across with sure nodes on
// both sides stays, vertices keeping their order. And on a real Boolean of faceted meshes whose
// surfaces nearly touch (a sphere minus a torus), where the contour made hundreds of specks of a
// dozen triangles, the export keeps one closed part of the same volume.
#include "engine/export/drop_specks.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/contour/contour_cells.h"
#include "engine/document/commands.h"
#include "engine/eval/cpu_backend.h"
#include "engine/export/contour_scene.h"
#include "engine/geometry/mesh_check.h"
#include "tests/support/export_cases.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

// A closed octahedron around `at` with half-diagonal r, `leaf`, every triangle's bits `bits`.
void addOctahedron(ExportMesh& m, std::vector<uint8_t>& resolved, glm::dvec3 at, double r,
                   uint32_t leaf, uint8_t bits) {
  const uint32_t b = uint32_t(m.mesh.positions.size());
  for (glm::dvec3 d : {glm::dvec3(r, 0, 0), glm::dvec3(-r, 0, 0), glm::dvec3(0, r, 0),
                       glm::dvec3(0, -r, 0), glm::dvec3(0, 0, r), glm::dvec3(0, 0, -r)})
    m.mesh.positions.push_back(at + d);
  const uint32_t faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : faces) {
    m.mesh.triangles.push_back({b + f[0], b + f[1], b + f[2]});
    m.triangleLeaf.push_back(leaf);
    resolved.push_back(bits);
  }
}

// The scene contoured on the CPU (report in *report) and its mesh checked.
MeshCheck exportedCheck(const Scene& scene, ContourReport* report) {
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  return checkMesh(contourScene(scene, evaluator, ContourOptions{}, progress, report).mesh);
}

TEST(DropSpecks, LeavesOutWhatTheGridDoesNotResolveAndKeepsTheRestInOrder) {
  const double h = 1.0;
  constexpr uint8_t kBoth = kInsideResolved | kOutsideResolved;
  ExportMesh m;
  std::vector<uint8_t> resolved;
  addOctahedron(m, resolved, {0, 0, 0}, 5.0, 1, kBoth);              // a part: kept
  addOctahedron(m, resolved, {20, 0, 0}, 0.3, 2, kBoth);             // within one cell
  addOctahedron(m, resolved, {40, 0, 0}, 3.0, 3, kOutsideResolved);  // encloses no sure node
  addOctahedron(m, resolved, {60, 0, 0}, 3.0, 4, kInsideResolved);   // excludes none
  addOctahedron(m, resolved, {80, 0, 0}, 0.6, 5, kBoth);             // 1.2 cells across: kept
  resolved[8 * 4 + 3] = 0;  // one triangle of the last without bits: its others carry them
  ExportMesh expected;
  std::vector<uint8_t> unused;
  addOctahedron(expected, unused, {0, 0, 0}, 5.0, 1, kBoth);
  addOctahedron(expected, unused, {80, 0, 0}, 0.6, 5, kBoth);

  const DroppedSpecks dropped = dropUnresolvedSpecks(&m, &resolved, h);
  EXPECT_EQ(dropped.components, 3);
  EXPECT_EQ(dropped.triangles, 24u);
  EXPECT_EQ(m.mesh.positions, expected.mesh.positions);
  EXPECT_EQ(m.mesh.triangles, expected.mesh.triangles);
  EXPECT_EQ(m.triangleLeaf, expected.triangleLeaf);
  EXPECT_EQ(resolved.size(), m.mesh.triangles.size());
  EXPECT_TRUE(checkMesh(m.mesh).watertight());
}

// Many parts and specks, so that what stays spans many of the compaction's blocks (65,536
// elements) with specks in most of them: the same as keeping the parts in order.
TEST(DropSpecks, KeepsOrderAcrossManyBlocks) {
  constexpr uint8_t kBoth = kInsideResolved | kOutsideResolved;
  ExportMesh m, expected;
  std::vector<uint8_t> resolved, unused;
  for (int k = 0; k < 30000; ++k) {
    const glm::dvec3 at(20.0 * (k % 100), 20.0 * (k / 100), 0.0);
    if (k % 7 == 3) {
      addOctahedron(m, resolved, at, 0.3, uint32_t(k), kBoth);  // a speck
    } else {
      addOctahedron(m, resolved, at, 3.0, uint32_t(k), kBoth);
      addOctahedron(expected, unused, at, 3.0, uint32_t(k), kBoth);
    }
  }
  ASSERT_GT(m.mesh.triangles.size(), size_t(3) * 65536);
  const DroppedSpecks dropped = dropUnresolvedSpecks(&m, &resolved, 1.0);
  EXPECT_EQ(dropped.components, 30000 / 7 + (30000 % 7 > 3 ? 1 : 0));
  EXPECT_EQ(m.mesh.positions, expected.mesh.positions);
  EXPECT_EQ(m.mesh.triangles, expected.mesh.triangles);
  EXPECT_EQ(m.triangleLeaf, expected.triangleLeaf);
  EXPECT_EQ(resolved.size(), m.mesh.triangles.size());
}

TEST(DropSpecks, NothingToDropChangesNothing) {
  ExportMesh m;
  std::vector<uint8_t> resolved;
  addOctahedron(m, resolved, {0, 0, 0}, 5.0, 1, kInsideResolved | kOutsideResolved);
  const ExportMesh before = m;
  const DroppedSpecks dropped = dropUnresolvedSpecks(&m, &resolved, 1.0);
  EXPECT_EQ(dropped.components, 0);
  EXPECT_EQ(m.mesh.positions, before.mesh.positions);
  EXPECT_EQ(m.mesh.triangles, before.mesh.triangles);
}

TEST(DropSpecks, ASphereMinusAGrazingTorusExportsOnePart) {
  const Scene scene = makeScene(
      op(NodeKind::Difference, {sphere(0.42), meshLeaf(facetedTorus(0.33, 0.12, 96, 48))}), 64);
  ContourReport report;
  const MeshCheck c = exportedCheck(scene, &report);
  EXPECT_TRUE(c.watertight());
  EXPECT_GT(report.droppedSpecks.components, 0);
  EXPECT_EQ(c.components, 1);
  // What was left out is no volume to speak of: each speck lies within one cell.
  EXPECT_LT(double(report.droppedSpecks.components) * std::pow(report.grid.h, 3), 1e-2 * c.volume);
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

TEST(DropSpecks, AResultThatIsAllSpecksIsKept) {
  ExportMesh m;
  std::vector<uint8_t> resolved;
  addOctahedron(m, resolved, {0, 0, 0}, 0.3, 1, kInsideResolved | kOutsideResolved);
  addOctahedron(m, resolved, {5, 0, 0}, 3.0, 2, kOutsideResolved);
  const ExportMesh before = m;
  const DroppedSpecks dropped = dropUnresolvedSpecks(&m, &resolved, 1.0);
  EXPECT_EQ(dropped.components, 0);
  EXPECT_EQ(m.mesh.triangles, before.mesh.triangles);
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

// A cube without its top face, taken as open, beside a closed box: the rays through its missing
// face are left empty, so no node of its inside has all three rays agreeing, and the speck rule
// left the whole cube out of the export (10,212 triangles, "1 speck the grid cannot resolve")
// while the preview showed it solid: an artist's test. Its surface counts as resolved; both
// parts are written, the open cube about as large as the closed one.
TEST(DropSpecks, AnOpenMeshBesideAnotherPartIsNotTakenForASpeck) {
  auto cube = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    cube->positions.push_back(
        glm::dvec3(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5));
  // Outward-facing sides; the top (z = +0.5) left out.
  cube->triangles = {{0, 2, 1}, {1, 2, 3}, {0, 1, 5}, {0, 5, 4}, {2, 6, 7},
                     {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  auto open = std::make_shared<Node>(
      *makeMeshNode(900, "open cube", cube, "/tmp/open_cube.obj", "", /*meshOpen=*/true));
  open->transform.translate = glm::dvec3(2.0, 0.0, 0.0);
  const NodePtr openLeaf = open;
  const Scene scene = makeScene(op(NodeKind::Union, {box(glm::dvec3(1.0)), openLeaf}), 48);
  ContourReport report;
  const MeshCheck c = exportedCheck(scene, &report);
  EXPECT_TRUE(c.watertight());
  EXPECT_EQ(c.components, 2) << report.droppedSpecks.components << " left out";
  EXPECT_EQ(report.droppedSpecks.components, 0);
  EXPECT_NEAR(c.volume, 2.0, 0.15);
}

}  // namespace
}  // namespace strata::test
