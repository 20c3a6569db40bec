// exportSceneDistributed over a group of threads standing in for MPI ranks: the file is the one
// a single process writes, byte for byte, whatever the number of processes; a process that fails
// makes process 0 fail with its message and leaves no file.
#include "engine/export/distributed_export.h"

#include <gtest/gtest.h>

#include <chrono>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "engine/eval/cpu_backend.h"
#include "engine/util/error.h"
#include "tests/support/gated_backend.h"
#include "tests/support/scene_builder.h"
#include "tests/support/thread_process_group.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

Scene partScene() {
  return makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.1, {1, 1, 1}),
                                             cylinder(0.3, 3.0, {0.2, 0.3, 0.0})}),
                   48);
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string folderFor(const std::string& name) {
  const fs::path folder = fs::path(testing::TempDir()) / ("strata_distributed_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

struct Outcome {
  std::vector<ExportReport> reports;
  std::vector<std::string> errors;  // "" where the process returned
};

// Runs the export on `processes` threads, each with its own CPU backend; `failing` (>= 0): that
// process's progress is cancelled before it starts.
Outcome runGroup(const Scene& scene, const std::string& path, int processes, int tileCells,
                 int failing = -1, bool streamed = false) {
  auto groups = makeThreadGroup(processes);
  Outcome out;
  out.reports.resize(size_t(processes));
  out.errors.resize(size_t(processes));
  std::vector<std::thread> threads;
  for (int p = 0; p < processes; ++p)
    threads.emplace_back([&, p] {
      Progress progress;
      if (p == failing) progress.cancel();
      ExportOptions options;
      options.tileCells = tileCells;
      options.streamed = streamed;
      try {
        out.reports[size_t(p)] = exportSceneDistributed(
            scene, path, options, std::make_shared<CpuBackend>(), *groups[size_t(p)], progress);
      } catch (const std::exception& e) {
        out.errors[size_t(p)] = e.what();
      }
    });
  for (auto& t : threads) t.join();
  return out;
}

TEST(DistributedExport, WritesTheFileOneProcessWritesByteForByte) {
  const std::string folder = folderFor("same");
  const Scene scene = partScene();
  Progress progress;
  const ExportReport single = exportScene(scene, folder + "/one.stl", ContourOptions{0, 16},
                                          std::make_shared<CpuBackend>(), progress);
  ASSERT_EQ(single.contour.tiles, 27);
  for (int processes : {1, 2, 3, 5}) {
    const std::string path = folder + "/group" + std::to_string(processes) + ".stl";
    const Outcome o = runGroup(scene, path, processes, 16);
    for (const std::string& e : o.errors) EXPECT_EQ(e, "");
    EXPECT_EQ(fileBytes(path), fileBytes(folder + "/one.stl")) << processes << " processes";
    const ExportReport& r = o.reports[0];
    EXPECT_TRUE(r.passed());
    EXPECT_EQ(r.contour.tiles, 27);
    EXPECT_EQ(r.contour.surfels, single.contour.surfels);
    EXPECT_EQ(r.contour.signDisagreements, single.contour.signDisagreements);
    EXPECT_EQ(r.check.triangles, single.check.triangles);
  }
}

TEST(DistributedExport, AFailedProcessFailsTheExportAndLeavesNoFile) {
  const std::string folder = folderFor("failed");
  const std::string path = folder + "/part.stl";
  const Outcome o = runGroup(partScene(), path, 3, 16, 2);
  EXPECT_NE(o.errors[0].find("process 2 of 3 failed: cancelled"), std::string::npos) << o.errors[0];
  EXPECT_EQ(o.errors[2], "cancelled");
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(folder));
}

// Streamed, the processes wait for process 0 (for room in the slabs, and for its word that it
// read their last tiles): when process 0 fails, it tells them to stop instead of leaving them
// waiting.
TEST(DistributedExport, AFailedProcessStopsEveryStreamedProcess) {
  const std::string folder = folderFor("failed_streamed");
  const std::string path = folder + "/part.stl";
  const Outcome o = runGroup(partScene(), path, 3, 8, 2, /*streamed=*/true);
  EXPECT_NE(o.errors[0].find("process 2 of 3 failed: cancelled"), std::string::npos) << o.errors[0];
  EXPECT_EQ(o.errors[2], "cancelled");
  EXPECT_TRUE(o.errors[1] == "" || o.errors[1] == "process 0 stopped the export") << o.errors[1];
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(folder));
}

// Streamed: while one process is held at its first tile, the others go on only within the
// slabs that may be held (distributedSlabsAhead), so process 0 holds no more than those however
// long the process falls behind; once it goes on, the file is the single process's.
TEST(DistributedExport, StreamedProcessZeroHoldsOnlyTheSlabsAheadOfOneFallenBehind) {
  const std::string folder = folderFor("held");
  const Scene scene = partScene();
  const int tileCells = 8;
  Progress single;
  exportScene(scene, folder + "/one.stl", ContourOptions{0, tileCells},
              std::make_shared<CpuBackend>(), single);
  const int processes = 3;
  auto groups = makeThreadGroup(processes);
  std::vector<std::shared_ptr<GatedBackend>> backends;
  for (int p = 0; p < processes; ++p) backends.push_back(std::make_shared<GatedBackend>());
  backends[1]->close();
  std::vector<DistributedShare> shares(processes);
  std::vector<std::string> errors(processes);
  std::vector<std::thread> threads;
  for (int p = 0; p < processes; ++p)
    threads.emplace_back([&, p] {
      Progress progress;
      ExportOptions options;
      options.tileCells = tileCells;
      options.streamed = true;
      try {
        exportSceneDistributed(scene, folder + "/group.stl", options, backends[size_t(p)],
                               *groups[size_t(p)], progress, &shares[size_t(p)]);
      } catch (const std::exception& e) {
        errors[size_t(p)] = e.what();
      }
    });
  ASSERT_TRUE(backends[1]->waitUntilHeld());
  // Long enough for the others to contour every tile of theirs (216 tiles of 8 cells, a few
  // milliseconds each) if nothing held them.
  std::this_thread::sleep_for(std::chrono::seconds(2));
  const int sampledWhileHeld = backends[0]->sampled() + backends[2]->sampled();
  backends[1]->open();
  for (auto& t : threads) t.join();
  for (const std::string& e : errors) EXPECT_EQ(e, "");
  const int tiles = shares[0].tiles, perSlab = 36;
  ASSERT_EQ(tiles, 216);
  const int ahead = distributedSlabsAhead(processes, perSlab);
  EXPECT_EQ(ahead, 2);
  EXPECT_GE(shares[0].mostSlabsHeld, 1);
  EXPECT_LE(shares[0].mostSlabsHeld, ahead);
  EXPECT_LT(sampledWhileHeld, backends[0]->sampled() + backends[2]->sampled())
      << "the others went on with every tile of theirs while one process was held";
  EXPECT_EQ(fileBytes(folder + "/group.stl"), fileBytes(folder + "/one.stl"));
}

TEST(DistributedExport, SlabsAheadAreTwoRoundsOfTiles) {
  EXPECT_EQ(distributedSlabsAhead(1, 1), 2);
  EXPECT_EQ(distributedSlabsAhead(3, 1), 6);
  EXPECT_EQ(distributedSlabsAhead(3, 36), 2);
  EXPECT_EQ(distributedSlabsAhead(40, 36), 4);
  EXPECT_EQ(distributedSlabsAhead(4, 0), 8);
}

}  // namespace
}  // namespace strata::test
