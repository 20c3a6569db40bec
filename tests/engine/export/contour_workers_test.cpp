// contourSceneOnWorkers: tiles taken by whichever worker is free, merged into the mesh one
// backend makes, vertex for vertex; a failure in one worker stops them all and is rethrown.
#include "engine/export/contour_workers.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

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

// The gate before each new tile: with tiles from 9 on held back, the workers do the first 9
// and wait there (none passes the gate), then do the rest once let through; every tile is
// handed on once.
TEST(ContourWorkers, WaitAtTheGateBeforeTilesNotYetTheirTurn) {
  const Scene scene = partScene();
  const ExportTiling tiling = exportTilingOfSize(scene, ContourOptions{}, glm::ivec3(16));
  ASSERT_EQ(tiling.count(), 27);
  constexpr int kHeldFrom = 9;
  std::mutex mutex;
  std::condition_variable changed;
  bool open = false;
  int passedBeyond = 0;
  std::vector<int> handed(27, 0);
  int done = 0;
  size_t triangles = 0;
  Progress progress;
  TileWorkers workers(
      scene, cpuBackends(3), tiling, progress, {},
      [&](int t, const Progress& stopping) {
        std::unique_lock<std::mutex> lock(mutex);
        while (t >= kHeldFrom && !open && !stopping.cancelled())
          changed.wait_for(lock, std::chrono::milliseconds(50));
        if (t >= kHeldFrom && !open) return;
        if (t >= kHeldFrom) ++passedBeyond;
      },
      [&](int t, std::vector<TileContour> contours) {
        std::lock_guard<std::mutex> lock(mutex);
        ++handed[size_t(t)];
        ++done;
        triangles += contours.empty() ? 0 : contours[0].triangles.size();
        changed.notify_all();
      });
  {
    std::unique_lock<std::mutex> lock(mutex);
    ASSERT_TRUE(
        changed.wait_for(lock, std::chrono::seconds(60), [&] { return done == kHeldFrom; }));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // a worker let through would show
  {
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_EQ(done, kHeldFrom);
    EXPECT_EQ(passedBeyond, 0);
    open = true;
  }
  changed.notify_all();
  ContourReport r;
  std::vector<TileContour> kept;
  workers.join(&r, &kept);
  EXPECT_TRUE(kept.empty());  // all handed on
  EXPECT_EQ(r.tiles, 27);
  EXPECT_GT(triangles, 0u);
  for (int t = 0; t < 27; ++t) EXPECT_EQ(handed[size_t(t)], 1) << t;
}

}  // namespace
}  // namespace strata::test
