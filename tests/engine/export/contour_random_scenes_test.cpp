// Robustness on scenes nobody designed: random CSG trees of random primitives, placed off the
// grid, at small resolutions where features are thin and faces ambiguous. Every export must be
// a closed, oriented 2-manifold without duplicate vertices, and tiling must not change it.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

#include "engine/export/contour_scene.h"
#include "tests/support/mesh_invariants.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

NodePtr randomLeaf(std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(-1.0, 1.0), size(0.15, 0.9), angle(0.0, 180.0);
  std::uniform_int_distribution<int> kind(0, 4);
  NodePtr n;
  switch (kind(rng)) {
    case 0:
      n = box({size(rng), size(rng), size(rng)});
      break;
    case 1:
      n = sphere(size(rng) * 0.7);
      break;
    case 2:
      n = cylinder(size(rng) * 0.4, size(rng) * 2);
      break;
    case 3:
      n = torus(0.5, 0.12 + 0.1 * size(rng));
      break;
    default:
      n = box({size(rng) * 0.2, size(rng) * 2, size(rng)});  // thin plates: ambiguous faces
      break;
  }
  Transform t;
  t.translate = {pos(rng), pos(rng), pos(rng)};
  t.rotateDegrees = {angle(rng), angle(rng), angle(rng)};
  return withTransform(n, t);
}

NodePtr randomTree(std::mt19937& rng, int depth) {
  std::uniform_int_distribution<int> op3(0, 2), fan(2, 3);
  if (depth == 0) return randomLeaf(rng);
  const NodeKind kinds[3] = {NodeKind::Union, NodeKind::Difference, NodeKind::Intersection};
  NodeKind k = kinds[op3(rng)];
  auto n = std::make_shared<Node>(*op(k, {}));
  int children = fan(rng);
  for (int c = 0; c < children; ++c)
    n->children.push_back(c == 0 || k != NodeKind::Intersection ? randomTree(rng, depth - 1)
                                                                : randomLeaf(rng));
  return n;
}

size_t duplicatePositions(const TriangleMesh& mesh) {
  std::map<std::tuple<double, double, double>, int> seen;
  size_t duplicates = 0;
  for (const auto& p : mesh.positions)
    if (seen[{p.x, p.y, p.z}]++ > 0) ++duplicates;
  return duplicates;
}

TEST(ContourRandomScenes, AlwaysWatertightAndTilingInvariant) {
  std::mt19937 rng(20261121);
  int exported = 0;
  for (int trial = 0; trial < 40; ++trial) {
    NodePtr root = randomTree(rng, 2);
    for (int resolution : {24, 48}) {
      Scene s = makeScene(root, resolution);
      Evaluator evaluator(std::make_shared<CpuBackend>());
      Progress progress;
      ExportMesh whole;
      try {
        whole = contourScene(s, evaluator, ContourOptions{0, 256}, progress);
      } catch (const Error& e) {
        // Only an empty scene (e.g. an intersection of disjoint parts) may refuse.
        EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
        continue;
      }
      if (whole.mesh.triangles.empty()) continue;  // the result is empty: nothing to check
      ++exported;
      EXPECT_TRUE(isWatertight(whole.mesh)) << "trial " << trial << " at " << resolution;
      EXPECT_EQ(duplicatePositions(whole.mesh), 0u) << "trial " << trial;
      ExportMesh tiled = contourScene(s, evaluator, ContourOptions{0, 8}, progress);
      EXPECT_TRUE(whole.mesh.positions == tiled.mesh.positions) << "trial " << trial;
      EXPECT_TRUE(whole.mesh.triangles == tiled.mesh.triangles) << "trial " << trial;
    }
  }
  EXPECT_GT(exported, 40);
}

}  // namespace
}  // namespace strata::test
