// The editor runs the preview worker and an export job at once, each with its own backend:
// nothing they share (the scene snapshot, meshes, engine tables) may race. Meant for the
// ThreadSanitizer pass in .ci/test as much as for its assertions.
#include <gtest/gtest.h>

#include <condition_variable>
#include <filesystem>
#include <mutex>

#include "engine/eval/cpu_backend.h"
#include "engine/jobs/export_job.h"
#include "engine/jobs/preview_worker.h"
#include "tests/engine/jobs/job_test_support.h"

namespace strata::test {
namespace {

TEST(Jobs, PreviewAndExportOfOneSnapshotRunTogether) {
  const std::filesystem::path folder = std::filesystem::path(testing::TempDir()) / "strata_jobs";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  auto scene = boxMinusSphere(32);

  std::mutex mutex;
  std::condition_variable changed;
  bool exported = false;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 16);
  worker.request(scene, 32, false, 1);
  ExportJob job(scene, (folder / "part.3mf").string(), ContourOptions{32, 16},
                std::make_shared<CpuBackend>(), [&](const ExportStatus& s) {
                  if (!s.finished) return;
                  std::lock_guard<std::mutex> lock(mutex);
                  exported = true;
                  changed.notify_all();
                });
  // A new snapshot while both run: the worker drops the old one, the export keeps its own.
  auto edited = boxMinusSphere(32, 3);
  worker.request(edited, 32, false, 2);
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  {
    std::unique_lock<std::mutex> lock(mutex);
    ASSERT_TRUE(changed.wait_for(lock, kJobTimeout, [&] { return exported; }));
  }
  std::shared_ptr<const PreviewResult> shown = worker.takeResult();
  ASSERT_TRUE(shown);
  EXPECT_EQ(shown->tag, 2u);
  EXPECT_TRUE(shown->ok()) << shown->error;
  const ExportStatus s = job.status();
  EXPECT_TRUE(s.succeeded) << s.error;
  EXPECT_TRUE(s.check.watertight());
}

}  // namespace
}  // namespace strata::test
