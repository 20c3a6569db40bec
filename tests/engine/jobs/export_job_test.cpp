// The background export, headless: a finished export leaves a checked file; one cancelled at any
// stage (evaluate, contour, write, check) or destroyed mid-way leaves nothing behind and an
// earlier file untouched; failures name the file. The waits are on the job's own reports.
#include "engine/jobs/export_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <vector>

#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/export/job_estimate.h"
#include "engine/io/mesh_io.h"
#include "tests/engine/jobs/job_test_support.h"
#include "tests/support/export_cases.h"
#include "tests/support/gated_backend.h"
#include "tests/support/mesh_invariants.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

// Follows a job through its listener: wakes the test when it ends, records the stages in
// order, and can hold the job's thread at the first report of a stage (by prefix) until the
// test releases it, so that a cancel lands in exactly that stage.
class ExportWatch {
 public:
  explicit ExportWatch(std::string holdAtStage = "") : holdAt_(std::move(holdAtStage)) {}
  ExportJob::Listener listener() {
    return [this](const ExportStatus& s) { onChange(s); };
  }
  bool waitUntilHeld() {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, kJobTimeout, [&] { return held_; });
  }
  void release() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      released_ = true;
    }
    changed_.notify_all();
  }
  bool waitUntilFinished() {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, kJobTimeout, [&] { return finished_; });
  }
  std::vector<std::string> stages() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stages_;
  }
  std::vector<double> fractions() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return fractions_;
  }

 private:
  void onChange(const ExportStatus& s) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (stages_.empty() || stages_.back() != s.stage) stages_.push_back(s.stage);
    if (s.running) fractions_.push_back(s.fraction);
    finished_ = s.finished;
    if (!holdAt_.empty() && !held_ && s.stage.rfind(holdAt_, 0) == 0) {
      held_ = true;
      changed_.notify_all();
      changed_.wait_for(lock, kJobTimeout, [&] { return released_; });
    }
    changed_.notify_all();
  }

  std::string holdAt_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool held_ = false;
  bool released_ = false;
  bool finished_ = false;
  std::vector<std::string> stages_;
  std::vector<double> fractions_;
};

// An empty folder of its own for each test.
std::string freshFolder(const std::string& name) {
  const fs::path folder = fs::path(testing::TempDir()) / ("strata_export_job_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

std::set<std::string> filesIn(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    names.insert(entry.path().filename().string());
  return names;
}

std::string contentOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Resolution 32 in tiles of 16: eight tiles, so a cancel during "export" lands between tiles.
ContourOptions smallTiles() {
  return ContourOptions{32, 16};
}

TEST(ExportJob, FinishedExportLeavesACheckedFile) {
  for (const std::string ext : {"stl", "obj"}) {
    SCOPED_TRACE(ext);
    const std::string folder = freshFolder("success_" + ext);
    const std::string path = folder + "/part." + ext;
    writeText(path, "an older export\n");  // replaced
    ExportWatch watch;
    ExportJob job(boxMinusSphere(32), path, smallTiles(), std::make_shared<CpuBackend>(),
                  watch.listener());
    ASSERT_TRUE(watch.waitUntilFinished());
    const ExportStatus s = job.status();
    ASSERT_TRUE(s.succeeded) << s.error;
    EXPECT_FALSE(s.running);
    EXPECT_FALSE(s.cancelled);
    EXPECT_EQ(s.path, path);
    EXPECT_EQ(s.resolution, 32);
    EXPECT_TRUE(s.check.watertight());
    EXPECT_GT(s.check.volume, 0.0);

    TriangleMesh written = readMeshFileRaw(path);
    EXPECT_TRUE(isWatertight(written));
    EXPECT_EQ(written.triangles.size(), s.check.triangles);
    std::set<std::string> expected{"part." + ext};
    if (ext == "obj") expected.insert("part.mtl");
    EXPECT_EQ(filesIn(folder), expected);  // no staging folder, no temporary file

    // The stages in the order they first appear ("write STL" counts as "write").
    std::vector<std::string> order;
    for (const auto& stage : watch.stages())
      for (const std::string name : {"evaluate", "export", "write", "check"})
        if (stage.rfind(name, 0) == 0 && std::find(order.begin(), order.end(), name) == order.end())
          order.push_back(name);
    EXPECT_EQ(order, (std::vector<std::string>{"evaluate", "export", "write", "check"}));
  }
}

// A simplified export: the file holds the simplified mesh, checked; the status says what the
// simplification did; the one progress bar never goes back, through every stage.
TEST(ExportJob, SimplifiedExportAndAProgressBarThatNeverGoesBack) {
  const std::string folder = freshFolder("simplified");
  const std::string path = folder + "/part.stl";
  ExportOptions options = smallTiles();
  options.simplifyCells = 0.25;
  ExportWatch watch;
  ExportJob job(boxMinusSphere(32), path, options, std::make_shared<CpuBackend>(),
                watch.listener());
  ASSERT_TRUE(watch.waitUntilFinished());
  const ExportStatus s = job.status();
  ASSERT_TRUE(s.succeeded) << s.error;
  EXPECT_TRUE(s.checkPassed());
  EXPECT_EQ(s.simplifyCells, 0.25);
  EXPECT_GT(s.simplify.trianglesBefore, s.simplify.trianglesAfter);
  EXPECT_EQ(s.simplify.trianglesAfter, s.check.triangles);
  EXPECT_EQ(readMeshFileRaw(path).triangles.size(), s.check.triangles);
  const std::vector<double> f = watch.fractions();
  ASSERT_GT(f.size(), 3u);
  for (size_t k = 1; k < f.size(); ++k) EXPECT_GE(f[k], f[k - 1]) << k;
  EXPECT_GT(f.back(), 0.9);
  bool simplified = false;
  for (const auto& stage : watch.stages()) simplified = simplified || stage == "simplify";
  EXPECT_TRUE(simplified);
}

// An export whose whole mesh would not fit the memory but whose pieces would is written in
// pieces (as `strata export --stream`): the same file as in memory, said in its estimate, its
// progress bar never going back.
TEST(ExportJob, AMeshTooLargeForMemoryIsWrittenInPieces) {
  const std::string folder = freshFolder("pieces");
  const auto scene = boxMinusSphere(600);  // above kProbeAbove: estimated from probes
  ExportOptions options;
  options.resolution = 600;
  auto backend = std::make_shared<CpuBackend>();
  Progress probe;
  const JobEstimate e = estimateExport(*scene, options, folder + "/x.stl", backend, probe);
  ASSERT_TRUE(e.probed);
  const uint64_t pieces = streamedPeakOnWorkers(e, 1);
  ASSERT_LT(pieces, e.peakBytes) << "a job whose pieces are no smaller proves nothing";
  ExportGuard guard;
  guard.memoryBytes = (pieces + e.peakBytes) / 2;  // the pieces fit, the whole does not
  ExportWatch watch;
  ExportJob job(scene, folder + "/part.stl", options, backend, watch.listener(), guard);
  ASSERT_TRUE(watch.waitUntilFinished());
  const ExportStatus s = job.status();
  ASSERT_TRUE(s.succeeded) << s.error;
  EXPECT_TRUE(s.inPieces);
  EXPECT_NE(s.estimate.find("written in pieces"), std::string::npos) << s.estimate;
  const std::vector<double> fractions = watch.fractions();
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  // The file the export in memory writes (insisted on with that memory).
  guard.insist = true;
  guard.memoryBytes = 0;
  ExportWatch whole;
  ExportJob again(scene, folder + "/whole.stl", options, backend, whole.listener(), guard);
  ASSERT_TRUE(whole.waitUntilFinished());
  ASSERT_TRUE(again.status().succeeded) << again.status().error;
  EXPECT_FALSE(again.status().inPieces);
  EXPECT_TRUE(contentOf(folder + "/part.stl") == contentOf(folder + "/whole.stl"));
}

// In the order the stages run (the first tile's evaluation and contour, then every tile's
// "export"), never back; a job of one tile fills most of the export's part of the bar while it
// evaluates (the bar sat at "evaluate 10%" through a long one: an artist's test).
TEST(ExportJob, TheStagesFillOneBarInOrder) {
  for (bool simplifying : {false, true}) {
    for (int tiles : {1, 2, 64}) {
      double last = 0.0;
      for (const std::string stage : {"estimate", "evaluate", "contour", "export", "merge",
                                      "simplify", "write STL", "check"}) {
        if (!simplifying && stage == "simplify") continue;
        // "export" is first reported once the first tile is done (1 / tiles).
        const std::vector<double> fractions =
            stage == "export" ? std::vector<double>{1.0 / tiles, (1.0 + 1.0 / tiles) / 2, 1.0}
                              : std::vector<double>{0.0, 0.5, 1.0};
        for (double f : fractions) {
          const double overall = overallExportFraction(stage, f, simplifying, tiles);
          EXPECT_GE(overall, last) << stage << " " << f << " " << tiles;
          last = overall;
        }
        if (stage == "contour") {  // the first tile done: its share of "export"
          EXPECT_DOUBLE_EQ(last, overallExportFraction("export", 1.0 / tiles, simplifying, tiles));
        }
      }
      EXPECT_DOUBLE_EQ(last, 1.0);
    }
    const double oneTile = overallExportFraction("evaluate", 1.0, simplifying, 1);
    EXPECT_GT(oneTile - overallExportFraction("estimate", 1.0, simplifying, 1),
              0.6 * (overallExportFraction("export", 1.0, simplifying, 1) -
                     overallExportFraction("estimate", 1.0, simplifying, 1)));
    EXPECT_LT(overallExportFraction("evaluate", 1.0, simplifying, 64),
              overallExportFraction("export", 0.05, simplifying, 64));
  }
}

// Exports a small scene to `path`, cancels the job while it is held at the first report of
// `stage`, and returns its status once it has ended (a failed assertion leaves it unfinished).
ExportStatus cancelledAt(const std::string& stage, const std::string& path) {
  ExportWatch watch(stage);
  ExportJob job(boxMinusSphere(32), path, smallTiles(), std::make_shared<CpuBackend>(),
                watch.listener());
  EXPECT_TRUE(watch.waitUntilHeld()) << "never reached " << stage;
  job.cancel();
  watch.release();
  EXPECT_TRUE(watch.waitUntilFinished());
  return job.status();
}

// Cancels the job while it is held at the first report of `stage`; expects it to end cancelled
// with `folder` as it was, and to say that the file at `path` was kept where there was one.
void cancelAt(const std::string& stage, const std::string& path, const std::string& folder) {
  const bool earlier = std::filesystem::exists(path);
  const std::set<std::string> before = filesIn(folder);
  std::vector<std::string> contents;
  for (const auto& name : before) contents.push_back(contentOf(folder + "/" + name));

  const ExportStatus s = cancelledAt(stage, path);
  EXPECT_TRUE(s.finished);
  EXPECT_TRUE(s.cancelled);
  EXPECT_FALSE(s.cancelledAfterWrite);
  EXPECT_EQ(s.cancelledKeptFile, earlier);
  EXPECT_FALSE(s.succeeded);
  EXPECT_EQ(s.error, "");

  EXPECT_EQ(filesIn(folder), before);
  std::vector<std::string> after;
  for (const auto& name : before) after.push_back(contentOf(folder + "/" + name));
  EXPECT_EQ(after, contents);
}

// Over an earlier file the job says that file was kept (the window said only "nothing was
// written": an artist's test). (A cancel during the check, after the new file is in place, leaves
// that whole new file: see ExportScene.CancelledDuringTheCheckLeavesTheWholeNewFile.)
TEST(ExportJob, CancelledAtAnyStageLeavesNothingAndKeepsTheOldFile) {
  for (const std::string stage : {"evaluate", "export", "write"}) {
    for (const std::string ext : {"stl", "obj", "3mf"}) {
      SCOPED_TRACE(stage + " ." + ext);
      const std::string folder = freshFolder("cancel_" + ext);
      writeText(folder + "/part." + ext, "the previous export\n");
      if (ext == "obj") writeText(folder + "/part.mtl", "newmtl previous\n");
      cancelAt(stage, folder + "/part." + ext, folder);
    }
    SCOPED_TRACE(stage + ", no earlier file");
    const std::string folder = freshFolder("cancel_new");
    cancelAt(stage, folder + "/part.ply", folder);
  }
}

// A cancel during the check leaves the new file, whole: the job says so, over an earlier file
// and where there was none (the window said "nothing was written" beside a complete file: an
// artist's test).
TEST(ExportJob, CancelledDuringTheCheckSaysTheFileWasWritten) {
  for (const bool earlier : {true, false}) {
    SCOPED_TRACE(earlier ? "over an earlier file" : "no earlier file");
    const std::string folder = freshFolder("cancel_check");
    const std::string path = folder + "/part.stl";
    if (earlier) writeText(path, "the previous export\n");
    const ExportStatus s = cancelledAt("check", path);
    EXPECT_TRUE(s.finished);
    EXPECT_TRUE(s.cancelled);
    EXPECT_TRUE(s.cancelledAfterWrite);
    EXPECT_FALSE(s.cancelledKeptFile);
    EXPECT_FALSE(s.succeeded);
    EXPECT_GT(readMeshFileRaw(path).triangles.size(), 100u) << "the new file, whole";
  }
}

TEST(ExportJob, DestroyedWhileEvaluatingLeavesNothing) {
  const std::string folder = freshFolder("destroyed");
  auto backend = std::make_shared<GatedBackend>();
  backend->close();
  std::weak_ptr<GatedBackend> watch = backend;
  auto job =
      std::make_unique<ExportJob>(boxMinusSphere(32), folder + "/part.stl", smallTiles(), backend);
  ASSERT_TRUE(backend->waitUntilHeld());
  backend.reset();
  expectReturnsWithin(
      kJobTimeout, [&] { job.reset(); }, "~ExportJob (held at the gate)");
  EXPECT_TRUE(watch.expired()) << "the job kept its backend alive";
  EXPECT_TRUE(filesIn(folder).empty());
}

TEST(ExportJob, FailuresNameTheFileAndLeaveNothing) {
  const std::string folder = freshFolder("failures");
  for (const std::string& path : {folder + "/missing/part.stl", folder + "/part.xyz"}) {
    SCOPED_TRACE(path);
    ExportWatch watch;
    ExportJob job(boxMinusSphere(32), path, smallTiles(), std::make_shared<CpuBackend>(),
                  watch.listener());
    ASSERT_TRUE(watch.waitUntilFinished());
    const ExportStatus s = job.status();
    EXPECT_FALSE(s.succeeded);
    EXPECT_FALSE(s.cancelled);
    EXPECT_NE(s.error.find(path), std::string::npos) << s.error;
    EXPECT_EQ(s.error.find(".export-"), std::string::npos) << s.error;  // not the staging folder
  }
  EXPECT_TRUE(filesIn(folder).empty());
}

// The export dialog's estimate, given, is the job's own: not probed again at Export (the dialog's
// probes were made twice). One marked to write a pebibyte is refused with that figure.
TEST(ExportJob, AnEstimateGivenIsTakenInsteadOfProbingAgain) {
  const std::string folder = freshFolder("given");
  const auto scene = boxMinusSphere(32);
  const ContourOptions big{520, 256};  // above kProbeAbove: estimated first
  Progress probe;
  JobEstimate given =
      estimateExport(*scene, big, folder + "/x.stl", std::make_shared<CpuBackend>(), probe);
  ASSERT_TRUE(given.probed);
  given.fileBytes = uint64_t(1) << 50;
  ExportGuard guard;
  guard.estimated = given;
  ExportWatch watch;
  ExportJob job(scene, folder + "/part.stl", big, std::make_shared<CpuBackend>(), watch.listener(),
                guard);
  ASSERT_TRUE(watch.waitUntilFinished());
  const ExportStatus s = job.status();
  EXPECT_TRUE(s.refused);
  EXPECT_NE(s.error.find("writes a file of about 1.0 PiB"), std::string::npos) << s.error;
}

// A job whose estimate does not fit is refused before any work, saying why, with its estimate;
// insisting exports it anyway.
TEST(ExportJob, AJobThatCannotFitIsRefusedUnlessInsistedOn) {
  const std::string folder = freshFolder("refused");
  const std::string path = folder + "/part.stl";
  writeText(path, "an older export\n");
  const ContourOptions big{520, 256};  // above kProbeAbove: estimated first
  {
    ExportWatch watch;
    ExportJob job(boxMinusSphere(32), path, big, std::make_shared<CpuBackend>(), watch.listener(),
                  ExportGuard{false, uint64_t(1) << 20, std::nullopt, std::nullopt});
    ASSERT_TRUE(watch.waitUntilFinished());
    const ExportStatus s = job.status();
    EXPECT_TRUE(s.refused);
    EXPECT_FALSE(s.succeeded);
    EXPECT_NE(s.error.find("the export at 520 cells needs about"), std::string::npos) << s.error;
    EXPECT_NE(s.error.find("1.0 MiB are available"), std::string::npos) << s.error;
    EXPECT_NE(s.estimate.find("triangles"), std::string::npos) << s.estimate;
    EXPECT_EQ(contentOf(path), "an older export\n");
  }
  // Insisted on: past the estimate the export itself starts (then cancelled: the test needs only
  // to see it begin).
  ExportWatch watch("evaluate");
  ExportJob job(boxMinusSphere(32), path, big, std::make_shared<CpuBackend>(), watch.listener(),
                ExportGuard{true, uint64_t(1) << 20, std::nullopt, std::nullopt});
  ASSERT_TRUE(watch.waitUntilHeld());
  job.cancel();
  watch.release();
  ASSERT_TRUE(watch.waitUntilFinished());
  const ExportStatus s = job.status();
  EXPECT_FALSE(s.refused);
  EXPECT_TRUE(s.cancelled);
  const std::vector<std::string> stages = watch.stages();
  ASSERT_GE(stages.size(), 2u);
  EXPECT_EQ(stages[0], "estimate");  // the probes' own stages are not shown
  EXPECT_EQ(stages[1], "evaluate");
  EXPECT_EQ(contentOf(path), "an older export\n");
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

// What the grid could not resolve and left out is said in the job's status, as the command
// line says it (the export window said only "watertight, 1 component(s)" where a part had been
// left out: an artist's test).
TEST(ExportJob, SpecksLeftOutAreSaid) {
  const std::string folder = freshFolder("specks");
  const std::string path = folder + "/part.stl";
  auto scene = std::make_shared<const Scene>(makeScene(
      op(NodeKind::Difference, {sphere(0.42), meshLeaf(facetedTorus(0.33, 0.12, 96, 48))}), 64));
  ExportWatch watch;
  ExportJob job(scene, path, ExportOptions{}, std::make_shared<CpuBackend>(), watch.listener());
  ASSERT_TRUE(watch.waitUntilFinished());
  const ExportStatus s = job.status();
  ASSERT_TRUE(s.succeeded) << s.error;
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.back().find("the grid cannot resolve left out"), std::string::npos)
      << s.warnings.back();
}

// Bodies the cells alone join or part are said: two bars whose ends lie closer than a cell of the
// estimate's probe (and between its nodes) are one body there and two at the job's cells, where
// the gap holds nodes; the job says so (a sphere resting on a box exported as one body at 512
// cells and as two at 1024, without a word: an artist's test). Bars a few probe cells apart are
// two bodies at both: nothing is said.
TEST(ExportJob, BodiesTheCellsAloneJoinOrPartAreSaid) {
  const int resolution = 600;  // probed (above kProbeAbove)
  int probeCells = 0;
  const auto close =
      std::make_shared<const Scene>(barsCloserThanTheProbesCell(resolution, &probeCells));
  const double probeH = Evaluator::gridFor(*close, probeCells).h;
  const auto backend = std::make_shared<CpuBackend>();
  const std::string folder = freshFolder("bodies");
  {
    ExportWatch watch;
    ExportJob job(close, folder + "/close.stl", ExportOptions{}, backend, watch.listener());
    ASSERT_TRUE(watch.waitUntilFinished());
    const ExportStatus s = job.status();
    ASSERT_TRUE(s.succeeded) << s.error;
    EXPECT_EQ(s.check.components, 2);
    const auto said = std::find_if(s.warnings.begin(), s.warnings.end(), [](const std::string& w) {
      return w.find("separate bodies at") != std::string::npos;
    });
    ASSERT_NE(said, s.warnings.end());
    EXPECT_NE(said->find("2 separate bodies at " + std::to_string(resolution) + " cells"),
              std::string::npos)
        << *said;
    EXPECT_NE(said->find(std::to_string(probeCells) + " cells made 1:"), std::string::npos)
        << *said;
  }
  {
    ExportWatch watch;
    ExportJob job(
        std::make_shared<const Scene>(barsWithAGap(-2.0 * probeH, 2.0 * probeH, resolution)),
        folder + "/apart.stl", ExportOptions{}, backend, watch.listener());
    ASSERT_TRUE(watch.waitUntilFinished());
    const ExportStatus s = job.status();
    ASSERT_TRUE(s.succeeded) << s.error;
    EXPECT_EQ(s.check.components, 2);
    for (const std::string& w : s.warnings)
      EXPECT_EQ(w.find("separate bod"), std::string::npos) << w;
  }
  EXPECT_EQ(bodiesDifferSentence(JobEstimate{}, resolution, 2), "");  // not probed: nothing
}

}  // namespace
}  // namespace strata::test
