// exportSceneStreamed: the export written in pieces gives the single-process export's file byte
// for byte, component steps (unfolded shells, dropped specks) and flat-triangle repairs included.
#include "engine/export/streamed_export.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/export/check_streamed.h"
#include "engine/export/job_estimate.h"
#include "engine/export/unfold_shells.h"
#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"
#include "tests/support/export_cases.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

std::string freshFolder(const std::string& name) {
  const fs::path folder = fs::path(testing::TempDir()) / ("strata_streamed_export_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t entriesIn(const std::string& folder) {
  return size_t(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

// The sliver on its regression's grid (8 cells), that grid lengthened along z by 16 cells of
// the same size: three slabs of 8 cells.
Scene foldedSliverScene() {
  Scene scene = makeScene(foldedSliver(), 8);
  const Grid g = Evaluator::gridFor(scene, 0);
  scene.settings.hasBounds = true;
  scene.settings.bounds.min = g.origin;
  scene.settings.bounds.max = g.origin + g.h * glm::dvec3(g.cells.x, g.cells.y, g.cells.z + 16);
  scene.settings.resolution = g.cells.z + 16;
  return scene;
}

struct Case {
  std::string name;
  Scene scene;
  int tile;  // the streamed export's: slabs of tiles this many cells deep
};

std::vector<Case> cases() {
  Transform turned;
  turned.rotateDegrees = glm::dvec3(0.0, 0.0, 45.0);
  return {
      {"box_minus_ball", makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2)}), 40), 8},
      {"disjoint_spheres",
       makeScene(op(NodeKind::Union, {sphere(0.5, {-1, 0, 0}), sphere(0.5, {1, 0, 0.8})}), 48), 16},
      {"grazing_torus",
       makeScene(
           op(NodeKind::Difference, {sphere(0.42), meshLeaf(facetedTorus(0.33, 0.12, 96, 48))}),
           64),
       8},
      {"folded_sliver", foldedSliverScene(), 8},
      // Far from the origin, where float32 holds a few steps per cell: flat and collapsed
      // triangles as stored, repaired.
      {"far_sphere", makeScene(sphere(0.05, {1e4, 1e4, 1e4}), 48), 16},
      {"turned_box",
       makeScene(
           op(NodeKind::Union, {withTransform(box({1, 1, 1}), turned), sphere(0.3, {0, 0, 1})}),
           37),
       8},
  };
}

// `node` with each leaf a colour of its own (a PLY colours each vertex by the leaf of the first
// triangle that uses it).
NodePtr colourLeaves(const NodePtr& node, int* next) {
  auto copy = std::make_shared<Node>(*node);
  if (copy->children.empty()) {
    const int k = (*next)++;
    copy->color =
        glm::vec3(0.2f + 0.3f * float(k % 3), 0.9f - 0.2f * float(k % 4), 0.1f * float(k));
  }
  for (NodePtr& c : copy->children) c = colourLeaves(c, next);
  return copy;
}

// The single-process export and the streamed one, with its slabs a few cells deep: the same
// bytes, the same component steps and repairs, the same verdict; as binary STL and as PLY (its
// vertices listed before the faces, welded by their global keys, coloured by leaf).
TEST(StreamedExport, WritesTheSingleProcessFileByteForByte) {
  const std::string folder = freshFolder("identical");
  for (const std::string extension : {"stl", "ply"}) {
    SCOPED_TRACE(extension);
    int unfolded = 0, dropped = 0;
    size_t repaired = 0, coloured = 0;
    for (Case& c : cases()) {
      SCOPED_TRACE(c.name);
      int leaves = 0;
      c.scene.root = colourLeaves(c.scene.root, &leaves);
      coloured += size_t(leaves);
      const std::string whole = folder + "/" + c.name + "_whole." + extension;
      const std::string streamed = folder + "/" + c.name + "_streamed." + extension;
      Progress progress;
      const ExportReport a =
          exportScene(c.scene, whole, ExportOptions(), std::make_shared<CpuBackend>(), progress);
      ExportOptions pieces;
      pieces.tileCells = c.tile;
      const ExportReport b =
          exportSceneStreamed(c.scene, streamed, pieces, std::make_shared<CpuBackend>(), progress);
      EXPECT_GT(b.contour.grid.cells.z / c.tile, 1);  // several slabs
      EXPECT_TRUE(bytesOf(whole) == bytesOf(streamed)) << "the files differ";
      EXPECT_EQ(a.contour.unfoldedShells, b.contour.unfoldedShells);
      EXPECT_EQ(a.contour.droppedSpecks.components, b.contour.droppedSpecks.components);
      EXPECT_EQ(a.contour.droppedSpecks.triangles, b.contour.droppedSpecks.triangles);
      EXPECT_EQ(a.degenerateRepair.flipped, b.degenerateRepair.flipped);
      EXPECT_EQ(a.degenerateRepair.rotated, b.degenerateRepair.rotated);
      EXPECT_EQ(a.degenerateRepair.collapsed, b.degenerateRepair.collapsed);
      EXPECT_EQ(a.degenerateRepair.left, b.degenerateRepair.left);
      EXPECT_TRUE(b.fileDifference.empty()) << b.fileDifference;
      EXPECT_EQ(a.passed(), b.passed());
      // The streamed check measures what checkMesh measures, the same numbers (but the vertex
      // count of an STL: checkMesh counts the mesh's vertices, the streamed check the file's
      // positions; of a PLY both count the file's vertices).
      EXPECT_EQ(a.check.triangles, b.check.triangles);
      EXPECT_EQ(a.check.boundaryEdges, b.check.boundaryEdges);
      EXPECT_EQ(a.check.nonManifoldEdges, b.check.nonManifoldEdges);
      EXPECT_EQ(a.check.misorientedEdges, b.check.misorientedEdges);
      EXPECT_EQ(a.check.degenerateTriangles, b.check.degenerateTriangles);
      EXPECT_EQ(a.check.components, b.check.components);
      EXPECT_EQ(a.check.genus, b.check.genus);
      EXPECT_EQ(a.check.volume, b.check.volume);
      EXPECT_EQ(a.check.area, b.check.area);
      EXPECT_EQ(a.check.smallestTriangleArea, b.check.smallestTriangleArea);
      const MeshCheck file = checkMesh(readMeshFileRaw(streamed));
      EXPECT_EQ(file.vertices, b.check.vertices);
      if (extension == "ply") {
        EXPECT_EQ(a.check.vertices, b.check.vertices);
      }
      unfolded += b.contour.unfoldedShells;
      dropped += b.contour.droppedSpecks.components;
      repaired +=
          b.degenerateRepair.flipped + b.degenerateRepair.rotated + b.degenerateRepair.collapsed;
    }
    // The list exercises both component steps, the repair (of the float32 STL stores: a PLY's
    // doubles flatten nothing), leaves of several colours.
    EXPECT_GT(unfolded, 0);
    EXPECT_GT(dropped, 0);
    if (extension == "stl") {
      EXPECT_GT(repaired, 0u);
    }
    EXPECT_GT(coloured, cases().size());
  }
  EXPECT_EQ(entriesIn(folder), 4 * cases().size());  // no scratch file left behind
}

// A box less a sphere and a ring, its eight slabs.
Scene slabbedScene() {
  return makeScene(
      op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2), torus(0.9, 0.15, {0, 0, 0.7})}), 160);
}

std::vector<std::shared_ptr<Backend>> cpuBackends(int n) {
  std::vector<std::shared_ptr<Backend>> b;
  for (int i = 0; i < n; ++i) b.push_back(std::make_shared<CpuBackend>());
  return b;
}

// On several workers (--gpus), the slabs' tiles contoured ahead of the merge in whatever order
// the workers finish them: the same file as on one backend; in cubes of a few cells (many tiles
// a slab) and in slabs of the grid's whole cross-section (a tile a slab).
TEST(StreamedExport, OnSeveralWorkersWritesTheFileOfOne) {
  const std::string folder = freshFolder("workers");
  std::vector<Case> all = cases();
  all.push_back({"slabbed", slabbedScene(), 0});  // slabs of the whole cross-section
  for (const Case& c : all) {
    SCOPED_TRACE(c.name);
    ExportOptions pieces;
    pieces.tileCells = c.tile;
    const std::string one = folder + "/one.stl", three = folder + "/three.stl";
    Progress progress;
    const ExportReport a = exportSceneStreamed(c.scene, one, pieces, cpuBackends(1), 1, progress);
    const ExportReport b = exportSceneStreamed(c.scene, three, pieces, cpuBackends(3), 3, progress);
    EXPECT_GE(b.contour.grid.cells.z / b.contour.tileCells, 2);  // several slabs (most: > 3)
    EXPECT_EQ(a.contour.tiles, b.contour.tiles);
    EXPECT_EQ(a.contour.surfels, b.contour.surfels);
    EXPECT_TRUE(b.passed());
    EXPECT_EQ(a.check.triangles, b.check.triangles);
    EXPECT_EQ(bytesOf(one), bytesOf(three));
  }
  EXPECT_EQ(entriesIn(folder), 2u);
}

// The passes over the pieces run on several threads, in blocks of a few thousand triangles of a
// piece: on one, two and three threads the single-process file, byte for byte, where the pieces
// hold many blocks, the shells' sums span several of their chunks (65,536 triangles) cut off the
// pieces' boundaries, and specks are dropped, shells unfolded and flat triangles repaired.
TEST(StreamedExport, OnAnyThreadCountWritesTheSingleProcessFile) {
  const std::string folder = freshFolder("threads");
  std::vector<Case> all = {
      {"slabbed", slabbedScene(), 0},
      {"far_sphere", makeScene(sphere(0.05, {1e4, 1e4, 1e4}), 128), 0},
      {"folded_sliver", foldedSliverScene(), 8},
      {"grazing_torus",
       makeScene(
           op(NodeKind::Difference, {sphere(0.42), meshLeaf(facetedTorus(0.33, 0.12, 96, 48))}),
           128),
       0},
  };
  size_t repaired = 0;
  int unfolded = 0, dropped = 0;
  for (const std::string extension : {"stl", "ply"})
    for (const Case& c : all) {
      SCOPED_TRACE(c.name + "." + extension);
      const std::string whole = folder + "/whole." + extension,
                        streamed = folder + "/streamed." + extension;
      Progress progress;
      const ExportReport a =
          exportScene(c.scene, whole, ExportOptions(), std::make_shared<CpuBackend>(), progress);
      const std::string expected = bytesOf(whole);
      ExportOptions pieces;
      pieces.tileCells = c.tile;
      int tiles = 0;
      for (int threads : {1, 2, 3}) {
        SCOPED_TRACE("threads " + std::to_string(threads));
        setWorkerCount(threads);
        const ExportReport b = exportSceneStreamed(c.scene, streamed, pieces,
                                                   std::make_shared<CpuBackend>(), progress);
        setWorkerCount(0);
        tiles = b.contour.tiles;
        EXPECT_TRUE(bytesOf(streamed) == expected) << "the files differ";
        EXPECT_TRUE(b.fileDifference.empty()) << b.fileDifference;
        EXPECT_EQ(a.check.triangles, b.check.triangles);
        EXPECT_EQ(a.check.volume, b.check.volume);
        EXPECT_EQ(a.contour.unfoldedShells, b.contour.unfoldedShells);
        EXPECT_EQ(a.contour.droppedSpecks.triangles, b.contour.droppedSpecks.triangles);
        EXPECT_EQ(a.degenerateRepair.collapsed, b.degenerateRepair.collapsed);
        EXPECT_EQ(a.degenerateRepair.flipped, b.degenerateRepair.flipped);
        if (threads == 1) {
          unfolded += b.contour.unfoldedShells;
          dropped += b.contour.droppedSpecks.components;
          repaired += b.degenerateRepair.flipped + b.degenerateRepair.rotated +
                      b.degenerateRepair.collapsed;
        }
      }
      if (c.name == "slabbed") {
        // Several pieces (a tile each: slabs of the whole cross-section) of many blocks, the mesh
        // of more than three chunks.
        EXPECT_GE(tiles, 8);
        EXPECT_GT(a.check.triangles, size_t(3 * ShellRunSums::kChunk));
        EXPECT_GT(a.check.triangles / size_t(tiles), size_t(3 * 4096));
      }
    }
  EXPECT_GT(unfolded, 0);
  EXPECT_GT(dropped, 0);
  EXPECT_GT(repaired, 0u);
  EXPECT_EQ(entriesIn(folder), 4u);
}

// A CPU backend that runs out of memory on every window: its worker's tiles go on on the CPU
// (the same bits), the one that failed included.
class OutOfMemoryBackend : public CpuBackend {
 public:
  std::string description() const override { return "out-of-memory test backend"; }
  LdiHandle sampleMesh(const TriangleMesh&, const glm::dmat4&, const Grid&, uint32_t,
                       Progress&) override {
    throw BackendOutOfMemory("pretend: out of device memory");
  }
};

TEST(StreamedExport, AWorkerOutOfMemoryGoesOnOnTheCpu) {
  const std::string folder = freshFolder("worker_memory");
  const Case c = cases()[0];
  ExportOptions pieces;
  pieces.tileCells = c.tile;
  Progress progress;
  exportSceneStreamed(c.scene, folder + "/one.stl", pieces, cpuBackends(1), 1, progress);
  std::vector<std::shared_ptr<Backend>> backends{std::make_shared<OutOfMemoryBackend>()};
  for (const auto& b : cpuBackends(2)) backends.push_back(b);
  std::vector<std::string> notices;
  const ExportReport r =
      exportSceneStreamed(c.scene, folder + "/three.stl", pieces, backends, 3, progress,
                          [&](const std::string& line) { notices.push_back(line); });
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(bytesOf(folder + "/one.stl"), bytesOf(folder + "/three.stl"));
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_NE(notices[0].find("its tiles go on on the CPU"), std::string::npos) << notices[0];
  EXPECT_EQ(r.notices, notices);
}

// How far the workers run ahead: one slab a worker, at most an eighth of the slabs (one at
// least); the estimate's peak grows with them.
TEST(StreamedExport, WorkersRunAheadByNoMoreThanAnEighthOfTheSlabs) {
  EXPECT_EQ(streamedSlabsAhead(1, 8), 1);
  EXPECT_EQ(streamedSlabsAhead(8, 8), 1);
  EXPECT_EQ(streamedSlabsAhead(2, 45), 2);
  EXPECT_EQ(streamedSlabsAhead(16, 45), 5);
  EXPECT_EQ(streamedSlabsAhead(64, 121), 15);
  JobEstimate e;
  e.streamedPeakBytes = 1000;
  e.streamedSlabs = 45;
  e.streamedWorkerBytes = 10;
  e.streamedSlabTileBytes = 100;
  EXPECT_EQ(streamedPeakOnWorkers(e, 1), 1000u);
  EXPECT_EQ(streamedPeakOnWorkers(e, 2), 1000u + 10u + 100u);
  EXPECT_EQ(streamedPeakOnWorkers(e, 16), 1000u + 15u * 10u + 4u * 100u);
}

// A CPU backend whose sampling fails (not for memory) from its `failAt`-th call on.
class FailingBackend : public CpuBackend {
 public:
  explicit FailingBackend(int failAt) : failAt_(failAt) {}
  std::string description() const override { return "failing test backend"; }
  LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                       uint32_t leafId, Progress& progress) override {
    if (++calls_ >= failAt_) throw Error("pretend: the device was lost");
    return CpuBackend::sampleMesh(mesh, objectToWorld, grid, leafId, progress);
  }

 private:
  const int failAt_;
  std::atomic<int> calls_{0};
};

// A worker that fails, or a cancel while the workers contour and the writer merges: every
// worker stops, the failure (or Cancelled) comes out, and nothing is left in the folder.
TEST(StreamedExport, AFailedWorkerOrACancelStopsTheWholeExport) {
  const std::string folder = freshFolder("worker_failure");
  ExportOptions pieces;
  pieces.tileCells = 8;
  const Scene scene = cases()[0].scene;
  {
    std::vector<std::shared_ptr<Backend>> backends = cpuBackends(2);
    backends.push_back(std::make_shared<FailingBackend>(1));
    Progress progress;
    try {
      exportSceneStreamed(scene, folder + "/part.stl", pieces, backends, 3, progress);
      ADD_FAILURE() << "no failure came out";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("the device was lost"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(entriesIn(folder), 0u);
  {
    // Half the tiles done: the first slabs handed to the writer, the workers on the next.
    Progress progress([&](const std::string& stage, double f) {
      if (stage == "export" && f > 0.5) progress.cancel();
    });
    EXPECT_THROW(
        exportSceneStreamed(scene, folder + "/part.stl", pieces, cpuBackends(3), 3, progress),
        Cancelled);
  }
  EXPECT_EQ(entriesIn(folder), 0u);
}

// The streamed check of the facets of `verbatim` fed in blocks of 10,000, in chunks of
// `chunkFacets` on `threads` threads.
MeshCheck streamedCheckOf(const TriangleMesh& verbatim, const Grid& grid, size_t chunkFacets,
                          int threads) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const auto& t : verbatim.triangles)
    for (uint32_t v : t) {
      lo = glm::min(lo, verbatim.positions[v]);
      hi = glm::max(hi, verbatim.positions[v]);
    }
  Progress progress;
  StreamedMeshCheck check(grid, verbatim.triangles.size(), lo, hi, progress, chunkFacets, threads);
  std::vector<glm::vec3> block;
  for (size_t t = 0; t < verbatim.triangles.size(); ++t) {
    for (uint32_t v : verbatim.triangles[t]) block.push_back(glm::vec3(verbatim.positions[v]));
    if (block.size() == 3 * 10000) {
      check.add(block);
      block.clear();
    }
  }
  check.add(block);
  return check.finish();
}

// The streamed check on files that are not what they should be: it counts what checkMesh counts
// on the file read back whole, whatever its chunks and threads.
void expectTheCheckOfTheFile(const std::string& path, const Grid& grid) {
  const TriangleMesh verbatim = readMeshFileVerbatim(path);
  ASSERT_GT(verbatim.triangles.size(), 3 * kMeasureBlock);  // chunks of one block: at least 4
  const MeshCheck whole = checkMesh(readMeshFileRaw(path));
  const std::pair<size_t, int> runs[] = {{kMeasureBlock, 1}, {2 * kMeasureBlock, 3}, {0, 0}};
  for (const auto& [chunk, threads] : runs) {
    SCOPED_TRACE("chunks of " + std::to_string(chunk) + " facets on " + std::to_string(threads) +
                 " threads");
    const MeshCheck streamed = streamedCheckOf(verbatim, grid, chunk, threads);
    EXPECT_EQ(whole.vertices, streamed.vertices);
    EXPECT_EQ(whole.triangles, streamed.triangles);
    EXPECT_EQ(whole.boundaryEdges, streamed.boundaryEdges);
    EXPECT_EQ(whole.nonManifoldEdges, streamed.nonManifoldEdges);
    EXPECT_EQ(whole.misorientedEdges, streamed.misorientedEdges);
    EXPECT_EQ(whole.degenerateTriangles, streamed.degenerateTriangles);
    EXPECT_EQ(whole.components, streamed.components);
    EXPECT_EQ(whole.genus, streamed.genus);
    EXPECT_EQ(whole.volume, streamed.volume);
    EXPECT_EQ(whole.area, streamed.area);
    EXPECT_EQ(whole.smallestTriangleArea, streamed.smallestTriangleArea);
  }
}

// Rewrites an STL with facet `facet` changed by `change` (or left out when it returns false).
void rewriteStl(const std::string& from, const std::string& to, size_t facet,
                const std::function<bool(std::string&)>& change) {
  const std::string bytes = bytesOf(from);
  std::string out = bytes.substr(0, 84);
  uint32_t count = 0;
  for (size_t f = 0; 84 + 50 * f < bytes.size(); ++f) {
    std::string record = bytes.substr(84 + 50 * f, 50);
    if (f == facet && !change(record)) continue;
    out += record;
    ++count;
  }
  std::memcpy(&out[80], &count, 4);
  std::ofstream(to, std::ios::binary) << out;
}

// Without --tile: slabs of the whole x and y extent, eight of them here, the same bytes.
TEST(StreamedExport, SlabsOfTheWholeCrossSectionGiveTheSameFile) {
  const std::string folder = freshFolder("slabs");
  const Scene scene = slabbedScene();
  const auto backend = std::make_shared<CpuBackend>();
  const ExportTiling slabs = streamedTiling(scene, ExportOptions(), backend->memoryAvailable(),
                                            backend->offsetBytesPerNode());
  EXPECT_EQ(slabs.size.x, slabs.grid.cells.x);
  EXPECT_EQ(slabs.size.y, slabs.grid.cells.y);
  EXPECT_EQ(slabs.counts, glm::ivec3(1, 1, kStreamedSlabs));
  Progress progress;
  const ExportReport a =
      exportScene(scene, folder + "/whole.stl", ExportOptions(), backend, progress);
  const ExportReport b =
      exportSceneStreamed(scene, folder + "/streamed.stl", ExportOptions(), backend, progress);
  EXPECT_EQ(b.contour.tiles, kStreamedSlabs);
  EXPECT_TRUE(b.passed());
  EXPECT_EQ(a.check.genus, b.check.genus);
  EXPECT_EQ(bytesOf(folder + "/whole.stl"), bytesOf(folder + "/streamed.stl"));
}

// Where a modifier's halo would grow thin slabs' windows severalfold along z, the streamed
// export takes cubes in at least kStreamedSlabs layers when they evaluate fewer nodes (the
// rebuilt bone scaffold at 4096 cells on the H200: 121 slabs, evaluate 20.7 s; 128 cubes,
// 6.4 s); without a halo, slabs. Figures only: the cubes' file is --tile's, tested above.
TEST(StreamedExport, AHaloThatWouldSwellThinSlabsGivesCubesInLayers) {
  const NodePtr block = box({1.8, 1.6, 4});  // the scaffold's proportions
  const Scene thick = makeScene(modifier(NodeKind::Offset, 0.03, {block}), 4096);
  const Scene plain = makeScene(block, 4096);
  const CpuBackend cpu;
  const uint64_t memory = uint64_t(40) << 30;
  const ExportTiling chosen =
      streamedTiling(thick, ExportOptions(), memory, cpu.offsetBytesPerNode());
  ASSERT_GT(chosen.halo, 16);
  const glm::ivec3 cells = chosen.grid.cells;
  EXPECT_LT(chosen.size.x, cells.x);  // cubes, not slabs of the whole cross-section
  EXPECT_EQ(chosen.size.x, chosen.size.z);
  EXPECT_GE(chosen.counts.z, kStreamedSlabs);
  // The slabs the memory allows (windows no larger than the export's cubes'): thin, and they
  // would have evaluated more.
  const ExportTiling cubes = exportTiling(thick, ExportOptions(), memory, cpu.offsetBytesPerNode());
  const double cube = std::pow(double(cubes.tileCells + 2 * cubes.halo + 3), 3.0);
  const int depth = int(cube / (double(cells.x + 3) * double(cells.y + 3))) - 2 * cubes.halo - 3;
  ASSERT_GE(depth, kMinStreamedTile);
  ASSERT_LT(depth, 2 * chosen.halo);  // windows of about three slabs' depth
  const ExportTiling slabs = exportTilingOfSize(thick, ExportOptions(), {cells.x, cells.y, depth});
  EXPECT_LT(chosen.evaluatedNodes(), 0.6 * slabs.evaluatedNodes());  // 0.48 when written
  // Without a halo, slabs of the whole cross-section at any memory that allows them, though
  // cubes of a few hundred cells (a node of overlap a side) may evaluate a little less than
  // slabs a hundred cells deep: the slabs hold less of the mesh.
  for (const int gib : {4, 8, 16, 40, 64, 128}) {
    SCOPED_TRACE(std::to_string(gib) + " GiB");
    const ExportTiling plainChosen =
        streamedTiling(plain, ExportOptions(), uint64_t(gib) << 30, cpu.offsetBytesPerNode());
    EXPECT_EQ(plainChosen.size.x, plainChosen.grid.cells.x);
    EXPECT_EQ(plainChosen.size.y, plainChosen.grid.cells.y);
    EXPECT_GE(plainChosen.counts.z, kStreamedSlabs);
  }
}

// A grid fewer than 8 cells across (a thin plate): its slabs reach past the grid there, and the
// estimate of any export of it (which reckons the streamed one too) still stands.
TEST(StreamedExport, AGridThinnerThanATileIsStillSlabbed) {
  const std::string folder = freshFolder("thin");
  const Scene plate =
      makeSceneInBox(box({0.01, 2, 2}), 240, {-0.02, -1.05, -1.05}, {0.02, 1.05, 1.05});
  ASSERT_LT(Evaluator::gridFor(plate, 0).cells.x, 8);
  const auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  JobEstimate estimate;
  EXPECT_NO_THROW(estimate = estimateExport(plate, ContourOptions{1024, 0}, folder + "/x.stl",
                                            backend, progress));
  EXPECT_GT(estimate.streamedPeakBytes, 0u);
  const ExportReport a =
      exportScene(plate, folder + "/whole.stl", ExportOptions(), backend, progress);
  const ExportReport b =
      exportSceneStreamed(plate, folder + "/streamed.stl", ExportOptions(), backend, progress);
  EXPECT_GT(b.contour.tiles, 1);
  EXPECT_TRUE(b.passed());
  EXPECT_EQ(bytesOf(folder + "/whole.stl"), bytesOf(folder + "/streamed.stl"));
}

// slabbedScene exported in pieces to `path` on the CPU.
ExportReport exportSlabbedScene(const std::string& path) {
  Progress progress;
  return exportSceneStreamed(slabbedScene(), path, ExportOptions(), std::make_shared<CpuBackend>(),
                             progress);
}

TEST(StreamedExport, TheStreamedCheckCountsWhatTheWholeCheckCounts) {
  const std::string folder = freshFolder("check");
  const std::string good = folder + "/good.stl";
  const ExportReport r = exportSlabbedScene(good);
  ASSERT_TRUE(r.passed());
  {
    SCOPED_TRACE("as written");
    expectTheCheckOfTheFile(good, r.contour.grid);
  }
  // In the middle, and at the first facet of a chunk and the last of the one before.
  for (const size_t facet : {r.check.triangles / 2, kMeasureBlock, 2 * kMeasureBlock - 1}) {
    SCOPED_TRACE("facet " + std::to_string(facet));
    {
      SCOPED_TRACE("left out: a hole");
      rewriteStl(good, folder + "/hole.stl", facet, [](std::string&) { return false; });
      expectTheCheckOfTheFile(folder + "/hole.stl", r.contour.grid);
    }
    {
      SCOPED_TRACE("turned over");
      rewriteStl(good, folder + "/turned.stl", facet, [](std::string& record) {
        std::string b = record.substr(24, 12);  // corners 2 and 3 swapped
        record.replace(24, 12, record.substr(36, 12));
        record.replace(36, 12, b);
        return true;
      });
      expectTheCheckOfTheFile(folder + "/turned.stl", r.contour.grid);
    }
    {
      SCOPED_TRACE("twice");
      std::string twice;
      rewriteStl(good, folder + "/twice.stl", facet, [&](std::string& record) {
        twice = record;
        return true;
      });
      const std::string bytes = bytesOf(folder + "/twice.stl");
      std::string out =
          bytes.substr(0, 84 + 50 * (facet + 1)) + twice + bytes.substr(84 + 50 * (facet + 1));
      const uint32_t count = uint32_t(r.check.triangles + 1);
      std::memcpy(&out[80], &count, 4);
      std::ofstream(folder + "/twice.stl", std::ios::binary) << out;
      expectTheCheckOfTheFile(folder + "/twice.stl", r.contour.grid);
    }
  }
}

// The file read back beside the measures' last chunks (compareStreamedFile): a file that says
// what was measured passes with the measures' numbers; one whose bytes changed after its facets
// were measured is caught by its fingerprint and checked whole as read back; a cancel stops both.
TEST(StreamedExport, TheReadBackCatchesAFileThatIsNotWhatWasMeasured) {
  const std::string folder = freshFolder("read_back");
  const std::string good = folder + "/good.stl";
  const ExportReport r = exportSlabbedScene(good);
  ASSERT_TRUE(r.passed());
  const TriangleMesh verbatim = readMeshFileVerbatim(good);
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  TriangleFingerprint meant;
  for (const auto& t : verbatim.triangles) {
    addToFingerprint(verbatim.positions[t[0]], verbatim.positions[t[1]], verbatim.positions[t[2]],
                     &meant);
    for (uint32_t v : t) {
      lo = glm::min(lo, verbatim.positions[v]);
      hi = glm::max(hi, verbatim.positions[v]);
    }
  }
  // `path` checked as the file whose facets are verbatim's, with `progress` (cancelled once the
  // facets are in where `cancel`).
  const auto compare = [&](const std::string& path, Progress& progress, bool cancel = false) {
    StreamedMeshCheck measures(r.contour.grid, verbatim.triangles.size(), lo, hi, progress,
                               kMeasureBlock, 2);
    std::vector<glm::vec3> corners;
    for (const auto& t : verbatim.triangles)
      for (uint32_t v : t) corners.push_back(glm::vec3(verbatim.positions[v]));
    measures.add(std::move(corners));
    if (cancel) progress.cancel();
    return compareStreamedFile(path, measures, meant, progress);
  };
  Progress progress;
  const WrittenCheck same = compare(good, progress);
  EXPECT_EQ(same.fileDifference, "");
  EXPECT_TRUE(same.check.watertight());
  EXPECT_EQ(same.check.triangles, verbatim.triangles.size());
  // One corner of a facet in the middle moved along x by its float's last bit.
  rewriteStl(good, folder + "/moved.stl", verbatim.triangles.size() / 2, [](std::string& record) {
    float x;
    std::memcpy(&x, &record[12], 4);
    x = std::nextafter(x, std::numeric_limits<float>::infinity());
    std::memcpy(&record[12], &x, 4);
    return true;
  });
  const WrittenCheck moved = compare(folder + "/moved.stl", progress);
  EXPECT_NE(moved.fileDifference.find("moved.stl"), std::string::npos) << moved.fileDifference;
  EXPECT_FALSE(moved.check.watertight()) << "a corner apart from its neighbours' is a hole";
  const MeshCheck whole = checkMesh(readMeshFileRaw(folder + "/moved.stl"));
  EXPECT_EQ(moved.check.boundaryEdges, whole.boundaryEdges);
  Progress cancelled;
  EXPECT_THROW(compare(good, cancelled, true), Cancelled);
}

// Chunks a few layers thick (a grid of three z layers over the whole part, its facets in a
// shuffled order, which is then still "in layer order"): every vertex is open at both ends of
// every chunk but the first's start, and the joining window counts them all.
TEST(StreamedExport, TheCheckOfChunksAFewLayersThickCountsWhatTheWholeCheckCounts) {
  const std::string folder = freshFolder("thin_chunks");
  const std::string good = folder + "/good.stl";
  const ExportReport r = exportSlabbedScene(good);
  ASSERT_TRUE(r.passed());
  const std::string bytes = bytesOf(good);
  std::vector<size_t> order(r.check.triangles);
  std::iota(order.begin(), order.end(), size_t(0));
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  std::string shuffled = bytes.substr(0, 84);
  for (size_t f : order) shuffled += bytes.substr(84 + 50 * f, 50);
  const std::string path = folder + "/shuffled.stl";
  std::ofstream(path, std::ios::binary) << shuffled;
  const TriangleMesh verbatim = readMeshFileVerbatim(path);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const glm::dvec3& p : verbatim.positions) {
    lo = std::min(lo, p.z);
    hi = std::max(hi, p.z);
  }
  Grid coarse = r.contour.grid;
  coarse.h = 0.5001 * (hi - lo);
  coarse.origin.z = lo - 0.0001 * (hi - lo);
  coarse.cells.z = 2;
  expectTheCheckOfTheFile(path, coarse);
}

// The check's chunks measured on several threads at once and joined as they finish (CI runs this
// one under ThreadSanitizer): the numbers of one chunk on one thread.
TEST(StreamedExport, TheCheckOnThreadsCountsWhatOneThreadCounts) {
  const std::string folder = freshFolder("check_threads");
  const std::string path = folder + "/part.stl";
  const ExportReport r = exportSlabbedScene(path);
  ASSERT_TRUE(r.passed());
  const TriangleMesh verbatim = readMeshFileVerbatim(path);
  ASSERT_GT(verbatim.triangles.size(), 3 * kMeasureBlock);
  const MeshCheck one = streamedCheckOf(verbatim, r.contour.grid, 0, 1);
  const MeshCheck many = streamedCheckOf(verbatim, r.contour.grid, kMeasureBlock, 3);
  EXPECT_EQ(one.vertices, many.vertices);
  EXPECT_EQ(one.triangles, many.triangles);
  EXPECT_EQ(one.boundaryEdges, many.boundaryEdges);
  EXPECT_EQ(one.nonManifoldEdges, many.nonManifoldEdges);
  EXPECT_EQ(one.misorientedEdges, many.misorientedEdges);
  EXPECT_EQ(one.degenerateTriangles, many.degenerateTriangles);
  EXPECT_EQ(one.components, many.components);
  EXPECT_EQ(one.genus, many.genus);
  EXPECT_EQ(one.volume, many.volume);
  EXPECT_EQ(one.area, many.area);
  EXPECT_EQ(one.smallestTriangleArea, many.smallestTriangleArea);
  EXPECT_EQ(r.check.genus, many.genus);
  EXPECT_EQ(r.check.vertices, many.vertices);
}

TEST(StreamedExport, RefusesWhatCannotBeWrittenInPieces) {
  const std::string folder = freshFolder("refused");
  const Scene scene = cases()[0].scene;
  Progress progress;
  EXPECT_THROW(exportSceneStreamed(scene, folder + "/part.obj", ExportOptions(),
                                   std::make_shared<CpuBackend>(), progress),
               Error);
  ExportOptions simplified;
  simplified.simplifyCells = 0.25;
  EXPECT_THROW(exportSceneStreamed(scene, folder + "/part.stl", simplified,
                                   std::make_shared<CpuBackend>(), progress),
               Error);
  EXPECT_EQ(entriesIn(folder), 0u);
}

TEST(StreamedExport, ACancelLeavesNothingBehind) {
  const std::string folder = freshFolder("cancel");
  const Scene scene = cases()[0].scene;
  int reports = 0;
  Progress progress([&](const std::string& stage, double) {
    if (stage == "write STL" && ++reports == 1) progress.cancel();
  });
  ExportOptions pieces;
  pieces.tileCells = 8;
  EXPECT_THROW(exportSceneStreamed(scene, folder + "/part.stl", pieces,
                                   std::make_shared<CpuBackend>(), progress),
               Cancelled);
  EXPECT_EQ(entriesIn(folder), 0u);
}

}  // namespace
}  // namespace strata::test
