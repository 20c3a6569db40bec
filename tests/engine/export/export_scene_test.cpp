// exportScene: the one export pipeline (contour, write, re-read, check) behind `strata
// export` and the editor's export job.
#include "engine/export/export_scene.h"

#include "engine/util/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "engine/eval/cpu_backend.h"
#include "engine/io/mesh_io.h"
#include "tests/support/mesh_invariants.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

Scene boxMinusSphereScene() {
  return makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.1, {1, 1, 1})}), 32);
}

std::string freshFolder(const std::string& name) {
  const fs::path folder = fs::path(testing::TempDir()) / ("strata_export_scene_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

size_t entriesIn(const std::string& folder) {
  return size_t(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

TEST(ExportScene, ReportsTheCheckOfTheFileAsWritten) {
  const std::string folder = freshFolder("report");
  const std::string path = folder + "/part.ply";
  Progress progress;
  ExportReport r = exportScene(boxMinusSphereScene(), path, ContourOptions{0, 16},
                               std::make_shared<CpuBackend>(), progress);
  EXPECT_EQ(r.contour.tiles, 8);
  EXPECT_EQ(r.contour.grid.cells.x, 32);
  EXPECT_TRUE(r.notices.empty());
  EXPECT_TRUE(r.check.watertight());
  EXPECT_GE(r.writeSeconds, 0.0);
  EXPECT_GE(r.checkSeconds, 0.0);
  TriangleMesh written = readMeshFileRaw(path);
  EXPECT_TRUE(isWatertight(written));
  EXPECT_EQ(written.triangles.size(), r.check.triangles);
  EXPECT_NEAR(checkMesh(written).volume, r.check.volume, 1e-9 * r.check.volume);
  EXPECT_EQ(entriesIn(folder), 1u);
}

// Its own file is checked whatever the input limit: a 3MF export far over --max-file-size
// (found at 29 million triangles, whose model part outgrew the 3MF reader's old 2 GiB cap).
TEST(ExportScene, TheCheckIgnoresTheInputLimit) {
  const std::string folder = freshFolder("limit");
  const uint64_t saved = maxInputFileBytes();
  setMaxInputFileBytes(64);
  Progress progress;
  ExportReport r;
  std::string error;
  try {
    r = exportScene(boxMinusSphereScene(), folder + "/part.3mf", ContourOptions{0, 16},
                    std::make_shared<CpuBackend>(), progress);
  } catch (const Error& e) {
    error = e.what();
  }
  setMaxInputFileBytes(saved);
  EXPECT_EQ(error, "");
  EXPECT_TRUE(r.check.watertight());
  EXPECT_GT(r.check.triangles, 100u);
}

TEST(ExportScene, CancelledDuringTheCheckLeavesTheWholeNewFile) {
  const std::string folder = freshFolder("cancel");
  Progress* self = nullptr;
  Progress progress([&](const std::string& stage, double) {
    if (stage == "check") self->cancel();
  });
  self = &progress;
  EXPECT_THROW(exportScene(boxMinusSphereScene(), folder + "/part.stl", ContourOptions{},
                           std::make_shared<CpuBackend>(), progress),
               Cancelled);
  EXPECT_EQ(entriesIn(folder), 1u);  // the file, no temporary beside it
  EXPECT_TRUE(checkMesh(readMeshFileRaw(folder + "/part.stl")).watertight());
}

TEST(ExportScene, APathWithoutAFolderIsWrittenInTheWorkingFolder) {
  const std::string folder = freshFolder("relative");
  const fs::path before = fs::current_path();
  fs::current_path(folder);  // this test runs in a process of its own (gtest_discover_tests)
  Progress progress;
  ExportReport r = exportScene(boxMinusSphereScene(), "part.obj", ContourOptions{},
                               std::make_shared<CpuBackend>(), progress);
  EXPECT_TRUE(r.check.watertight());
  try {
    exportScene(boxMinusSphereScene(), "part.xyz", ContourOptions{}, std::make_shared<CpuBackend>(),
                progress);
    ADD_FAILURE() << "an unknown format was written";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("part.xyz: ", 0), 0u) << e.what();
  }
  fs::current_path(before);
  EXPECT_TRUE(fs::exists(folder + "/part.obj"));
  EXPECT_TRUE(fs::exists(folder + "/part.mtl"));
  EXPECT_EQ(entriesIn(folder), 2u);
}

}  // namespace
}  // namespace strata::test
