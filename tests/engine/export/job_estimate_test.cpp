// Estimates before long jobs: scaled from probes at an eighth of the job (at least 64 cells),
// they must land within a factor of two of what the job then does, and say so in words a user
// reads.
#include "engine/export/job_estimate.h"

#include <gtest/gtest.h>

#include <sys/mman.h>

#include <chrono>
#include <cstring>
#include <thread>
#include <vector>

#include "engine/eval/cpu_backend.h"
#include "engine/export/simplify_mesh.h"
#include "engine/export/streamed_export.h"
#include "engine/io/scene_file.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

// A 2 x 2 x 1 box with a bowl cut into its top (a sphere's), at 160 cells.
Scene boxWithBowl() {
  return test::makeScene(
      test::op(NodeKind::Difference, {test::box({2.0, 2.0, 1.0}), test::sphere(0.8, {0, 0, 0.5})}),
      160);
}

// A probe is timed as the middle of its runs: a run slowed by a passing load (one 1 s run among
// runs of 10 ms; an artist saw an estimate ten times the job) is left out, and the seconds its
// modifiers took (excluded) are the middle ones too. Runs are repeated only within the budget:
// probes of 0.2 s with a budget of 0.3 s run twice, and the smaller counts.
TEST(JobEstimate, AProbeIsTimedAsTheMiddleOfItsRuns) {
  const auto sleeping = [](std::vector<double> seconds, std::vector<double> excluded) {
    return [seconds, excluded, i = size_t(0)]() mutable {
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds.at(i)));
      return excluded.at(i++);
    };
  };
  const ProbeTime spiked = probeTime(sleeping({1.0, 0.01, 0.01}, {0.0, 0.0, 0.0}), 3, 10.0);
  EXPECT_EQ(spiked.runs, 3);
  EXPECT_GE(spiked.seconds, 0.01);
  EXPECT_LT(spiked.seconds, 0.2) << "the slowed run counted (a mean would be 0.34)";
  const ProbeTime modifiers = probeTime(sleeping({0.01, 0.01, 0.01}, {0.5, 0.002, 0.004}), 3, 10.0);
  EXPECT_EQ(modifiers.excludedSeconds, 0.004);
  const ProbeTime budget = probeTime(sleeping({0.2, 0.3, 0.2}, {0.0, 0.0, 0.0}), 3, 0.3);
  EXPECT_EQ(budget.runs, 2);
  EXPECT_GE(budget.seconds, 0.2);
  EXPECT_LT(budget.seconds, 0.3) << "of two runs, the smaller";
  const ProbeTime once = probeTime(sleeping({0.01}, {0.0}), 1, 10.0);
  EXPECT_EQ(once.runs, 1);
}

// The scaffold of scaled copies: no modifier, so it is exported in tiles.
TEST(JobEstimate, ExportEstimateIsWithinAFactorOfTwo) {
  const Scene scene =
      loadScene(test::assetsDir() + "/scenes/bone_scaffold_scaled_copy.strata.json");
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  ContourOptions options;
  options.resolution = 256;
  options.tileCells = 64;
  const JobEstimate e =
      estimateExport(scene, options, "/tmp/x.3mf", backend, progress, /*probeAbove=*/0);
  ASSERT_TRUE(e.probed);
  EXPECT_GT(e.tiles, 1);
  Evaluator evaluator(backend);
  const ExportMesh mesh = contourScene(scene, evaluator, options, progress);
  const double ratio = double(e.triangles) / double(mesh.mesh.triangles.size());
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 2.0);
  EXPECT_NEAR(double(e.fileBytes), 19.0 * double(e.triangles), 1.0 * double(e.triangles));
  const std::string text = describeEstimate(e);
  EXPECT_NE(text.find("cells"), std::string::npos) << text;
  EXPECT_NE(text.find("tiles"), std::string::npos) << text;
  EXPECT_NE(text.find("triangles"), std::string::npos) << text;
}

// The memory an estimate gives starts from what the process holds now, not from its peak: an
// editor's estimates of the same scene grew by a third after an export (an artist's test). 256
// MiB held and let go between two estimates leave the second within 64 MiB of the first (the
// probes' own memory is let go as well).
TEST(JobEstimate, MemoryAnEarlierJobLetGoIsNotCounted) {
  const Scene scene = boxWithBowl();
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  ContourOptions options;
  options.resolution = 160;
  const auto estimate = [&] {
    return estimateExport(scene, options, "/tmp/x.stl", backend, progress, /*probeAbove=*/0);
  };
  const JobEstimate first = estimate();
  ASSERT_TRUE(first.probed);
  constexpr size_t kBytes = size_t(256) << 20;  // mapped directly: no allocator keeps it
  void* block = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(block, MAP_FAILED);
  std::memset(block, 1, kBytes);
  ASSERT_EQ(munmap(block, kBytes), 0);
  const JobEstimate second = estimate();
  EXPECT_LT(second.peakBytes, first.peakBytes + (uint64_t(64) << 20))
      << "first " << first.peakBytes << " bytes, then " << second.peakBytes;
}

// The export window's estimate says the export dialog's count (3.3 million there against
// 3.6 million in the dialog, for 3.69 million written: an artist's test): given the dialog's
// count, the job's triangles, file and simplified triangles are its.
TEST(JobEstimate, TheJobTakesTheDialogsCountOfItsTriangles) {
  const Scene scene = boxWithBowl();
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  ContourOptions options;
  options.resolution = 160;
  for (const double cells : {0.0, 0.25}) {
    const TriangleEstimate dialog = estimateExportTriangles(scene, 160, cells, backend, progress);
    ASSERT_GT(dialog.triangles, 0u);
    const JobEstimate alone =
        estimateExport(scene, options, "/tmp/x.stl", backend, progress, /*probeAbove=*/0, cells);
    const JobEstimate job = estimateExport(scene, options, "/tmp/x.stl", backend, progress,
                                           /*probeAbove=*/0, cells, &dialog);
    ASSERT_TRUE(job.probed);
    EXPECT_NE(alone.triangles, dialog.triangles) << "probes that agree prove nothing";
    EXPECT_EQ(job.triangles, dialog.triangles);
    if (cells > 0.0) {
      EXPECT_EQ(job.simplifiedTriangles, dialog.simplified);
      EXPECT_EQ(job.fileBytes, dialog.simplified * 50u);
    } else {
      EXPECT_EQ(job.fileBytes, dialog.triangles * 50u);
    }
    // (Counts under a million are written out in full.)
    ASSERT_LT(dialog.triangles, 1000000u);
    const uint64_t said = cells > 0.0 ? dialog.simplified : dialog.triangles;
    EXPECT_NE(describeEstimate(job).find("about " + std::to_string(said)), std::string::npos)
        << describeEstimate(job);
  }
}

// A simplified export's estimate counts the simplification (an export estimated at "3 s,
// 1 GiB" took 95 s and 3.1 GB): more time and memory than the same export unsimplified, a file
// of the simplified triangles, within a factor of two of them, and says it is simplified.
TEST(JobEstimate, ASimplifiedExportCountsItsSimplification) {
  const Scene scene = test::makeScene(
      test::op(NodeKind::Difference, {test::box({2.0, 2.0, 1.0}), test::sphere(0.8, {0, 0, 0.5})}),
      128);
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  ContourOptions options;
  options.resolution = 128;
  const JobEstimate plain =
      estimateExport(scene, options, "/tmp/x.stl", backend, progress, /*probeAbove=*/0);
  const JobEstimate simplified = estimateExport(scene, options, "/tmp/x.stl", backend, progress,
                                                /*probeAbove=*/0, /*simplifyCells=*/0.25);
  ASSERT_TRUE(plain.probed);
  ASSERT_TRUE(simplified.probed);
  EXPECT_EQ(plain.simplifiedTriangles, 0u);
  EXPECT_GT(simplified.simplifiedTriangles, 0u);
  EXPECT_LT(simplified.simplifiedTriangles, simplified.triangles / 4);
  EXPECT_GT(simplified.seconds, plain.seconds);
  EXPECT_GE(simplified.peakBytes, plain.peakBytes + uint64_t(300.0 * double(simplified.triangles)));
  EXPECT_LT(simplified.fileBytes, plain.fileBytes / 4);
  // Against the export itself.
  Evaluator evaluator(backend);
  ExportMesh mesh = contourScene(scene, evaluator, options, progress);
  const SimplifyReport done =
      simplifyMesh(&mesh, 0.25 * Evaluator::gridFor(scene, 128).h, progress);
  const double ratio = double(simplified.simplifiedTriangles) / double(done.trianglesAfter);
  EXPECT_GT(ratio, 0.5) << simplified.simplifiedTriangles << " for " << done.trianglesAfter;
  EXPECT_LT(ratio, 2.0) << simplified.simplifiedTriangles << " for " << done.trianglesAfter;
  const std::string text = describeEstimate(simplified);
  EXPECT_NE(text.find("simplified to about"), std::string::npos) << text;
}

// With several workers sharing a device's memory (--gpus N on one device), the export tiles
// for each worker's share (workersMemory): the estimate must reckon the same tilings, in memory
// and streamed, not the ones the whole memory would give.
TEST(JobEstimate, TilesAsTheExportDoesForItsWorkersShareOfMemory) {
  const Scene scene =
      loadScene(test::assetsDir() + "/scenes/bone_scaffold_scaled_copy.strata.json");
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  ContourOptions options;
  options.resolution = 512;
  const WorkersMemory whole{uint64_t(256) << 20, backend->offsetBytesPerNode()};
  const WorkersMemory shared = workersMemory({backend, backend}, 2);  // the call the export makes
  WorkersMemory half = whole;
  half.bytes /= 2;
  const ExportTiling wholeTiles =
      exportTiling(scene, options, whole.bytes, whole.offsetBytesPerNode);
  const ExportTiling halfTiles = exportTiling(scene, options, half.bytes, half.offsetBytesPerNode);
  ASSERT_NE(wholeTiles.count(), halfTiles.count()) << "memories that tile alike prove nothing";
  // (The host's available memory moves between two readings while other work runs.)
  EXPECT_NEAR(double(shared.bytes), double(backend->memoryAvailable() / 2),
              0.05 * double(shared.bytes));
  for (const WorkersMemory& memory : {whole, half}) {
    const JobEstimate e = estimateExport(scene, options, "/tmp/x.stl", backend, memory, progress,
                                         /*probeAbove=*/0);
    const uint64_t perNode = memory.offsetBytesPerNode;
    EXPECT_EQ(e.tiles, exportTiling(scene, options, memory.bytes, perNode).count()) << memory.bytes;
    EXPECT_EQ(e.streamedSlabs, streamedTiling(scene, options, memory.bytes, perNode).counts.z)
        << memory.bytes;
  }
}

// The export dialog's count for an artist's pen holder (3 mm walls and 6 mm slots in a 70 mm
// cylinder 100 mm tall, two scaled bunnies on its rim, rounded and filleted by 1 mm): probed at
// 64 cells it lost detail and said 32% too few triangles for 256 cells; probed at half the
// resolution it is within 10%, and the simplified count is well below the unsimplified one.
TEST(JobEstimate, DialogsTriangleCountHoldsForAnArtistsPart) {
  const Scene scene = loadScene(test::testDataDir() + "/pen_holder.strata.json");
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  const int resolution = 256;
  const TriangleEstimate e = estimateExportTriangles(scene, resolution, 0.25, backend, progress);
  Evaluator evaluator(backend);
  ContourOptions options;
  options.resolution = resolution;
  const double actual =
      double(contourScene(scene, evaluator, options, progress).mesh.triangles.size());
  EXPECT_NEAR(double(e.triangles) / actual, 1.0, 0.1) << e.triangles << " for " << actual;
  EXPECT_GT(e.simplified, 0u);
  EXPECT_LT(e.simplified, e.triangles / 4);
}

// A small export is probed at its own resolution: the bone scaffold at 128 cells, whose pores a
// probe at 64 cells lost (32,000 triangles said for 57,916 written: an artist's test).
TEST(JobEstimate, ASmallExportIsCountedAtItsOwnResolution) {
  const Scene scene = loadScene(test::assetsDir() + "/scenes/bone_scaffold.strata.json");
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  const TriangleEstimate e = estimateExportTriangles(scene, 128, 0.0, backend, progress);
  Evaluator evaluator(backend);
  ContourOptions options;
  options.resolution = 128;
  const double actual =
      double(contourScene(scene, evaluator, options, progress).mesh.triangles.size());
  EXPECT_NEAR(double(e.triangles) / actual, 1.0, 0.02) << e.triangles << " for " << actual;
}

// The estimate's memory counts one tile's LDIs (the cache is cleared between tiles): the report
// gives the most one tile held, not the sum over tiles.
TEST(JobEstimate, ReportGivesTheLdiMemoryOfOneTile) {
  const Scene scene =
      loadScene(test::assetsDir() + "/scenes/bone_scaffold_scaled_copy.strata.json");
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  uint64_t bytes[2] = {0, 0};
  for (int tiled = 0; tiled < 2; ++tiled) {
    ContourOptions options;
    options.resolution = 128;
    options.tileCells = tiled ? 40 : 256;
    Evaluator evaluator(backend);
    ContourReport report;
    contourScene(scene, evaluator, options, progress, &report);
    EXPECT_EQ(report.tiles > 1, tiled == 1);
    bytes[tiled] = report.tileLdiBytes;
  }
  EXPECT_GT(bytes[1], 0u);
  EXPECT_LT(double(bytes[1]), 0.6 * double(bytes[0])) << "one tile of several against the whole";
}

TEST(JobEstimate, SmallJobsAreNotProbedAndRefusalsSayWhy) {
  const Scene scene = loadScene(test::assetsDir() + "/scenes/demo.strata.json");
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  const JobEstimate small = estimateEvaluation(scene, 64, backend, progress, 0);
  EXPECT_FALSE(small.probed);
  EXPECT_FALSE(estimateEvaluation(scene, 512, backend, progress).probed);  // kProbeAbove
  EXPECT_FALSE(estimateWorthTelling(small));
  EXPECT_EQ(estimateRefusal(small, 1, 1), "");
  JobEstimate big = estimateEvaluation(scene, 1024, backend, progress, 0);
  ASSERT_TRUE(big.probed);
  EXPECT_GT(big.surfels, 0u);
  big.peakBytes = uint64_t(40) << 30;
  big.fileBytes = uint64_t(3) << 30;
  EXPECT_EQ(estimateRefusal(big, uint64_t(16) << 30, 0),
            "needs about 40.0 GiB of memory and 16.0 GiB are available");
  EXPECT_EQ(estimateRefusal(big, uint64_t(64) << 30, uint64_t(1) << 30),
            "writes a file of about 3.0 GiB and the disk has 1.0 GiB free");
  EXPECT_EQ(estimateRefusal(big, 0, 0), "");  // unknown room: not refused
  EXPECT_TRUE(estimateWorthTelling(big));
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

// The simplified count grows as the power of the resolution two probes measure: the bunny
// within 0.25 cells (3,512 at 128, 4,664 at 256, 6,268 written at 512 cells) is put at 6,185 at
// 512 (the linear rule said 9,328) and about 8,200 at 1024 (it said 18,000); flat faces stay
// as they are; the power is held between 0 and 2.
TEST(JobEstimate, SimplifiedTrianglesGrowAsTheProbesMeasure) {
  const uint64_t bunny512 = simplifiedAtResolution(3512, 128, 4664, 256, 512);
  EXPECT_NEAR(double(bunny512) / 6268.0, 1.0, 0.03) << bunny512;
  EXPECT_NEAR(double(simplifiedAtResolution(3512, 128, 4664, 256, 1024)), 8224.0, 10.0);
  EXPECT_EQ(simplifiedAtResolution(12, 128, 12, 256, 2048), 12u);        // a box
  EXPECT_EQ(simplifiedAtResolution(1000, 128, 2000, 256, 1024), 8000u);  // linear
  EXPECT_EQ(simplifiedAtResolution(100, 128, 10000, 256, 512), 40000u);  // held at 2
  EXPECT_EQ(simplifiedAtResolution(5000, 128, 4000, 256, 512), 4000u);   // held at 0
  EXPECT_EQ(simplifiedAtResolution(0, 128, 4000, 256, 512), 8000u);      // no coarse: linear
  EXPECT_EQ(simplifiedAtResolution(3512, 128, 4664, 256, 256), 4664u);   // the probe is the job
}

// The export job says the number the export dialog said (they differed by 57% for one bunny at
// 1024 cells, "about 18,000" and "about 28,346": two probes, two rules): one function counts both.
TEST(JobEstimate, TheJobsSimplifiedCountIsTheDialogs) {
  const Scene scene = test::makeScene(
      test::op(NodeKind::Difference, {test::sphere(1.0), test::box({0.8, 0.8, 3.0}, {0.6, 0, 0})}),
      264);
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  ContourOptions options;
  options.resolution = 264;
  const JobEstimate job = estimateExport(scene, options, "/tmp/x.stl", backend, progress,
                                         /*probeAbove=*/0, /*simplifyCells=*/0.25);
  const TriangleEstimate dialog = estimateExportTriangles(scene, 264, 0.25, backend, progress);
  ASSERT_TRUE(job.probed);
  ASSERT_GT(dialog.simplified, 0u);
  EXPECT_EQ(job.simplifiedTriangles, std::min(job.triangles, dialog.simplified));
  EXPECT_GT(dialog.simplifySecondsPerTriangle, 0.0);
}

}  // namespace
}  // namespace strata
