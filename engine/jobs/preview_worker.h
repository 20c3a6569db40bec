// The preview worker (the editor's engine thread): evaluates scene snapshots in the background
// so that the UI never waits on the engine (libfive Studio's scheduling).
//
//   - The caller hands immutable snapshots (std::shared_ptr<const Scene>) with the requested
//     resolution; only the latest request survives, and a new one cancels the running
//     evaluation (Progress::cancel), except that a drag's request lets a drag's running draft
//     finish (each draft shows, the next takes the newest position). Requests replaced before
//     the worker took them are never evaluated.
//   - An interactive request (the user is dragging) is evaluated only at a draft resolution
//     (dragResolutionFor: the finest of requested, requested/2, requested/4 that the drag's own
//     passes so far, or before its first, the last full pass and the last pass that computed
//     every node predict under quickPassSeconds, never under coarseResolution; on a GPU a drag
//     is often evaluated in full); the request made when
//     the hand stops refines it. A calm request for a new scene shows the draft result first, then
//     the full one, unless the last full pass took less than quickPassSeconds (then the full one
//     comes at once). A calm request whose full result the cache holds whole (an edit that changed
//     no part: a measurement, a name) skips the coarse pass, and where its root is the one shown
//     its result carries the same splats (the UI keeps its image). Nor does a calm request
//     whose parts are those of the full result shown (only the resolution or the grid changed):
//     that image stays until the new full one, a coarse pass would show the same parts worse.
//     A coarse pass passes modifiers
//     under kCoarseModifierCells of its cells through (EvalOptions::skipModifiersUnderCells): it
//     shows the parts whole, unrounded, rather than torn by a radius its cells cannot resolve, and
//     comes sooner; but not the modifiers being edited (request's `edited`), whose amount a drag
//     must show.
//   - Results are finished, immutable values (std::shared_ptr<const PreviewResult>): the root's
//     splats (Backend::splats: made where the backend keeps its LDIs, on the device for CUDA)
//     and the evaluation's statistics. A pass that finished before it was superseded still
//     delivers its result; a cancelled pass delivers none. Where the caller cannot take device
//     splats it says so (setHostSplats(true), the default) and the worker copies them to the
//     host first: into memory the caller lends (setHostSplatLender: the editor's mapped GL
//     buffers, which the UI then copies from on the GPU) where it has a region free, else into
//     arrays of its own.
//   - Ghosts (the splats of cutters' and intersectors' own LDIs, PreviewResult::ghosts) come
//     with the result where they lie within its grid. One that reaches beyond it is evaluated
//     alone on a window of its own (ghostWindow) after the result is published, which then
//     carries that node's ghost as last shown (moved with the node where it only moved and
//     ghosts take a while: the constructor's moveGhostAfterSeconds); a copy of the result with
//     the new ghost follows (same splats: the UI keeps its image). A newer request waits for it
//     (so that a drag's ghosts follow the hand); stop and cancel() end it.
//   - At rest, the lattice of the export: a calm request's full pass follows the lattice of the
//     last one (Evaluator::previewGridFor keeps it while the scene's size changes a little, so
//     that an edit keeps the LDIs of the parts it left alone); where that is not the scene's own
//     lattice (the one gridFor, and so `strata export` at that resolution and a reopened
//     document, samples), the same request is evaluated again on its own lattice once no newer
//     request has come for `settleSeconds`, and published. The image at rest is what the export
//     at that resolution samples (a preview on a kept lattice showed a strut a reopen lost).
//   - Nothing here draws (no GL): ui/ uploads the splats or copies them through CUDA-GL
//     interop. The worker catches everything and reports it in the result's `error`.
//
// Threads: request(), cancel(), takeResult(), status(), waitUntilIdle(), setHostSplats() and
// setHostSplatLender() from any thread, never blocking for longer than a mutex hand-over (but
// waitUntilIdle). Construct and destroy on the owning thread, never from inside onResult.
// Evaluation runs on the worker's own thread, which owns the Evaluator and its cache and is the
// only user of the backend.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "engine/document/scene.h"
#include "engine/eval/evaluator.h"
#include "engine/ldi/lent_splats.h"
#include "engine/ldi/splats.h"
#include "engine/util/progress.h"

namespace strata {

// The splats of one node's own LDI (a cutter, an intersector), drawn as a translucent ghost.
struct GhostSplats {
  NodeId id = 0;
  std::shared_ptr<const HostSplats> splats;  // always on the host (few; drawn by upload)
  // The cell size of the lattice they were made on (scene units): drawn with splats of that
  // size (a ghost carried from a coarse pass into a fine one was drawn as scattered dots).
  double h = 0.0;
};

// Modifiers whose amount is under this many cells of a coarse pass are left out of it.
constexpr double kCoarseModifierCells = 2.0;

struct PreviewResult {
  uint64_t tag = 0;                    // the caller's tag of the request (its document revision)
  std::shared_ptr<const Scene> scene;  // the snapshot it shows
  int resolution = 0;                  // cells along the longest side, as evaluated
  bool coarse = false;                 // a coarse pass; a finer one follows unless superseded
  SplatsHandle splats;                 // what the viewport draws; null on failure
  size_t surfels = 0;                  // in the root's LDI
  size_t ldiBytes = 0;                 // held by the root's LDI
  EvalResult stats;                    // stages, nodes, grid (its `root` handle released)
  double splatSeconds = 0.0;           // making the splats (and copying them to the host)
  std::vector<GhostSplats> ghosts;     // of the request's ghost ids that were evaluated
  std::string error;                   // empty on success

  size_t splatCount() const { return splats ? splats->count() : 0; }
  bool ok() const { return splats != nullptr; }
};

struct PreviewStatus {
  bool busy = false;       // a request is being evaluated
  std::string stage;       // of the running evaluation ("start", "evaluate", ...)
  double fraction = 0.0;   // of that stage
  int resolution = 0;      // of the running pass
  bool gridKnown = false;  // the running pass's grid is decided:
  Grid grid;               // that grid
  bool settling = false;   // the pass on the scene's own lattice, after an edit came to rest
};

// The resolution of a draft (a drag's, or a calm edit's first) pass when `full` is asked for:
// the finest of full, full/2 and full/4 whose time, scaled from what a pass took
// (`measuredSeconds` at `measuredResolution`; time grows with the square of the resolution), is
// under `budgetSeconds`; never under min(full, coarse) (the coarsest draft worth showing); that
// while nothing is measured (measuredSeconds < 0). A fixed ladder below `full`, so that drafts
// keep their lattice (and the cache its LDIs) from one drag to the next.
int draftResolutionFor(int full, int coarse, int measuredResolution, double measuredSeconds,
                       double budgetSeconds);

// The resolution of a drag's pass when `full` is asked for. Where passes of drags were measured
// (`dragSeconds`: resolution -> seconds of the last drag pass there that reused cached parts),
// the finest of full, full/2 and full/4 (never under min(full, coarse)) whose own measured time,
// or else the time scaled from the finest one measured, is under `budgetSeconds`: a drag costs
// what its part and the operations above it cost, not what a pass of every part did (a plate
// dragged at 256 cells was drafted at 96 cells, blocky, all the way on this 2-core machine: an
// artist's test). Nothing measured: draftResolutionFor from `predictedFullSeconds` (the cost at
// `full`, or < 0 for none).
int dragResolutionFor(int full, int coarse, const std::map<int, double>& dragSeconds,
                      double predictedFullSeconds, double budgetSeconds);

// The resolution a preview is evaluated at when `requested` is asked for. The preview evaluates
// the whole grid at once (no tiles): a resolution typed far past the slider must neither take
// all memory nor keep the preview busy for minutes (exports tile, and estimate first). Scaled
// from the last result shown (`shownResolution`; its LDIs held `shownCacheBytes` and took
// `shownSeconds`; both grow with the square of the resolution):
//   - memory: at most a quarter of `availableBytes` (what the system has; 0 = unknown: no cap),
//     a margin for the transient buffers of sampling and Booleans;
//   - time, above kSliderMaxResolution only (the slider's range is always honoured): at most
//     kPreviewSeconds.
// With nothing shown yet, at most kSliderMaxResolution until a result tells the scene's cost.
constexpr int kSliderMaxResolution = 1024;
constexpr double kPreviewSeconds = 5.0;
int previewResolutionFor(int requested, int shownResolution, uint64_t shownCacheBytes,
                         double shownSeconds, uint64_t availableBytes);

// The grid the ghost of node `id` is drawn from: `grid` itself where the node lies within it
// with kGuardCells to spare (or is not in `scene`, or holds a modifier, whose work grows with a
// window's nodes), else a window covering the node with kGuardCells of room, up to the grid's
// longest side beyond the grid on every side (a cutter far longer than its part shows that much
// of it: a ghost's rays grow with its window's area), on `grid`'s lattice with its origin moved
// back by a power of two at least that long (nodes at the same places; the window never starts
// below node 0, and the lattice stays while the grid's size changes within a factor of two).
// Such a window is at most kGhostMaxCells along its longest side: past that, its lattice keeps
// every second node (every fourth, ...) of `grid`'s, its cell size `grid.h` times a power of two.
constexpr int kGhostMaxCells = 512;
Grid ghostWindow(const Scene& scene, NodeId id, const Grid& grid);

class PreviewWorker {
 public:
  // `backend` is used by the worker thread alone from now on. `onResult`, when given, is called
  // on the worker thread each time a result is ready (e.g. to wake the UI's event loop); it may
  // call takeResult().
  // A ghost beyond the grid carried until its own is evaluated is moved with its part where the
  // last ghosts took at least `moveGhostAfterSeconds` (0: always). A result on a kept lattice is
  // evaluated again on the scene's own once no request has come for `settleSeconds`.
  explicit PreviewWorker(std::shared_ptr<Backend> backend, int coarseResolution = 96,
                         std::function<void()> onResult = {}, double quickPassSeconds = 0.05,
                         double moveGhostAfterSeconds = 0.02, double settleSeconds = 1.0);
  ~PreviewWorker();  // cancels the running evaluation, drops the pending one, and joins
  PreviewWorker(const PreviewWorker&) = delete;
  PreviewWorker& operator=(const PreviewWorker&) = delete;

  // Replaces any pending request and cancels the running one. The result carries the splats of
  // each of `ghosts`' own LDIs (visible nodes only).
  // `edited`: the nodes being edited (the selection): a coarse pass applies their modifiers
  // whatever its cells (EvalOptions::applyModifiers), so that a drag on an amount shows it.
  void request(std::shared_ptr<const Scene> scene, int resolution, bool interactive, uint64_t tag,
               std::vector<NodeId> ghosts = {}, std::vector<NodeId> edited = {});
  // Drops the pending request and cancels the running one (e.g. nothing is left to show).
  void cancel();
  // The newest finished result not taken yet, or null.
  std::shared_ptr<const PreviewResult> takeResult();
  PreviewStatus status() const;
  // Blocks until no request is pending or being evaluated and no pass on the scene's own
  // lattice is due (the settle time and that pass included), or until `timeout` has passed;
  // returns whether the worker is idle. For tests and headless callers: the UI never waits.
  bool waitUntilIdle(std::chrono::milliseconds timeout);
  // Whether results must carry host splats (default) or may keep them where the backend made
  // them (the UI copies device splats through CUDA-GL interop).
  void setHostSplats(bool host) { hostSplats_ = host; }
  // Where host copies of device splats go first (null: the worker's own arrays), from the next
  // pass on. The worker holds it (and a pass in flight may still lend from the one replaced).
  void setHostSplatLender(std::shared_ptr<HostSplatLender> lender);
  const std::string& backendDescription() const { return backendDescription_; }

 private:
  struct Request {
    std::shared_ptr<const Scene> scene;
    int resolution = 0;
    bool interactive = false;
    uint64_t tag = 0;
    std::vector<NodeId> ghosts;
    std::vector<NodeId> edited;
    bool ownLattice = false;  // on the scene's own lattice (the settling pass), not the last one
  };
  void run();
  // The settling pass due after `request` was served (a copy on the scene's own lattice), or
  // none: a drag's, a cancelled one, one on its own lattice already, one with an error.
  std::optional<Request> settlingPass(const Request& request, const Progress& progress) const;
  // Evaluates one request: its coarse pass where one applies, then its full pass.
  void serve(Evaluator& evaluator, const Request& request, Progress& progress);
  // Evaluates one pass and publishes its result; returns false when cancelled, or with
  // `onlyIfCached` when the cache does not hold the whole result (nothing computed then).
  bool evaluatePass(Evaluator& evaluator, const Request& request, int resolution, bool coarse,
                    Progress& progress, bool onlyIfCached = false);
  // The evaluation and splats of one pass into `result`; false where `onlyIfCached` and the
  // cache does not hold it (Evaluator::evaluateCached). Throws what the engine throws. Ghosts
  // that reach beyond the result's grid are left to finishGhosts (deferredGhosts_).
  bool computePass(Evaluator& evaluator, const Request& request, Progress& progress,
                   PreviewResult& result, bool onlyIfCached);
  // After `shown` was published: evaluates deferredGhosts_ and publishes a copy of `shown` with
  // them, unless none changed (each the LDI its shown ghost was made from: the same key on the
  // same window). A ghost that fails (its window's memory) is left out and said in the copy's
  // warnings. Cancelled by stop and cancel() only. Returns whether it published.
  bool finishGhosts(const Request& request, const std::shared_ptr<const PreviewResult>& shown);

  std::shared_ptr<Backend> backend_;
  std::string backendDescription_;
  int coarse_;
  double quickPassSeconds_;
  std::function<void()> onResult_;
  std::atomic<bool> hostSplats_{true};
  // The host copies' arrays, reused once their results are released (SplatArrayPool).
  std::shared_ptr<SplatArrayPool> splatArrays_ = std::make_shared<SplatArrayPool>();
  std::shared_ptr<HostSplatLender> lender_;       // guarded by mutex_
  std::unique_ptr<Evaluator> modifierEvaluator_;  // worker thread only: see computePass
  // Worker thread only: the ghosts evaluated alone on windows of their own (ghostWindow) in the
  // last pass, an evaluator each (on the backend of the pass: the worker's, or the CPU's beside
  // modifierEvaluator_).
  struct GhostEvaluator {
    const Backend* backend = nullptr;
    std::unique_ptr<Evaluator> evaluator;
  };
  std::map<NodeId, GhostEvaluator> ghostEvaluators_;
  // Worker thread only: the ghosts of the pass just computed that reach beyond its grid (the
  // window each is evaluated on, and on which backend: the pass's, or the CPU's), and the options
  // they are evaluated with.
  struct DeferredGhost {
    NodeId id = 0;
    Grid window;
    const Backend* backend = nullptr;
    bool onCpu = false;  // the pass ran on modifierEvaluator_'s CPU backend
  };
  std::vector<DeferredGhost> deferredGhosts_;
  EvalOptions ghostOptions_;
  // Worker thread only: the ghosts of the last result published, shown in the next result until
  // that one's are finished; of those evaluated alone, what they were made from (the evaluated
  // node's key on its window), so that a ghost made from the same LDI is not made again.
  struct ShownGhost {
    std::shared_ptr<const HostSplats> splats;
    bool alone = false;
    uint64_t key = 0;
    Grid window;
    glm::dmat4 world{1.0};  // the node's object-to-world matrix where its splats were made
    double h = 0.0;         // the cell size of their lattice
  };
  std::map<NodeId, ShownGhost> lastGhosts_;
  std::map<NodeId, ShownGhost> passGhosts_;  // the pass being computed's, for lastGhosts_
  // Worker thread only: how long the last finishGhosts that made ghosts took; a ghost carried is
  // moved with its part (movedGhost) only where that is at least moveGhostAfterSeconds_.
  double ghostSeconds_ = 0.0;
  double moveGhostAfterSeconds_;
  // A ghost last shown, for its node now at `world`: where the node only moved (no turn or
  // scale), its splats moved by as much (an old ghost over solid material stood where a moved
  // cutter had been until its own was evaluated); else as it was.
  static ShownGhost movedGhost(const ShownGhost& shown, const glm::dmat4& world);

  mutable std::mutex mutex_;
  std::condition_variable wake_;  // the worker: a request arrived, or stop
  std::condition_variable idle_;  // waitUntilIdle: nothing pending or running any more
  bool stopping_ = false;
  bool hasRequest_ = false;
  Request pending_;
  bool runningInteractive_ = false;  // the request being served is a drag's
  std::optional<Request> settling_;  // the settling pass due once settleSeconds_ pass
  double settleSeconds_;
  std::shared_ptr<Progress> running_;        // of the request being served; null when none
  std::shared_ptr<Progress> ghostsRunning_;  // of finishGhosts while it runs; null otherwise
  std::shared_ptr<const PreviewResult> finished_;
  PreviewStatus status_;
  std::shared_ptr<const Scene> lastShown_;  // worker thread only
  // The root of the last result published, and its resolution where it was a full pass (0 for a
  // coarse one or an error): a request with the same root (the resolution or the grid changed,
  // no part) keeps that image until its own full result. Worker thread only.
  NodePtr shownRoot_;
  int shownFullResolution_ = 0;
  double lastFullSeconds_ = -1.0;  // worker thread only: the last full pass; -1 none yet
  int lastFullResolution_ = 0;     // worker thread only: of that pass
  double wholeSeconds_ = -1.0;     // worker thread only: the last pass that computed every node
  int wholeResolution_ = 0;        // worker thread only: of that pass
  // Worker thread only: the last drag pass at each resolution that reused cached parts (its
  // seconds, and when it ended), for dragResolutionFor. Kept across drags and the calm requests
  // between them (a hand resting mid-drag refines in full); a verdict of "too slow" is trusted
  // for kDragVerdictSeconds, then that resolution is tried again (a busy moment of a 2-core
  // machine kept a drag coarse to its end: a review).
  struct DragCost {
    double seconds = 0.0;
    std::chrono::steady_clock::time_point at;
  };
  std::map<int, DragCost> dragCosts_;
  static constexpr double kDragVerdictSeconds = 2.0;
  // Worker thread only: the last grid of each resolution evaluated, which the next follows
  // (Evaluator::previewGridFor) so that the cache keeps what an edit left alone.
  std::map<int, Grid> lastGrids_;
  // Worker thread only: the last full pass's root (its key, grid and backend) and its splats,
  // while a result still holds them: a pass with the same root hands the same splats on (the
  // UI then keeps the image it shows) instead of making them again.
  struct ShownRoot {
    uint64_t key = 0;
    Grid grid;
    const Backend* backend = nullptr;
    std::weak_ptr<const SplatResource> splats;
  };
  ShownRoot lastRoot_;
  std::thread thread_;
};

}  // namespace strata
