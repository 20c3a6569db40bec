// exportSceneDistributed over a group of threads standing in for MPI ranks: the file is the one
// a single process writes, byte for byte, whatever the number of processes; a process that fails
// makes process 0 fail with its message and leaves no file.
#include "engine/export/distributed_export.h"

#include <gtest/gtest.h>

#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "engine/eval/cpu_backend.h"
#include "engine/util/error.h"
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
                 int failing = -1) {
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

}  // namespace
}  // namespace strata::test
