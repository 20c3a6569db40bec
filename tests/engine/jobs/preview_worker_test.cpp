// The preview worker's scheduling, headless: the latest request wins, cancel stops a pass, a calm
// edit goes coarse then fine, a drag stays coarse and its stop refines, and the worker can be
// destroyed while it evaluates. The waits are on results and idleness, never on sleeps.
#include "engine/jobs/preview_worker.h"

#include <gtest/gtest.h>

#include <condition_variable>
#include <cstring>
#include <map>
#include <mutex>
#include <vector>

#include "engine/ldi/lent_splats.h"
#include "tests/engine/jobs/job_test_support.h"
#include "tests/support/gated_backend.h"
#include "tests/support/off_host_splats_backend.h"

namespace strata::test {
namespace {

using ResultPtr = std::shared_ptr<const PreviewResult>;

// Every result the worker delivers, in order: taken inside onResult, so a coarse result is seen
// even when the full one follows at once.
class ResultLog {
 public:
  std::function<void()> callback() {
    return [this] { onResult(); };
  }
  // Call before the first request (onResult comes only after one).
  void attach(PreviewWorker* worker) { worker_ = worker; }
  bool waitFor(size_t count) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, kJobTimeout, [&] { return results_.size() >= count; });
  }
  std::vector<ResultPtr> results() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return results_;
  }
  // Requests `scene` calmly from the attached worker and waits until `total` results have come
  // and the worker is idle.
  ::testing::AssertionResult serve(std::shared_ptr<const Scene> scene, int resolution, uint64_t tag,
                                   size_t total) {
    worker_->request(std::move(scene), resolution, false, tag);
    if (!waitFor(total)) return ::testing::AssertionFailure() << "fewer than " << total;
    if (!worker_->waitUntilIdle(kJobTimeout)) return ::testing::AssertionFailure() << "busy";
    return ::testing::AssertionSuccess();
  }

 private:
  void onResult() {
    ResultPtr result = worker_->takeResult();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      results_.push_back(std::move(result));
    }
    changed_.notify_all();
  }

  PreviewWorker* worker_ = nullptr;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<ResultPtr> results_;
};

void expectShows(const ResultPtr& r, uint64_t tag, int resolution, bool coarse) {
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->ok()) << r->error;
  EXPECT_EQ(r->tag, tag);
  EXPECT_EQ(r->resolution, resolution);
  EXPECT_EQ(r->coarse, coarse);
  EXPECT_GT(r->splatCount(), 0u);
}

TEST(PreviewWorker, QuickRequestsLeaveOnlyTheLastResult) {
  auto backend = std::make_shared<GatedBackend>();
  backend->close(GatedBackend::OnCancel::Stay);
  ResultLog log;
  PreviewWorker worker(backend, 96, log.callback());
  log.attach(&worker);
  const int n = 8;
  std::vector<std::shared_ptr<const Scene>> scenes;
  for (int i = 0; i < n; ++i) scenes.push_back(boxMinusSphere(32, i));

  worker.request(scenes[0], 32, false, 1);
  ASSERT_TRUE(backend->waitUntilHeld());  // the first request is being evaluated
  EXPECT_TRUE(worker.status().busy);
  for (int i = 1; i < n; ++i) worker.request(scenes[i], 32, false, uint64_t(i + 1));
  backend->open();
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));

  std::vector<ResultPtr> results = log.results();
  ASSERT_EQ(results.size(), 1u);
  expectShows(results[0], n, 32, false);
  EXPECT_EQ(results[0]->scene, scenes.back());
  // Two evaluations began: the first (cancelled at the gate) and the last; requests 2..n-1
  // were replaced before the worker took them. Only the last one sampled anything.
  EXPECT_EQ(backend->arrivals(), 3);  // the first leaf of request 1, both leaves of request n
  EXPECT_EQ(backend->sampled(), 2);
  EXPECT_FALSE(worker.takeResult());  // the log took it
  EXPECT_FALSE(worker.status().busy);
}

// While a pass evaluates, its status names the grid it evaluates on: the grid its result then
// has (the preview panel shows it; the scene's own grid at that resolution may differ, as the
// preview keeps its lattice while parts move).
TEST(PreviewWorker, TheStatusNamesTheGridOfThePassBeingEvaluated) {
  auto backend = std::make_shared<GatedBackend>();
  backend->close();
  ResultLog log;
  PreviewWorker worker(backend, 96, log.callback());
  log.attach(&worker);
  auto scene = boxMinusSphere(40);
  EXPECT_FALSE(worker.status().gridKnown);
  worker.request(scene, 40, false, 1);
  ASSERT_TRUE(backend->waitUntilHeld());
  const PreviewStatus during = worker.status();
  EXPECT_TRUE(during.busy);
  ASSERT_TRUE(during.gridKnown);
  EXPECT_EQ(during.resolution, 40);
  backend->open();
  ASSERT_TRUE(log.waitFor(1));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  const ResultPtr shown = log.results().back();
  ASSERT_TRUE(shown->ok()) << shown->error;
  EXPECT_TRUE(shown->stats.grid == during.grid);
  EXPECT_FALSE(worker.status().gridKnown);  // idle: no pass, no grid
}

// A drag's newer positions do not cancel the draft of an earlier one: it finishes and shows,
// then the newest position is evaluated (the ones between are never evaluated). Cancelling each
// draft in turn showed nothing through a whole drag wherever a draft took longer than the hand's
// next move (an artist's 100 armadillos). The hand's release (a calm request) still cancels.
TEST(PreviewWorker, ADragsDraftFinishesAndTheNewestPositionFollows) {
  auto backend = std::make_shared<GatedBackend>();
  backend->close(GatedBackend::OnCancel::Leave);
  ResultLog log;
  PreviewWorker worker(backend, 32, log.callback());
  log.attach(&worker);
  worker.request(boxMinusSphere(32, 1), 32, true, 1);
  ASSERT_TRUE(backend->waitUntilHeld());  // the first position's draft is sampling
  worker.request(boxMinusSphere(32, 2), 32, true, 2);
  worker.request(boxMinusSphere(32, 3), 32, true, 3);
  backend->open();
  ASSERT_TRUE(log.waitFor(2));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 2u);
  expectShows(r[0], 1, 32, false);
  expectShows(r[1], 3, 32, false);

  backend->close(GatedBackend::OnCancel::Leave);
  worker.request(boxMinusSphere(32, 4), 32, true, 4);
  ASSERT_TRUE(backend->waitUntilHeld());
  worker.request(boxMinusSphere(32, 5), 32, false, 5);  // released: the draft is cancelled
  backend->open();
  ASSERT_TRUE(log.waitFor(3));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  r = log.results();
  ASSERT_EQ(r.size(), 3u);
  expectShows(r[2], 5, 32, false);
}

TEST(PreviewWorker, CancelStopsAPassMidwayAndTheWorkerServesOn) {
  auto backend = std::make_shared<GatedBackend>();
  backend->close();
  ResultLog log;
  PreviewWorker worker(backend, 96, log.callback());
  log.attach(&worker);
  auto scene = boxMinusSphere(32);

  worker.request(scene, 32, false, 7);
  ASSERT_TRUE(backend->waitUntilHeld());
  worker.cancel();
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  EXPECT_TRUE(log.results().empty());
  EXPECT_EQ(backend->sampled(), 0);
  EXPECT_FALSE(worker.takeResult());
  EXPECT_FALSE(worker.status().busy);

  backend->open();
  worker.request(scene, 32, false, 8);
  ASSERT_TRUE(log.waitFor(1));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  ASSERT_EQ(log.results().size(), 1u);
  expectShows(log.results()[0], 8, 32, false);
}

TEST(PreviewWorker, CancelAfterTheCoarsePassSkipsTheRefinement) {
  ResultLog log;
  PreviewWorker* self = nullptr;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, [&] {
    log.callback()();
    self->cancel();  // from the worker's thread, right after the coarse result
  });
  self = &worker;
  log.attach(&worker);
  worker.request(boxMinusSphere(64), 64, false, 3);
  ASSERT_TRUE(log.waitFor(1));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  ASSERT_EQ(log.results().size(), 1u);
  expectShows(log.results()[0], 3, 32, true);
}

TEST(PreviewWorker, CalmEditShowsTheCoarseResultThenTheFullOne) {
  ResultLog log;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback());
  log.attach(&worker);
  auto scene = boxMinusSphere(64);
  worker.request(scene, 64, false, 1);
  ASSERT_TRUE(log.waitFor(2));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 2u);
  expectShows(r[0], 1, 32, true);
  expectShows(r[1], 1, 64, false);
  EXPECT_EQ(r[0]->scene, scene);
  EXPECT_EQ(r[1]->scene, scene);
  EXPECT_GT(r[1]->surfels, r[0]->surfels);  // the finer grid has more rays
}

// The coarse pass of a calm edit shows a part under a round smaller than two of its cells
// unrounded (a round its cells cannot resolve tears thin walls apart), and says so; the full
// pass rounds it.
TEST(PreviewWorker, TheCoarsePassLeavesOutModifiersItsCellsCannotResolveButTheEditedOne) {
  ResultLog log;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 16, log.callback());
  log.attach(&worker);
  auto round = std::make_shared<Node>(*modifier(NodeKind::Round, 0.2, {box({4.0, 4.0, 1.0})}));
  round->name = "rim";
  auto scene = std::make_shared<const Scene>(makeScene(round, 64));
  worker.request(scene, 64, false, 1);
  ASSERT_TRUE(log.waitFor(2));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 2u);
  expectShows(r[0], 1, 16, true);
  expectShows(r[1], 1, 64, false);
  ASSERT_EQ(r[0]->stats.skippedModifiers.size(), 1u);
  EXPECT_EQ(r[0]->stats.skippedModifiers[0], "round 'rim'");
  EXPECT_TRUE(r[1]->stats.skippedModifiers.empty());
  EXPECT_LT(r[1]->stats.measure.volume, 15.8);  // the box of 16, its edges rounded
  EXPECT_GT(r[0]->stats.measure.volume, r[1]->stats.measure.volume + 0.3);  // not rounded
  // The modifier being edited is applied by the coarse pass too: a drag on a round's radius
  // showed the parts unrounded ("coarse, unmodified") whatever the radius (an artist's test).
  // A worker of its own: one that has measured a quick full pass drafts in full.
  ResultLog dragLog;
  PreviewWorker dragWorker(std::make_shared<CpuBackend>(), 16, dragLog.callback());
  dragLog.attach(&dragWorker);
  dragWorker.request(scene, 64, true, 2, {}, {round->id});
  ASSERT_TRUE(dragLog.waitFor(1));
  ASSERT_TRUE(dragWorker.waitUntilIdle(kJobTimeout));
  const std::vector<ResultPtr> drafts = dragLog.results();
  ASSERT_EQ(drafts.size(), 1u);
  expectShows(drafts[0], 2, 16, true);
  EXPECT_TRUE(drafts[0]->stats.skippedModifiers.empty());
}

TEST(PreviewWorker, DragStaysCoarseAndItsStopRefinesWithoutRepeatingIt) {
  ResultLog log;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback());
  log.attach(&worker);
  auto dragged = boxMinusSphere(64, 1);
  worker.request(dragged, 64, true, 1);  // the hand moves
  ASSERT_TRUE(log.waitFor(1));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  worker.request(dragged, 64, false, 2);  // the hand stops on the same snapshot
  ASSERT_TRUE(log.waitFor(2));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  // At or below the coarse resolution a drag is evaluated in full.
  worker.request(boxMinusSphere(24, 2), 24, true, 3);
  ASSERT_TRUE(log.waitFor(3));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));

  std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 3u);
  expectShows(r[0], 1, 32, true);
  expectShows(r[1], 2, 64, false);
  expectShows(r[2], 3, 24, false);
}

TEST(PreviewWorker, ErrorsArriveAsResults) {
  ResultLog log;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback());
  log.attach(&worker);
  worker.request(std::make_shared<const Scene>(), 32, false, 4);  // no root
  ASSERT_TRUE(log.waitFor(1));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  ResultPtr r = log.results().at(0);
  EXPECT_FALSE(r->ok());
  EXPECT_FALSE(r->error.empty());
  EXPECT_EQ(r->tag, 4u);
}

TEST(PreviewWorker, DestructionWhileEvaluatingNeitherHangsNorLeaks) {
  auto backend = std::make_shared<GatedBackend>();
  backend->close();
  std::weak_ptr<GatedBackend> watch = backend;
  auto worker = std::make_unique<PreviewWorker>(backend, 96);
  worker->request(boxMinusSphere(32), 32, false, 1);
  ASSERT_TRUE(backend->waitUntilHeld());
  backend.reset();  // the worker holds the last reference now
  expectReturnsWithin(
      kJobTimeout, [&] { worker.reset(); }, "~PreviewWorker (held at the gate)");
  EXPECT_TRUE(watch.expired()) << "the worker kept its backend alive";
}

TEST(PreviewWorker, DestructionWithRealWorkInFlightReturns) {
  // No gate: wherever the evaluation happens to be (not yet taken, sampling, combining, making
  // splats), the destructor cancels and joins.
  for (int i = 0; i < 4; ++i) {
    auto worker = std::make_unique<PreviewWorker>(std::make_shared<CpuBackend>(), 32);
    worker->request(boxMinusSphere(64, i), 64, false, 1);
    worker->request(boxMinusSphere(64, i + 10), 64, i % 2 == 0, 2);
    expectReturnsWithin(
        kJobTimeout, [&] { worker.reset(); }, "~PreviewWorker");
  }
}

// A resolution typed far past the slider is previewed at what fits in a quarter of the memory
// the system has and, above the slider's range, in kPreviewSeconds, scaled from the last
// result; nothing shown yet: at most the slider's maximum.
TEST(PreviewResolution, CappedToWhatFitsInMemoryAndTime) {
  const uint64_t gib = uint64_t(1) << 30;
  // Shown: 256 cells held 64 MiB in 0.01 s; 4 GiB available: 1 GiB of budget fits 1024 cells.
  EXPECT_EQ(previewResolutionFor(512, 256, 64u << 20, 0.01, 4 * gib), 512);
  EXPECT_EQ(previewResolutionFor(16384, 256, 64u << 20, 0.01, 4 * gib), 1024);
  EXPECT_EQ(previewResolutionFor(16384, 1024, 1024u << 20, 0.16, 4 * gib), 1024);  // stable
  // Plenty of memory: time decides above the slider (0.05 s at 256 -> 5 s at 2560)...
  EXPECT_EQ(previewResolutionFor(16384, 256, 1u << 20, 0.05, 64 * gib), 2560);
  // ...but never below the slider's range.
  EXPECT_EQ(previewResolutionFor(16384, 256, 1u << 20, 10.0, 64 * gib), 1024);
  EXPECT_EQ(previewResolutionFor(1024, 256, 1u << 20, 10.0, 64 * gib), 1024);
  EXPECT_EQ(previewResolutionFor(16384, 0, 0, 0.0, 2 * gib), kSliderMaxResolution);
  EXPECT_EQ(previewResolutionFor(600, 0, 0, 0.0, 2 * gib), 600);
  EXPECT_EQ(previewResolutionFor(64, 256, uint64_t(1) << 40, 0.01, 1), kMinResolution);
}

// A drag is drafted at the finest of full, full/2, full/4 that the last full pass predicts
// within the budget (time grows with the square of the resolution), never under the coarse
// resolution, which is also what it gets while nothing is measured.
TEST(PreviewResolution, DraftsAsFineAsTheLastFullPassPredictsWithinTheBudget) {
  EXPECT_EQ(draftResolutionFor(512, 96, 0, -1.0, 0.05), 96);      // nothing measured
  EXPECT_EQ(draftResolutionFor(512, 96, 512, 0.007, 0.05), 512);  // a GPU: drags in full
  EXPECT_EQ(draftResolutionFor(512, 96, 512, 0.12, 0.05), 256);   // 0.03 s at 256
  EXPECT_EQ(draftResolutionFor(512, 96, 512, 0.6, 0.05), 128);    // 0.0375 s at 128
  EXPECT_EQ(draftResolutionFor(512, 96, 512, 3.0, 0.05), 96);     // too slow for any
  EXPECT_EQ(draftResolutionFor(256, 96, 1024, 2.4, 0.05), 128);   // measured at another
  EXPECT_EQ(draftResolutionFor(300, 96, 300, 1.0, 0.05), 96);     // 300/4 is under 96
  EXPECT_EQ(draftResolutionFor(64, 96, 512, 100.0, 0.05), 64);    // at most the full one
}

// A drag is drafted from what its own passes cost once they are measured: a part dragged costs
// less than a pass of every part (a plate dragged at 256 cells stayed at 96 all the way: an
// artist's test). Measured at a resolution, that time; else scaled from the finest measured.
TEST(PreviewResolution, ADragIsDraftedFromWhatItsOwnPassesCost) {
  // Nothing measured yet: as the last full pass predicts (2 s at 256: 96).
  EXPECT_EQ(dragResolutionFor(256, 96, {}, 2.0, 0.05), 96);
  // Its passes at 96 took 8 ms: 128 (14 ms) and 256 (57 ms, over) predicted, 128 taken.
  EXPECT_EQ(dragResolutionFor(256, 96, {{96, 0.008}}, 2.0, 0.05), 128);
  // At 96 5 ms: 256 predicted 36 ms, drafted in full.
  EXPECT_EQ(dragResolutionFor(256, 96, {{96, 0.005}}, 2.0, 0.05), 256);
  // Measured at 256 itself and slow there: 128, whose own time holds.
  EXPECT_EQ(dragResolutionFor(256, 96, {{96, 0.005}, {128, 0.02}, {256, 0.09}}, 2.0, 0.05), 128);
  // Too slow even at 128: the coarsest.
  EXPECT_EQ(dragResolutionFor(256, 96, {{128, 0.07}}, 2.0, 0.05), 96);
  EXPECT_EQ(dragResolutionFor(64, 96, {{64, 1.0}}, 2.0, 0.05), 64);  // at most the full one
}

// After a quick full pass, a calm edit skips the coarse pass: its full result comes at once
// (a coarse one first would only delay the edit on the screen by a frame).
TEST(PreviewWorker, AfterAQuickFullPassACalmEditGoesStraightToTheFullResult) {
  ResultLog log;
  // Everything counts as quick here, whatever the machine (sanitizers included).
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback(), 1e9);
  log.attach(&worker);
  worker.request(boxMinusSphere(64, 0), 64, false, 1);
  ASSERT_TRUE(log.waitFor(2));  // the first: coarse, then full (nothing measured yet)
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  worker.request(boxMinusSphere(64, 1), 64, false, 2);
  ASSERT_TRUE(log.waitFor(3));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 3u);
  expectShows(r[2], 2, 64, false);
}

// A calm edit that changed no part (here a rename; a measurement is the same) is served from the
// cache at once, without a coarse pass, and carries the splats already shown (the same handle:
// the UI keeps its image); one that changes a part goes coarse, then full, with new splats.
TEST(PreviewWorker, AnEditThatChangedNoPartKeepsTheSplatsShown) {
  ResultLog log;
  // Nothing counts as quick: a changed part always goes coarse first.
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback(), 0.0);
  log.attach(&worker);
  auto scene = boxMinusSphere(64, 0);
  ASSERT_TRUE(log.serve(scene, 64, 1, 2));
  auto renamed = std::make_shared<Scene>(*scene);
  auto root = std::make_shared<Node>(*renamed->root);
  root->name = "renamed";
  renamed->root = root;
  ASSERT_TRUE(log.serve(renamed, 64, 2, 3));
  ASSERT_TRUE(log.serve(boxMinusSphere(64, 1), 64, 3, 5));  // the sphere grew: a part changed
  std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 5u);
  expectShows(r[1], 1, 64, false);
  expectShows(r[2], 2, 64, false);  // no coarse result before it
  EXPECT_EQ(r[2]->splats, r[1]->splats);
  EXPECT_EQ(r[2]->stats.computed, 0);
  expectShows(r[3], 3, 32, true);
  expectShows(r[4], 3, 64, false);
  EXPECT_NE(r[4]->splats, r[1]->splats);
}

// The preview's resolution raised (the same parts, a finer grid): the full result shown stays
// until the finer one replaces it, with no coarse pass between them (an artist saw the scaffold
// at 96 cells, porous, for the whole 13 s of a 768-cell pass). A part changed afterwards goes
// coarse first again.
TEST(PreviewWorker, AFinerResolutionOfTheSamePartsKeepsTheFullResultShown) {
  ResultLog log;
  // Nothing counts as quick: only the rule under test skips the coarse pass.
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback(), 0.0);
  log.attach(&worker);
  auto scene = boxMinusSphere(64, 0);
  ASSERT_TRUE(log.serve(scene, 64, 1, 2));
  auto finer = std::make_shared<Scene>(*scene);
  finer->settings.resolution = 128;  // the same root: no part changed
  ASSERT_TRUE(log.serve(finer, 128, 2, 3));
  ASSERT_TRUE(log.serve(boxMinusSphere(128, 1), 128, 3, 5));  // the sphere grew: a part changed
  std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 5u);
  expectShows(r[0], 1, 32, true);
  expectShows(r[1], 1, 64, false);
  expectShows(r[2], 2, 128, false);  // no coarse result before it
  expectShows(r[3], 3, 32, true);
  expectShows(r[4], 3, 128, false);
}

// An edit that grows the scene a little is evaluated on the lattice of the result before it (the
// cache keeps the parts it left alone); once no request has come for the settle time, the same
// scene is evaluated again on its own lattice: the image at rest is the one a reopened document
// and `strata export` at that resolution sample (an artist's reopened scene looked different).
TEST(PreviewWorker, AtRestTheResultIsOnTheScenesOwnLattice) {
  ResultLog log;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback(), 1e9, 0.02, 0.0);
  log.attach(&worker);
  auto scene = [](double x) {
    return std::make_shared<const Scene>(
        makeScene(op(NodeKind::Union, {box({2, 2, 2}), sphere(0.5, {x, 1, 1})}), 64));
  };
  const auto before = scene(3.0);
  ASSERT_TRUE(log.serve(before, 64, 1, 2));  // coarse, then full: on its own lattice already
  EXPECT_EQ(log.results().size(), 2u);
  const auto grown = scene(3.13);  // about 4% longer along x: within the lattice's slack
  worker.request(grown, 64, false, 2);
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  const std::vector<ResultPtr> r = log.results();
  ASSERT_EQ(r.size(), 4u);  // the edit's full result, then the one at rest
  const Grid own = Evaluator::previewGridFor(*grown, 64, nullptr);
  expectShows(r[2], 2, 64, false);
  EXPECT_FALSE(r[2]->stats.grid == own) << "the edit's pass kept the lattice before it";
  EXPECT_EQ(r[2]->stats.grid.h, r[1]->stats.grid.h);
  expectShows(r[3], 2, 64, false);
  EXPECT_TRUE(r[3]->stats.grid == own);
  // What the export at 64 cells samples: the same surfels.
  EXPECT_EQ(r[3]->surfels, evaluateCpu(*grown).root->surfelCount());
  EXPECT_NE(r[2]->surfels, r[3]->surfels);
  // Served again unchanged: nothing more to settle.
  ASSERT_TRUE(log.serve(grown, 64, 3, 5));
  EXPECT_EQ(log.results().size(), 5u);
  EXPECT_TRUE(log.results().back()->stats.grid == own);
}

// A cutter that sticks out of its part (a rod through a plate) is drawn whole as a ghost: it was
// clipped at the result's grid, which covers the plate (an artist saw a stub). One far longer is
// drawn up to the grid's longest side beyond it; one inside the grid comes from the
// result's own evaluation.
TEST(PreviewWorker, AGhostReachesBeyondTheResultsGrid) {
  ResultLog log;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback(), 0.0);
  log.attach(&worker);
  NodePtr rod = cylinder(0.3, 6.0);
  NodePtr longRod = cylinder(0.2, 600.0, {0.5, 0.5, 0.0});
  NodePtr inside = sphere(0.4, {-0.5, -0.5, 0.5});
  NodePtr pin = cylinder(0.1, 5.0, {-0.5, 0.5, 0.0});  // a third that sticks out
  auto scene = std::make_shared<const Scene>(
      makeScene(op(NodeKind::Difference, {box({2, 2, 2}), rod, longRod, inside, pin}), 64));
  const std::vector<NodeId> ghosts{rod->id, longRod->id, inside->id, pin->id};
  worker.request(scene, 64, false, 1, ghosts);
  ASSERT_TRUE(log.waitFor(2));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  const ResultPtr r = log.results().back();
  expectShows(r, 1, 64, false);
  const Grid& grid = r->stats.grid;
  const Bounds window = grid.bounds();
  const double h = grid.h;
  std::map<NodeId, Bounds> drawn;
  for (const GhostSplats& g : r->ghosts) {
    drawn[g.id] = splatBounds(*g.splats);
    EXPECT_EQ(g.h, r->stats.grid.h) << "drawn with splats of its own lattice";
  }
  ASSERT_EQ(drawn.size(), 4u);

  const Bounds rodBox = nodeBounds(rod, scene->root, glm::dmat4(1.0));
  ASSERT_LT(rodBox.min.z, window.min.z - 1.0);  // it does reach beyond the result's grid
  ASSERT_GT(rodBox.max.z, window.max.z + 1.0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(drawn[rod->id].min[a], rodBox.min[a], 1.01 * h) << a;
    EXPECT_NEAR(drawn[rod->id].max[a], rodBox.max[a], 1.01 * h) << a;
  }
  EXPECT_EQ(ghostWindow(*scene, rod->id, grid).h, h);  // the result's lattice

  const int reach = std::max(grid.cells.x, std::max(grid.cells.y, grid.cells.z));
  const Grid longWindow = ghostWindow(*scene, longRod->id, grid);
  EXPECT_NEAR(longWindow.bounds().max.z, window.max.z + reach * h, 1e-9);
  EXPECT_NEAR(longWindow.bounds().min.z, window.min.z - reach * h, 1e-9);
  EXPECT_NEAR(drawn[longRod->id].max.z, window.max.z + reach * h, 1.01 * h);
  EXPECT_NEAR(drawn[longRod->id].min.z, window.min.z - reach * h, 1.01 * h);

  EXPECT_EQ(ghostWindow(*scene, inside->id, grid), grid);
  const Bounds insideBox = nodeBounds(inside, scene->root, glm::dmat4(1.0));
  EXPECT_NEAR(drawn[inside->id].max.x, insideBox.max.x, 1.01 * h);

  // An edit that changes no part (a rename) is shown from the cache at once, every ghost
  // included (one evaluator for all ghosts dropped the first ghost's LDIs while it evaluated
  // the next: the edit went coarse and computed them again).
  auto renamed = std::make_shared<Scene>(*scene);
  auto root = std::make_shared<Node>(*renamed->root);
  root->name = "renamed";
  renamed->root = root;
  const size_t before = log.results().size();
  worker.request(renamed, 64, false, 2, ghosts);
  ASSERT_TRUE(log.waitFor(before + 1));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  const std::vector<ResultPtr> after = log.results();
  ASSERT_EQ(after.size(), before + 1) << "no coarse pass first";
  expectShows(after.back(), 2, 64, false);
  EXPECT_EQ(after.back()->stats.computed, 0);
  EXPECT_EQ(after.back()->ghosts.size(), 4u);
}

// A ghost's own window is at most kGhostMaxCells along its longest side: a box cutting half a
// part and reaching far beyond it (rays over nine times the part's area at 1024 cells) is drawn
// from every second, fourth ... node of the result's lattice, and still covers what it did.
TEST(GhostWindow, AFarReachingCutterIsDrawnFromACoarserLatticeOfTheSameNodes) {
  NodePtr slab = box({40, 40, 40}, {0, 0, 20});  // the upper half of the part and far beyond
  auto scene = std::make_shared<const Scene>(
      makeScene(op(NodeKind::Difference, {box({2, 2, 2}), slab}), 1024));
  const Grid grid = Evaluator::previewGridFor(*scene, 1024, nullptr);
  const Grid own = ghostWindow(*scene, slab->id, grid);
  EXPECT_LE(std::max(own.cells.x, std::max(own.cells.y, own.cells.z)), kGhostMaxCells);
  const double scale = own.h / grid.h;
  EXPECT_GE(scale, 2.0);
  EXPECT_EQ(scale, std::exp2(std::round(std::log2(scale))));  // a power of two
  for (int a = 0; a < 3; ++a) {  // its first node is a node of the result's lattice
    const double node = (own.origin[a] + own.first[a] * own.h - grid.origin[a]) / grid.h;
    EXPECT_NEAR(node, std::round(node), 1e-6) << a;
  }
  // It reaches as far as the window on the result's lattice would: the grid's longest side
  // beyond it (the slab's own faces are farther).
  const int reach = std::max(grid.cells.x, std::max(grid.cells.y, grid.cells.z));
  const Bounds shown = own.bounds(), part = grid.bounds();
  for (int a = 0; a < 2; ++a) {
    EXPECT_LE(shown.min[a], part.min[a] - reach * grid.h + 1e-9) << a;
    EXPECT_GE(shown.max[a], part.max[a] + reach * grid.h - 1e-9) << a;
  }
  EXPECT_LE(shown.min.z, 0.0 - kGuardCells * grid.h);
  // The same scene at 128 cells (a window of at most 384): the result's own lattice.
  const Grid coarse = Evaluator::previewGridFor(*scene, 128, nullptr);
  EXPECT_EQ(ghostWindow(*scene, slab->id, coarse).h, coarse.h);
}

// An edit's result is published before the ghosts that reach beyond its grid are evaluated (a
// slow ghost must not hold the edit's image back): it carries the ghost last shown of that
// node, moved as the node moved, and a copy with the new ghost (the same splats) follows.
TEST(PreviewWorker, AnEditsResultComesBeforeItsGhostsBeyondTheGrid) {
  auto gated = std::make_shared<test::GatedBackend>();
  ResultLog log;
  // No coarse pass once a full pass was quick (the first request's is coarse first); a ghost
  // carried always moved with its part (however quick its ghosts).
  PreviewWorker worker(gated, 32, log.callback(), 1e9, 0.0);
  log.attach(&worker);
  NodePtr rod = cylinder(0.3, 6.0);
  NodePtr base = box({2, 2, 2});
  auto scene = std::make_shared<const Scene>(makeScene(op(NodeKind::Difference, {base, rod}), 64));
  worker.request(scene, 64, false, 1, {rod->id});
  ASSERT_TRUE(log.waitFor(1));
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  const ResultPtr first = log.results().back();
  expectShows(first, 1, 64, false);
  ASSERT_EQ(first->ghosts.size(), 1u);
  const auto firstGhost = first->ghosts[0].splats;
  ASSERT_GT(firstGhost->count(), 0u);

  // The rod moved along x: the result samples it once on its grid, then its ghost alone is held.
  auto moved = std::make_shared<Scene>(*scene);
  auto root = std::make_shared<Node>(*moved->root);
  auto movedRod = std::make_shared<Node>(*rod);
  movedRod->transform.translate.x += 0.25;
  root->children[1] = movedRod;
  moved->root = root;
  const size_t before = log.results().size();
  gated->close(test::GatedBackend::OnCancel::Leave, 1);
  worker.request(moved, 64, false, 2, {rod->id});
  ASSERT_TRUE(gated->waitUntilHeld());
  std::vector<ResultPtr> results = log.results();
  ASSERT_EQ(results.size(), before + 1) << "the edit's result waited for its ghost";
  const ResultPtr shown = results.back();
  expectShows(shown, 2, 64, false);
  ASSERT_EQ(shown->ghosts.size(), 1u);
  // Meanwhile the ghost last shown, moved as the rod moved (it stood where the rod had been).
  const Bounds firstBox = splatBounds(*firstGhost);
  const Bounds meanwhile = splatBounds(*shown->ghosts[0].splats);
  EXPECT_EQ(shown->ghosts[0].splats->count(), firstGhost->count());
  EXPECT_NEAR(meanwhile.min.x - firstBox.min.x, 0.25, 1e-5);
  EXPECT_NEAR(meanwhile.max.y - firstBox.max.y, 0.0, 1e-5);
  EXPECT_EQ(shown->ghosts[0].h, first->ghosts[0].h);  // made on that ghost's lattice
  gated->open();
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  results = log.results();
  ASSERT_EQ(results.size(), before + 2);
  const ResultPtr withGhost = results.back();
  EXPECT_EQ(withGhost->tag, 2u);
  EXPECT_EQ(withGhost->splats, shown->splats) << "the same image";
  ASSERT_EQ(withGhost->ghosts.size(), 1u);
  const Bounds was = splatBounds(*firstGhost), now = splatBounds(*withGhost->ghosts[0].splats);
  EXPECT_NEAR(now.min.x - was.min.x, 0.25, 1.01 * shown->stats.grid.h);
  EXPECT_NEAR(now.max.x - was.max.x, 0.25, 1.01 * shown->stats.grid.h);
  EXPECT_GT(now.max.z, shown->stats.grid.bounds().max.z + 1.0) << "whole, beyond the grid";
}

// A ghost beyond the grid follows an undo back to the state before last: its evaluator holds
// that LDI still (nothing computed), but the ghost shown is the other state's (a review: the
// skip of "nothing computed" left the moved ghost on the restored scene).
TEST(PreviewWorker, AGhostBeyondTheGridFollowsAnUndoToTheStateBeforeLast) {
  ResultLog log;
  // The ghost carried never moved with its part (however slow the ghosts): the skip by the LDI's
  // key is what is tested.
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback(), 1e9, 1e9);
  log.attach(&worker);
  NodePtr rod = cylinder(0.3, 6.0);
  auto first =
      std::make_shared<const Scene>(makeScene(op(NodeKind::Difference, {box({2, 2, 2}), rod}), 64));
  const auto ghostOf = [&](std::shared_ptr<const Scene> scene, uint64_t tag) {
    worker.request(scene, 64, false, tag, {rod->id});
    EXPECT_TRUE(worker.waitUntilIdle(kJobTimeout));
    const ResultPtr r = log.results().back();
    EXPECT_EQ(r->tag, tag);
    EXPECT_EQ(r->ghosts.size(), 1u);
    return r->ghosts.empty() ? std::vector<Splat>() : r->ghosts[0].splats->splats();
  };
  const std::vector<Splat> a = ghostOf(first, 1);
  const Grid grid = log.results().back()->stats.grid;
  // Moved by a fraction of a cell that keeps its window (the window's ends are whole cells):
  // another ghost on the same window.
  std::shared_ptr<Scene> moved;
  for (int k = 1; k <= 16 && !moved; ++k) {
    auto scene = std::make_shared<Scene>(*first);
    auto root = std::make_shared<Node>(*scene->root);
    auto movedRod = std::make_shared<Node>(*rod);
    movedRod->transform.translate.x += grid.h * k / 17.0;
    root->children[1] = movedRod;
    scene->root = root;
    if (ghostWindow(*first, rod->id, grid) == ghostWindow(*scene, rod->id, grid)) moved = scene;
  }
  ASSERT_TRUE(moved) << "no move within a cell kept the window";
  const std::vector<Splat> b = ghostOf(moved, 2);
  ASSERT_EQ(log.results().back()->stats.grid, grid);
  const auto same = [](const std::vector<Splat>& x, const std::vector<Splat>& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(Splat)) == 0);
  };
  ASSERT_FALSE(same(a, b)) << "the move changed the ghost";
  const std::vector<Splat> c = ghostOf(first, 3);  // undone
  EXPECT_TRUE(same(a, c)) << "the ghost of the state undone to";
}

// A turned cutter beyond the grid that did not move (an edit elsewhere: a rename) keeps the ghost
// shown, the same splats, and no copy of the result follows (its world matrix's inverse left a
// rounding's move, which made a moved copy and a new ghost on every edit).
TEST(PreviewWorker, AnUnmovedTurnedGhostIsKeptAsItIs) {
  ResultLog log;
  PreviewWorker worker(std::make_shared<CpuBackend>(), 32, log.callback(), 1e9, 0.0);
  log.attach(&worker);
  auto turned = std::make_shared<Node>(*cylinder(0.3, 6.0, {0.2, -0.3, 0.1}));
  turned->transform.rotateDegrees = glm::dvec3(30.0, 20.0, 0.0);
  const NodePtr rod = turned;
  auto scene =
      std::make_shared<const Scene>(makeScene(op(NodeKind::Difference, {box({2, 2, 2}), rod}), 64));
  worker.request(scene, 64, false, 1, {rod->id});
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  const ResultPtr first = log.results().back();
  ASSERT_EQ(first->ghosts.size(), 1u);
  ASSERT_FALSE(ghostWindow(*scene, rod->id, first->stats.grid) == first->stats.grid);
  auto renamed = std::make_shared<Scene>(*scene);
  auto root = std::make_shared<Node>(*renamed->root);
  root->name = "renamed";
  renamed->root = root;
  const size_t before = log.results().size();
  worker.request(renamed, 64, false, 2, {rod->id});
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  const std::vector<ResultPtr> after = log.results();
  ASSERT_EQ(after.size(), before + 1) << "a copy with a ghost made again";
  ASSERT_EQ(after.back()->ghosts.size(), 1u);
  EXPECT_EQ(after.back()->ghosts[0].splats, first->ghosts[0].splats) << "the ghost shown, kept";
}

// Regions of host memory lent as the editor's mapped buffers are (ui/mapped_splat_slots.h),
// given back on whatever thread drops the last result holding one.
class TestLender : public HostSplatLender {
 public:
  TestLender(int regions, size_t capacity) : memory_(size_t(regions)), lent_(size_t(regions)) {
    for (auto& m : memory_) m.resize(capacity);
  }
  std::shared_ptr<LentHostSplats> lend(size_t count, const SplatLevels& levels) override {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < memory_.size(); ++i) {
      if (lent_[i] || memory_[i].size() < count) continue;
      lent_[i] = true;
      ++lends_;
      return std::make_shared<LentHostSplats>(memory_[i].data(), count, levels, [this, i] {
        std::lock_guard<std::mutex> giveBack(mutex_);
        lent_[i] = false;
        ++givenBack_;
      });
    }
    return nullptr;
  }
  bool owns(const Splat* p) const {
    for (const auto& m : memory_)
      if (m.data() == p) return true;
    return false;
  }
  size_t lends() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lends_;
  }
  size_t givenBack() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return givenBack_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::vector<Splat>> memory_;
  std::vector<bool> lent_;
  size_t lends_ = 0, givenBack_ = 0;
};

bool sameSplats(const SplatResource& a, const SplatResource& b) {
  return a.count() == b.count() && a.hostData() && b.hostData() &&
         std::memcmp(a.hostData(), b.hostData(), a.bytes()) == 0;
}

// Device splats copied to the host go into the regions lent while one is free (else into the
// worker's own arrays), hold the splats the CPU backend makes, and every region comes back once
// the results holding it are gone: those the worker dropped (superseded before they were taken)
// on its thread, the rest on this one.
TEST(PreviewWorker, HostCopiesOfDeviceSplatsGoIntoLentRegionsAndComeBack) {
  auto lender = std::make_shared<TestLender>(1, 200000);
  // Nothing taken while it works: each result replaces the one before it in the worker. Every
  // pass counts as quick: after the first request's coarse and full passes, full passes only.
  PreviewWorker worker(std::make_shared<OffHostSplatsBackend>(), 32, {}, 1e9);
  worker.setHostSplatLender(lender);
  PreviewWorker reference(std::make_shared<CpuBackend>(), 32, {}, 1e9);
  const std::shared_ptr<const Scene> scenes[] = {boxMinusSphere(48, 0), boxMinusSphere(48, 1),
                                                 boxMinusSphere(48, 2)};
  const auto expectCpuSplats = [&](const ResultPtr& r, int variant) {
    reference.request(scenes[variant], 48, false, 1);
    ASSERT_TRUE(reference.waitUntilIdle(kJobTimeout));
    ResultPtr expected = reference.takeResult();
    ASSERT_TRUE(expected && expected->ok());
    EXPECT_EQ(expected->resolution, r->resolution);
    EXPECT_TRUE(sameSplats(*r->splats, *expected->splats))
        << "variant " << variant << ": " << r->splats->count() << " splats against "
        << expected->splats->count();
  };

  // Coarse, then full: the coarse result holds the one region while the full one is copied (into
  // the worker's arrays), and gives it back on the worker's thread when the full one replaces it.
  worker.request(scenes[0], 48, false, 1);
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  ResultPtr full = worker.takeResult();
  ASSERT_TRUE(full && full->ok()) << (full ? full->error : "no result");
  EXPECT_FALSE(full->coarse);
  EXPECT_FALSE(lender->owns(full->splats->hostData())) << "no region was free";
  EXPECT_EQ(lender->lends(), 1u);
  EXPECT_EQ(lender->givenBack(), 1u);
  expectCpuSplats(full, 0);

  // A full pass with the region free: copied into it.
  worker.request(scenes[1], 48, false, 2);
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  ResultPtr lent = worker.takeResult();
  ASSERT_TRUE(lent && lent->ok()) << (lent ? lent->error : "no result");
  EXPECT_TRUE(lender->owns(lent->splats->hostData()));
  expectCpuSplats(lent, 1);
  lent.reset();  // given back on this thread
  EXPECT_EQ(lender->givenBack(), lender->lends());

  // Requests in a burst: cancelled passes, results replaced before they were taken.
  for (int k = 0; k < 8; ++k) worker.request(scenes[k % 3], 48, false, 10 + k);
  ASSERT_TRUE(worker.waitUntilIdle(kJobTimeout));
  ResultPtr last = worker.takeResult();
  ASSERT_TRUE(last && last->ok()) << (last ? last->error : "no result");
  EXPECT_EQ(last->tag, 17u);
  last.reset();
  EXPECT_EQ(lender->givenBack(), lender->lends()) << "every region lent came back";
}

}  // namespace
}  // namespace strata::test
