// The CUDA backend against the CPU reference: identical surfels ray by ray (same per-ray math,
// same tie rules), identical node signs and mesh topology on export, equal volumes. Labelled
// `gpu`; without a CUDA device every test skips and says why.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>

#include "engine/export/contour_scene.h"
#include "engine/export/contour_workers.h"
#include "engine/io/scene_file.h"
#include "engine/jobs/preview_worker.h"
#include "gpu/cuda_backend.h"
#include "tests/support/mesh_invariants.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

class CudaVsCpu : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!cudaDeviceAvailable(&why)) GTEST_SKIP() << "no CUDA device (" << why << "): skipped";
    cuda_ = makeCudaBackend();
  }
  std::shared_ptr<Backend> cuda_;
};

// Evaluates on both backends and compares the root LDIs exactly.
void expectIdentical(const Scene& scene, const std::shared_ptr<Backend>& cuda, const char* what) {
  Progress progress;
  Evaluator onCpu(std::make_shared<CpuBackend>()), onGpu(cuda);
  EvalResult a = onCpu.evaluate(scene, {}, progress);
  EvalResult b = onGpu.evaluate(scene, {}, progress);
  auto x = onCpu.backend().download(a.root);
  auto y = onGpu.backend().download(b.root);
  ASSERT_TRUE(x->grid == y->grid) << what;
  for (int axis = 0; axis < 3; ++axis) {
    ASSERT_EQ(x->axes[axis].offsets, y->axes[axis].offsets) << what << " axis " << axis;
    ASSERT_EQ(x->axes[axis].surfels.size(), y->axes[axis].surfels.size());
    for (size_t k = 0; k < x->axes[axis].surfels.size(); ++k) {
      const Surfel& s = x->axes[axis].surfels[k];
      const Surfel& t = y->axes[axis].surfels[k];
      ASSERT_EQ(s.depth, t.depth) << what << " axis " << axis << " surfel " << k;
      ASSERT_EQ(s.normal, t.normal) << what;
      ASSERT_EQ(s.tag, t.tag) << what;
    }
  }
  EXPECT_NEAR(a.measure.volume, b.measure.volume, 1e-9 * std::max(1.0, a.measure.volume)) << what;
  EXPECT_NEAR(a.measure.area, b.measure.area, 1e-9 * std::max(1.0, a.measure.area)) << what;
  // The thinnest wall: the same per-ray math and the same tie rule, so the same bits.
  EXPECT_EQ(a.measure.thinnestWall, b.measure.thinnestWall) << what;
  EXPECT_EQ(a.measure.thinnestAt, b.measure.thinnestAt) << what;
  EXPECT_EQ(a.computed, b.computed);

  // The editor's splats, made on each backend: the same bits in the same order.
  SplatsHandle p = onCpu.backend().splats(a.root, progress);
  SplatsHandle q = onGpu.backend().splats(b.root, progress);
  ASSERT_NE(p->hostData(), nullptr);
  ASSERT_EQ(q->hostData(), nullptr) << "CUDA splats stay on the device";
  ASSERT_EQ(p->count(), q->count()) << what;
  std::vector<Splat> onDevice(q->count());
  q->copyToHost(onDevice.data());
  EXPECT_EQ(std::memcmp(p->hostData(), onDevice.data(), p->bytes()), 0) << what << ": splats";
  for (int level = 0; level < kSplatLevels; ++level)
    EXPECT_EQ(p->levels().end[level], q->levels().end[level]) << what << ": level " << level;
}

// Exports on both backends in tiles of `tile` cells: the same mesh, vertex for vertex.
void expectSameExport(const Scene& scene, const std::shared_ptr<Backend>& cuda, int tile) {
  Progress progress;
  Evaluator onCpu(std::make_shared<CpuBackend>()), onGpu(cuda);
  ExportMesh a = contourScene(scene, onCpu, ContourOptions{0, tile}, progress);
  ExportMesh b = contourScene(scene, onGpu, ContourOptions{0, tile}, progress);
  EXPECT_TRUE(isWatertight(b.mesh));
  EXPECT_TRUE(a.mesh.triangles == b.mesh.triangles);
  EXPECT_TRUE(a.mesh.positions == b.mesh.positions);
}

TEST_F(CudaVsCpu, AnalyticBooleansMatchRayByRay) {
  for (int resolution : {64, 160}) {
    expectIdentical(
        makeScene(op(NodeKind::Union, {sphere(1, {-0.5, 0, 0}), sphere(1, {0.5, 0, 0})}),
                  resolution),
        cuda_, "sphere union");
    expectIdentical(
        makeScene(op(NodeKind::Intersection, {cylinder(1, 3, {}, {0, 90, 0}),
                                              cylinder(1, 3, {}, {90, 0, 0}), cylinder(1, 3)}),
                  resolution),
        cuda_, "steinmetz");
    expectIdentical(makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2)}), resolution),
                    cuda_, "cube minus ball");
    expectIdentical(
        makeScene(op(NodeKind::Intersection, {torus(1, 0.25), box({4, 4, 1}, {0, 0, 0.5})}),
                  resolution),
        cuda_, "torus half");
  }
}

TEST_F(CudaVsCpu, GridAlignedTiesMatch) {
  NodePtr a = box({1, 1, 1}, {0.5, 0.5, 0.5});
  NodePtr b = box({1, 1, 1}, {1.5, 0.5, 0.5});
  Scene s = makeSceneInBox(op(NodeKind::Union, {a, b}), 64, {-1, -1, -1}, {3, 3, 3});
  expectIdentical(s, cuda_, "cubes sharing a face");
  s.root = op(NodeKind::Difference, {a, a});
  expectIdentical(s, cuda_, "A - A");
}

TEST_F(CudaVsCpu, RealMeshesMatch) {
  auto bunny = dataMesh("bunny.obj");
  auto armadillo = dataMesh("armadillo.obj");
  Bounds b = meshBounds(*bunny);
  NodePtr x = meshLeaf(bunny), y = meshLeaf(bunny, b.size() * glm::dvec3(0.3, 0.2, 0.1));
  for (int resolution : {128, 512}) {
    expectIdentical(makeScene(op(NodeKind::Difference, {x, y}), resolution), cuda_, "bunny");
    expectIdentical(makeScene(meshLeaf(armadillo), resolution), cuda_, "armadillo");
  }
}

// An open mesh (holes every 400th triangle): the rays through its holes are left empty on both
// backends alike, and its export is the same mesh.
TEST_F(CudaVsCpu, AnOpenMeshMatches) {
  auto open = withHoles(*dataMesh("bunny.obj"), 400);
  for (int resolution : {96, 384}) {
    expectIdentical(makeScene(meshLeaf(open), resolution), cuda_, "open bunny");
    expectSameExport(makeScene(meshLeaf(open), resolution), cuda_, 64);
  }
}

TEST_F(CudaVsCpu, SceneFilesMatch) {
  for (const char* name :
       {"demo.strata.json", "bone_scaffold.strata.json", "bone_scaffold_scaled_copy.strata.json",
        "flange_patterns.strata.json"}) {
    Scene s = loadScene(assetsDir() + "/scenes/" + name);
    expectIdentical(s, cuda_, name);
  }
}

TEST_F(CudaVsCpu, ExportedMeshesAreIdentical) {
  Scene s = loadScene(assetsDir() + "/scenes/demo.strata.json");
  s.settings.resolution = 192;
  expectSameExport(s, cuda_, 64);
}

// The tiles of one export spread over several CUDA workers (--gpus: one a device, and here
// also three on device 0, which one GPU can run): the CPU's mesh, vertex for vertex.
TEST_F(CudaVsCpu, ExportOnSeveralWorkersMatchesTheCpu) {
  Scene s = loadScene(assetsDir() + "/scenes/demo.strata.json");
  Progress progress;
  Evaluator cpu(std::make_shared<CpuBackend>());
  const ExportMesh expected = contourScene(s, cpu, ContourOptions{192, 48}, progress);
  const int devices = cudaDeviceCount();
  for (int workers : {devices, 3}) {
    std::vector<std::shared_ptr<Backend>> backends{cuda_};
    for (int w = 1; w < workers; ++w) backends.push_back(makeCudaBackend(w % devices));
    ContourReport r;
    const ExportMesh m = contourSceneOnWorkers(s, backends, ContourOptions{192, 48},
                                               (workers + devices - 1) / devices, progress, &r);
    EXPECT_GT(r.tiles, 4);
    EXPECT_TRUE(m.mesh.positions == expected.mesh.positions) << workers << " workers";
    EXPECT_TRUE(m.mesh.triangles == expected.mesh.triangles) << workers << " workers";
    EXPECT_TRUE(m.triangleLeaf == expected.triangleLeaf) << workers << " workers";
  }
}

// Leaves small against the grid are stored windowed on both backends (with different windows:
// exact on the CPU, from the vertex box on the GPU); the results must still be identical: many
// small parts united and cut, and a root that is one small leaf (splats and contours then read
// a windowed root).
TEST_F(CudaVsCpu, SmallPartsOnABigGridMatch) {
  std::vector<NodePtr> parts, cutters;
  uint64_t seed = 7;
  auto next = [&](double lo, double hi) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * double(seed >> 11) / double(1ull << 53);
  };
  for (int k = 0; k < 300; ++k)
    parts.push_back(box(glm::dvec3(next(0.2, 1.5), next(0.2, 1.5), next(0.2, 1.5)),
                        glm::dvec3(next(-9, 9), next(-9, 9), next(-9, 9))));
  parts.push_back(box(glm::dvec3(14.0), glm::dvec3(0.0)));  // one part over most of the grid
  // All sampled in one batch (Backend::sampleMeshes) with parts the grid does not reach and a
  // mesh without triangles.
  parts.push_back(box(glm::dvec3(1.0), glm::dvec3(30.0, 0.0, 0.0)));
  parts.push_back(box(glm::dvec3(2.0), glm::dvec3(10.5, 10.5, 0.0)));  // partly inside
  parts.push_back(meshLeaf(std::make_shared<TriangleMesh>()));
  for (int k = 0; k < 60; ++k)
    cutters.push_back(sphere(next(0.2, 1.0), glm::dvec3(next(-9, 9), next(-9, 9), next(-9, 9))));
  auto united = std::make_shared<Node>(*op(NodeKind::Union, {}));
  united->children = parts;
  auto cut = std::make_shared<Node>(*op(NodeKind::Difference, {}));
  cut->children = {united};
  cut->children.insert(cut->children.end(), cutters.begin(), cutters.end());
  const glm::dvec3 lo(-10.0), hi(10.0);
  expectIdentical(makeSceneInBox(united, 128, lo, hi), cuda_, "300 small boxes and a big one");
  expectIdentical(makeSceneInBox(cut, 128, lo, hi), cuda_, "minus 60 small spheres");
  const Scene single = makeSceneInBox(sphere(0.8, glm::dvec3(2.0, -3.0, 1.0)), 128, lo, hi);
  expectIdentical(single, cuda_, "one small sphere as the root");
  expectSameExport(single, cuda_, 64);
}

// Offsets (engine/ldi/offset_ldi.h and its twin gpu/ldi/offset_ldi.cu) and the modifiers built
// from them: the analytic cases of OffsetAnalytic at two resolutions, real meshes, a modifier
// inside a tree, and one export.
TEST_F(CudaVsCpu, ModifiersMatchRayByRay) {
  ASSERT_TRUE(cuda_->evaluatesModifiers());
  for (int resolution : {48, 96}) {
    expectIdentical(makeScene(modifier(NodeKind::Offset, 0.25, {sphere(1)}), resolution), cuda_,
                    "sphere grown");
    expectIdentical(makeScene(modifier(NodeKind::Offset, -0.25, {sphere(1)}), resolution), cuda_,
                    "sphere shrunk");
    expectIdentical(makeScene(modifier(NodeKind::Offset, 0.25, {box({2, 2, 2})}), resolution),
                    cuda_, "cube grown");
    expectIdentical(makeScene(modifier(NodeKind::Offset, -0.25, {box({2, 2, 2})}), resolution),
                    cuda_, "cube shrunk");
    expectIdentical(makeScene(modifier(NodeKind::Shell, 0.1, {sphere(1)}), resolution), cuda_,
                    "sphere shelled");
    {
      // Shelled, open where a box cuts its top (Node::opening).
      NodePtr top = box({4, 4, 1}, {0, 0, 1});
      auto opened = std::make_shared<Node>(
          *modifier(NodeKind::Shell, 0.1, {op(NodeKind::Difference, {sphere(1), top})}));
      opened->opening = top->id;
      expectIdentical(makeScene(opened, resolution), cuda_, "sphere shelled, open where cut");
    }
    expectIdentical(makeScene(modifier(NodeKind::Round, 0.25, {box({2, 2, 2})}), resolution), cuda_,
                    "cube rounded");
    expectIdentical(
        makeScene(modifier(NodeKind::Fillet, 0.2,
                           {op(NodeKind::Union, {box({2, 1, 1}), sphere(0.7, {1, 0.5, 0})})}),
                  resolution),
        cuda_, "fillet of a seam");
  }
  auto bunny = dataMesh("bunny.obj");
  auto armadillo = dataMesh("armadillo.obj");
  const double bunnySize = glm::length(meshBounds(*bunny).size());
  const double armadilloSize = glm::length(meshBounds(*armadillo).size());
  for (int resolution : {128, 256}) {
    expectIdentical(
        makeScene(modifier(NodeKind::Offset, 0.02 * armadilloSize, {meshLeaf(armadillo)}),
                  resolution),
        cuda_, "armadillo grown by 2%");
    expectIdentical(
        makeScene(modifier(NodeKind::Offset, -0.01 * armadilloSize, {meshLeaf(armadillo)}),
                  resolution),
        cuda_, "armadillo shrunk by 1%");
    expectIdentical(makeScene(op(NodeKind::Difference,
                                 {modifier(NodeKind::Shell, 0.02 * bunnySize, {meshLeaf(bunny)}),
                                  box(meshBounds(*bunny).size() * glm::dvec3(1.0, 0.4, 1.0),
                                      meshBounds(*bunny).center() +
                                          glm::dvec3(0.0, 0.5, 0.0) * meshBounds(*bunny).size())}),
                              resolution),
                    cuda_, "bunny shelled and cut open");
  }
  // A cube with a spherical bite out of one corner, rounded: convex and concave edges.
  Scene rounded =
      makeScene(modifier(NodeKind::Round, 0.2,
                         {op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2, {1, 1, 1})})}),
                96);
  expectSameExport(rounded, cuda_, 64);
}

// The editor's preview grid follows the scene on one lattice: on the device, a part moved out
// past the scene's bounds keeps the others' LDIs, moved onto the grown window
// (Backend::rewindow), and the result is the CPU's fresh evaluation on that window, bit for bit.
TEST_F(CudaVsCpu, LdisMovedOntoAGrownWindowMatchAFreshEvaluation) {
  auto plate = std::make_shared<Node>(*modifier(NodeKind::Round, 0.15, {box({2, 2, 0.6})}));
  const NodePtr drilled = op(NodeKind::Difference, {plate, cylinder(0.3, 0.5, {0.4, -0.4, 0})});
  auto ball = std::make_shared<Node>(*sphere(0.4, {1.6, 0, 0}));  // moved in place below
  Scene scene = makeScene(op(NodeKind::Union, {drilled, sphere(0.5, {-1, 1.2, 0}), ball}), 128);
  Progress progress;
  Evaluator onGpu(cuda_);
  Grid grid = Evaluator::previewGridFor(scene, 128, nullptr);
  onGpu.evaluateOn(scene, grid, progress);
  for (const double x : {1.9, -1.8}) {
    ball->transform.translate = {x, 0, 0};
    const Grid next = Evaluator::previewGridFor(scene, 128, &grid);
    ASSERT_FALSE(next == grid);
    ASSERT_EQ(next.h, grid.h);
    grid = next;
    const EvalResult b = onGpu.evaluateOn(scene, grid, progress);
    EXPECT_EQ(b.computed, 2) << "x " << x << ": the ball and the root";
    Evaluator onCpu(std::make_shared<CpuBackend>());
    const EvalResult a = onCpu.evaluateOn(scene, grid, progress);
    auto p = wholeLdi(onCpu.backend().download(a.root));
    auto q = onGpu.backend().download(b.root);
    for (int axis = 0; axis < 3; ++axis) {
      ASSERT_EQ(p->axes[axis].offsets, q->axes[axis].offsets) << "x " << x << " axis " << axis;
      ASSERT_EQ(p->axes[axis].surfels.size(), q->axes[axis].surfels.size());
      EXPECT_EQ(std::memcmp(p->axes[axis].surfels.data(), q->axes[axis].surfels.data(),
                            p->axes[axis].surfels.size() * sizeof(Surfel)),
                0)
          << "x " << x << " axis " << axis;
    }
  }
}

// Tiles of a modifier scene are evaluated on a window grown by the modifiers' reach and cropped
// back (Backend::crop): the device's crop gives the CPU's bits, and a tiled export of the
// rebuilt scaffold gives the CPU's mesh and that of one tile, vertex for vertex.
TEST_F(CudaVsCpu, CroppedTilesOfModifierScenesMatch) {
  Scene s = loadScene(assetsDir() + "/scenes/bone_scaffold.strata.json");
  Progress progress;
  Evaluator onCpu(std::make_shared<CpuBackend>()), onGpu(cuda_);
  const Grid grid = Evaluator::gridFor(s, 96);
  const EvalResult a = onCpu.evaluateOn(s, grid, progress);
  const EvalResult b = onGpu.evaluateOn(s, grid, progress);
  const Grid window = grid.window(glm::ivec3(5, 7, 11), grid.cells / 2);
  auto x = onCpu.backend().download(onCpu.backend().crop(a.root, window, progress));
  auto y = onGpu.backend().download(onGpu.backend().crop(b.root, window, progress));
  ASSERT_TRUE(x->grid == window);
  ASSERT_TRUE(y->grid == window);
  size_t surfels = 0;
  for (int axis = 0; axis < 3; ++axis) {
    ASSERT_EQ(x->axes[axis].offsets, y->axes[axis].offsets) << "axis " << axis;
    ASSERT_EQ(x->axes[axis].surfels.size(), y->axes[axis].surfels.size()) << "axis " << axis;
    surfels += x->axes[axis].surfels.size();
    EXPECT_EQ(std::memcmp(x->axes[axis].surfels.data(), y->axes[axis].surfels.data(),
                          x->axes[axis].surfels.size() * sizeof(Surfel)),
              0)
        << "axis " << axis;
  }
  EXPECT_GT(surfels, 1000u);
  s.settings.resolution = 160;
  expectSameExport(s, cuda_, 40);
  Evaluator one(std::make_shared<CpuBackend>());
  const ExportMesh whole = contourScene(s, one, ContourOptions{0, 0}, progress);
  ContourReport r;
  const ExportMesh tiled = contourScene(s, onGpu, ContourOptions{0, 40}, progress, &r);
  EXPECT_GT(r.tiles, 4);
  EXPECT_TRUE(whole.mesh.positions == tiled.mesh.positions);
  EXPECT_TRUE(whole.mesh.triangles == tiled.mesh.triangles);
}

// The editor's ghost of a cutter that sticks out of its part is evaluated alone on a window of
// its own (ghostWindow): the device draws the CPU's splats, bit for bit, beyond the result's grid.
TEST_F(CudaVsCpu, AGhostBeyondTheResultsGridMatchesTheCpu) {
  NodePtr pin = cylinder(0.3, 6.0, {0.4, 0.4, 0.0});
  NodePtr rod = cylinder(0.2, 7.0, {0.0, -0.5, 0.0}, {0.0, 90.0, 0.0});
  auto scene = std::make_shared<const Scene>(
      makeScene(op(NodeKind::Difference, {box({4, 4, 0.5}), pin, rod}), 128));
  std::vector<std::shared_ptr<const PreviewResult>> results;
  for (std::shared_ptr<Backend> backend :
       {std::shared_ptr<Backend>(std::make_shared<CpuBackend>()), cuda_}) {
    PreviewWorker worker(backend, 32);
    worker.request(scene, 128, false, 1, {pin->id, rod->id});
    ASSERT_TRUE(worker.waitUntilIdle(std::chrono::seconds(120)));
    results.push_back(worker.takeResult());
    ASSERT_TRUE(results.back() && results.back()->ok()) << results.back()->error;
    ASSERT_EQ(results.back()->resolution, 128);
  }
  const Bounds window = results[0]->stats.grid.bounds();
  ASSERT_EQ(results[0]->ghosts.size(), 2u);
  ASSERT_EQ(results[1]->ghosts.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const HostSplats& a = *results[0]->ghosts[k].splats;
    const HostSplats& b = *results[1]->ghosts[k].splats;
    EXPECT_EQ(results[0]->ghosts[k].id, results[1]->ghosts[k].id);
    ASSERT_EQ(a.count(), b.count()) << "ghost " << k;
    EXPECT_EQ(std::memcmp(a.hostData(), b.hostData(), a.bytes()), 0) << "ghost " << k;
    const Bounds drawn = splatBounds(a);
    EXPECT_TRUE(drawn.min.x < window.min.x - 1.0 || drawn.max.z > window.max.z + 1.0)
        << "ghost " << k << " reaches beyond the result's grid";
  }
}

TEST_F(CudaVsCpu, AutoChoosesCudaAndCancelWorks) {
  Evaluator evaluator(cuda_);
  Progress progress;
  progress.cancel();
  EXPECT_THROW(evaluator.evaluate(makeScene(sphere(1), 64), {}, progress), Cancelled);
  EXPECT_NE(cuda_->description().find("cuda"), std::string::npos);
}

}  // namespace
}  // namespace strata::test
