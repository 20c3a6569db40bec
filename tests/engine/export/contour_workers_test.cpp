// contourSceneOnWorkers: tiles taken by whichever worker is free, merged into the mesh one
// backend makes, vertex for vertex; a failure in one worker stops them all and is rethrown.
#include "engine/export/contour_workers.h"

#include <gtest/gtest.h>

#include "engine/eval/cpu_backend.h"
#include "engine/util/error.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

Scene partScene() {
  return makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.1, {1, 1, 1}),
                                             cylinder(0.3, 3.0, {0.2, 0.3, 0.0})}),
                   48);
}

std::vector<std::shared_ptr<Backend>> cpuBackends(int n) {
  std::vector<std::shared_ptr<Backend>> b;
  for (int i = 0; i < n; ++i) b.push_back(std::make_shared<CpuBackend>());
  return b;
}

TEST(ContourWorkers, MakeTheMeshOneBackendMakes) {
  const Scene scene = partScene();
  Progress progress;
  Evaluator one(std::make_shared<CpuBackend>());
  ContourReport single;
  const ExportMesh expected = contourScene(scene, one, ContourOptions{0, 16}, progress, &single);
  for (int workers : {1, 2, 4}) {
    ContourReport r;
    const ExportMesh m = contourSceneOnWorkers(scene, cpuBackends(workers), ContourOptions{0, 16},
                                               workers, progress, &r);
    EXPECT_EQ(r.tiles, single.tiles);
    EXPECT_EQ(r.surfels, single.surfels);
    EXPECT_EQ(r.signDisagreements, single.signDisagreements);
    ASSERT_EQ(m.mesh.positions.size(), expected.mesh.positions.size()) << workers;
    EXPECT_TRUE(m.mesh.positions == expected.mesh.positions) << workers;
    EXPECT_TRUE(m.mesh.triangles == expected.mesh.triangles) << workers;
    EXPECT_TRUE(m.triangleLeaf == expected.triangleLeaf) << workers;
  }
}

TEST(ContourWorkers, ACancelStopsEveryWorker) {
  Progress progress;
  progress.cancel();
  EXPECT_THROW(contourSceneOnWorkers(partScene(), cpuBackends(3), ContourOptions{0, 16}, 3,
                                     progress, nullptr),
               Cancelled);
}

}  // namespace
}  // namespace strata::test
