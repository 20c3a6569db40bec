// The export dialog's estimate on its background thread (engine/jobs/export_estimate_job.h):
// the triangle counts and, for a job above kProbeAbove cells, the export's time and memory from
// them, as the export itself would estimate them (the dialog showed only triangles and a file
// size, and a short export ended before its time could be read: an artist's test).
#include "engine/jobs/export_estimate_job.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "tests/engine/jobs/job_test_support.h"

namespace strata::test {
namespace {

void waitUntilDone(const ExportEstimateJob& job) {
  const auto start = std::chrono::steady_clock::now();
  while (!job.done() && std::chrono::steady_clock::now() - start < kJobTimeout)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(job.done()) << "the estimate did not finish";
}

TEST(ExportEstimateJob, ABigJobGetsItsTimeAndMemoryFromTheSameCount) {
  const auto scene = boxMinusSphere(640);
  const auto cpu = [] { return std::make_shared<CpuBackend>(); };
  ExportEstimateJob job(scene, "/tmp/part.stl", 640, 0.0, cpu);
  waitUntilDone(job);
  ASSERT_EQ(job.error(), "");
  const TriangleEstimate counted = job.result();
  const JobEstimate e = job.jobEstimate();
  ASSERT_GT(counted.triangles, 0u);
  ASSERT_TRUE(e.probed);
  EXPECT_EQ(e.triangles, counted.triangles) << "the export's triangles are the dialog's";
  EXPECT_EQ(e.fileBytes, counted.triangles * 50u);  // binary STL
  EXPECT_GT(e.seconds, 0.0);
  EXPECT_GT(e.peakBytes, 0u);
  EXPECT_EQ(e.grid.cells, Evaluator::gridFor(*scene, 640).cells);
  // What Export may take instead of probing again: for this scene, choice and format only.
  ASSERT_TRUE(job.estimateOf(scene, "/home/me/other name.STL", 640, 0.0));
  EXPECT_EQ(job.estimateOf(scene, "/tmp/part.stl", 640, 0.0)->seconds, e.seconds);
  EXPECT_FALSE(job.estimateOf(scene, "/tmp/part.obj", 640, 0.0)) << "another format's bytes";
  EXPECT_FALSE(job.estimateOf(scene, "/tmp/part.stl", 641, 0.0));
  EXPECT_FALSE(job.estimateOf(scene, "/tmp/part.stl", 640, 0.25));
  EXPECT_FALSE(job.estimateOf(boxMinusSphere(640), "/tmp/part.stl", 640, 0.0)) << "another scene";

  // At kProbeAbove cells or fewer: the count alone (such a job takes about a second).
  ExportEstimateJob small(scene, "/tmp/part.ply", kProbeAbove, 0.0, cpu);
  waitUntilDone(small);
  ASSERT_EQ(small.error(), "");
  EXPECT_GT(small.result().triangles, 0u);
  EXPECT_FALSE(small.jobEstimate().probed);
  EXPECT_FALSE(small.estimateOf(scene, "/tmp/part.ply", kProbeAbove, 0.0)) << "nothing probed";
}

}  // namespace
}  // namespace strata::test
