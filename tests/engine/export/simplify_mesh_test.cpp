// simplifyMesh: fewer triangles within a tolerance, with every guarantee of the export kept:
// closed, manifold, oriented, the same genus and components, each triangle's leaf, the volume
// within the shell the tolerance allows;
// flat faces collapse to a few triangles; the Hausdorff distance both ways stays within the
// tolerance (measured independently); chunked and whole runs both keep all of it; a cancel changes
// nothing.
#include "engine/export/simplify_mesh.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "engine/eval/cpu_backend.h"
#include "engine/export/contour_scene.h"
#include "engine/geometry/mesh_check.h"
#include "engine/geometry/mesh_distance.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

struct Contoured {
  ExportMesh mesh;
  double h = 0.0;
};

Contoured contour(const NodePtr& root, int resolution) {
  const Scene scene = makeScene(root, resolution);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  ContourReport report;
  Contoured c;
  c.mesh = contourScene(scene, evaluator, ContourOptions{}, progress, &report);
  c.h = report.grid.h;
  return c;
}

// Checks what simplifying `before` into `after` within `tolerance` must keep.
void expectGuaranteesKept(const ExportMesh& before, const ExportMesh& after, double tolerance) {
  const MeshCheck b = checkMesh(before.mesh), a = checkMesh(after.mesh);
  EXPECT_TRUE(a.watertight());
  EXPECT_TRUE(a.closed());
  EXPECT_TRUE(a.manifold());
  EXPECT_TRUE(a.oriented());
  EXPECT_EQ(a.genus, b.genus);
  EXPECT_EQ(a.components, b.components);
  // Vertices moved off the chords onto the covered surface: the volume is kept to a small part
  // of the shell the tolerance allows (a surface on the chords of a sphere 6 cells across loses
  // about a third of it).
  EXPECT_NEAR(a.volume, b.volume, 0.1 * b.area * tolerance);
  ASSERT_EQ(after.triangleLeaf.size(), after.mesh.triangles.size());
  // Every point of the unsimplified surface within the tolerance of the simplified one and back
  // (the Hausdorff distance, measured independently of the simplifier's own bound).
  Progress progress;
  const SurfaceDeviation d = measureDeviation(before.mesh, after.mesh, false, 0.01 * tolerance,
                                              8 * tolerance, 0.9 * tolerance, progress);
  EXPECT_LE(d.aToBBound, tolerance * (1 + 1e-9));
  EXPECT_FALSE(d.capped);
  EXPECT_LE(d.bToABound, tolerance * (1 + 1e-9));
}

TEST(SimplifyMesh, ABoxCollapsesToAFewTrianglesAndKeepsItsCornersAndVolume) {
  const Contoured c = contour(box({1.0, 0.6, 0.4}), 48);
  ExportMesh m = c.mesh;
  Progress progress;
  const SimplifyReport r = simplifyMesh(&m, 0.25 * c.h, progress);
  EXPECT_FALSE(r.refused);
  EXPECT_EQ(r.trianglesBefore, c.mesh.mesh.triangles.size());
  EXPECT_EQ(r.trianglesAfter, m.mesh.triangles.size());
  // Six flat faces: a few large triangles each, not thousands.
  EXPECT_LT(m.mesh.triangles.size(), 200u) << "from " << r.trianglesBefore;
  expectGuaranteesKept(c.mesh, m, 0.25 * c.h);
  // The eight corners stay sharp: the bounding box is the one before.
  const Bounds before = meshBounds(c.mesh.mesh), after = meshBounds(m.mesh);
  EXPECT_NEAR(glm::length(after.min - before.min), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(after.max - before.max), 0.0, 1e-12);
  // The measured deviation is reported, both ways.
  EXPECT_GT(r.measured.samples, 0u);
  EXPECT_LE(r.measured.bound(), 0.25 * c.h * (1 + 1e-9));
}

TEST(SimplifyMesh, ATorusAndASphereKeepGenusComponentsAndLeaves) {
  const Contoured c =
      contour(op(NodeKind::Union, {torus(0.3, 0.1), sphere(0.15, {0.7, 0.0, 0.0})}), 64);
  ASSERT_EQ(checkMesh(c.mesh.mesh).genus, 1);
  ASSERT_EQ(checkMesh(c.mesh.mesh).components, 2);
  for (size_t chunk : {kTrianglesPerChunk, size_t(3000)}) {  // whole, and in chunks
    ExportMesh m = c.mesh;
    Progress progress;
    const SimplifyReport r = simplifyMesh(&m, 0.25 * c.h, progress, chunk);
    EXPECT_LT(double(r.trianglesAfter), 0.35 * double(r.trianglesBefore)) << chunk;
    expectGuaranteesKept(c.mesh, m, 0.25 * c.h);
    // Each part keeps its own leaf: the sphere's triangles lie beyond x = 0.5.
    uint32_t sphereLeaf = UINT32_MAX;
    for (size_t t = 0; t < c.mesh.mesh.triangles.size(); ++t)
      if (c.mesh.mesh.positions[c.mesh.mesh.triangles[t][0]].x > 0.5)
        sphereLeaf = c.mesh.triangleLeaf[t];
    for (size_t t = 0; t < m.mesh.triangles.size(); ++t)
      EXPECT_EQ(m.mesh.positions[m.mesh.triangles[t][0]].x > 0.5, m.triangleLeaf[t] == sphereLeaf);
  }
}

TEST(SimplifyMesh, AnAttemptBeyondTheBoundIsMeasuredAndTriedAgainTighter) {
  // Rules at 1.5 tolerances let the surface stray beyond the bound: the measurement catches it
  // and a tighter attempt keeps within it.
  const Contoured c = contour(op(NodeKind::Difference, {sphere(0.4), torus(0.3, 0.12)}), 48);
  ExportMesh m = c.mesh;
  std::vector<double> fractions;
  Progress progress([&](const std::string& stage, double fraction) {
    if (stage == "simplify") fractions.push_back(fraction);
  });
  const SimplifyReport r = simplifyMesh(&m, 0.25 * c.h, progress, kTrianglesPerChunk, 1.5);
  EXPECT_FALSE(r.refused) << r.refusedWhy;
  EXPECT_GE(r.attempts, 2);
  EXPECT_LT(r.rulesTolerance, 0.25 * c.h);
  EXPECT_LE(r.measured.bound(), 0.25 * c.h);
  EXPECT_LT(r.trianglesAfter, r.trianglesBefore);
  expectGuaranteesKept(c.mesh, m, 0.25 * c.h);
  for (size_t k = 1; k < fractions.size(); ++k) EXPECT_GE(fractions[k], fractions[k - 1]);
}

TEST(SimplifyMesh, AnOpenMeshIsMeasuredWithoutTheClosedSurfaceBound) {
  // A box without its top: flat regions end at an open edge, where the flat-region bound of a
  // closed surface does not hold; the result stays within the tolerance all the same.
  const Contoured c = contour(box({1.0, 0.6, 0.4}), 40);
  ExportMesh open = c.mesh;
  const double top = meshBounds(c.mesh.mesh).max.z;
  std::vector<std::array<uint32_t, 3>> kept;
  std::vector<uint32_t> keptLeaf;
  for (size_t t = 0; t < open.mesh.triangles.size(); ++t) {
    const auto& tri = open.mesh.triangles[t];
    bool onTop = true;
    for (uint32_t v : tri) onTop = onTop && open.mesh.positions[v].z > top - 1e-9;
    if (onTop) continue;
    kept.push_back(tri);
    keptLeaf.push_back(open.triangleLeaf[t]);
  }
  ASSERT_LT(kept.size(), open.mesh.triangles.size());
  open.mesh.triangles = kept;
  open.triangleLeaf = keptLeaf;
  ExportMesh m = open;
  Progress progress;
  const SimplifyReport r = simplifyMesh(&m, 0.25 * c.h, progress);
  ASSERT_FALSE(r.refused) << r.refusedWhy;
  EXPECT_LT(r.trianglesAfter, r.trianglesBefore / 4);
  EXPECT_LE(r.measured.bound(), 0.25 * c.h);
  const SurfaceDeviation d =
      measureDeviation(open.mesh, m.mesh, false, 0.01 * c.h, 2.0 * c.h, 0.9 * 0.25 * c.h, progress);
  EXPECT_LE(d.bound(), 0.25 * c.h * (1 + 1e-9));
}

TEST(SimplifyMesh, ACancelLeavesTheMeshAsItWas) {
  const Contoured c = contour(sphere(0.4), 32);
  ExportMesh m = c.mesh;
  Progress progress;
  progress.cancel();
  EXPECT_THROW(simplifyMesh(&m, 0.25 * c.h, progress), Cancelled);
  EXPECT_EQ(m.mesh.triangles, c.mesh.mesh.triangles);
  EXPECT_EQ(m.mesh.positions, c.mesh.mesh.positions);
}

TEST(SimplifyMesh, ANonManifoldMeshIsLeftAsItWasAndSaysWhy) {
  // Two tetrahedra sharing one edge: the edge has four faces.
  ExportMesh m;
  m.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}};
  m.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
                      {0, 4, 1}, {0, 1, 5}, {0, 5, 4}, {1, 4, 5}};
  m.triangleLeaf.assign(8, 0);
  const ExportMesh before = m;
  Progress progress;
  const SimplifyReport r = simplifyMesh(&m, 0.1, progress);
  EXPECT_TRUE(r.refused);
  EXPECT_NE(std::string(r.refusedWhy), "");
  EXPECT_EQ(m.mesh.triangles, before.mesh.triangles);
}

}  // namespace
}  // namespace strata::test
