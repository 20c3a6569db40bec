#include "engine/jobs/preview_worker.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <optional>
#include <vector>

#include "engine/document/measurement.h"
#include "engine/eval/cpu_backend.h"
#include "engine/jobs/background_job.h"
#include "engine/util/error.h"
#include "engine/util/limits.h"
#include "engine/util/thread_priority.h"
#include "engine/util/timer.h"

namespace strata {

int previewResolutionFor(int requested, int shownResolution, uint64_t shownCacheBytes,
                         double shownSeconds, uint64_t availableBytes) {
  if (shownResolution <= 0 || shownCacheBytes == 0)
    return availableBytes == 0 ? requested : std::min(requested, kSliderMaxResolution);
  const double shownSquare = double(shownResolution) * shownResolution;
  double cap = double(kMaxResolution);
  if (availableBytes > 0)
    cap = std::min(cap, std::sqrt(double(availableBytes) / 4.0 / (shownCacheBytes / shownSquare)));
  if (requested > kSliderMaxResolution && shownSeconds > 0.0)
    cap = std::min(cap, std::max(double(kSliderMaxResolution),
                                 std::sqrt(kPreviewSeconds / (shownSeconds / shownSquare))));
  return std::max(std::min(requested, kMinResolution), std::min(requested, int(cap)));
}

PreviewWorker::PreviewWorker(std::shared_ptr<Backend> backend, int coarseResolution,
                             std::function<void()> onResult, double quickPassSeconds,
                             double moveGhostAfterSeconds, double settleSeconds)
    : backend_(std::move(backend)),
      backendDescription_(backend_->description()),
      coarse_(std::max(coarseResolution, 8)),
      quickPassSeconds_(quickPassSeconds),
      onResult_(std::move(onResult)),
      moveGhostAfterSeconds_(moveGhostAfterSeconds),
      settleSeconds_(settleSeconds) {
  thread_ = std::thread([this] { run(); });
}

PreviewWorker::~PreviewWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    hasRequest_ = false;
    settling_.reset();
    if (running_) running_->cancel();
    if (ghostsRunning_) ghostsRunning_->cancel();
  }
  wake_.notify_all();
  thread_.join();
}

void PreviewWorker::request(std::shared_ptr<const Scene> scene, int resolution, bool interactive,
                            uint64_t tag, std::vector<NodeId> ghosts, std::vector<NodeId> edited) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = Request{std::move(scene),  resolution,       interactive, tag,
                       std::move(ghosts), std::move(edited)};
    hasRequest_ = true;
    // A drag's newer position does not cancel the draft of an earlier one: that draft finishes
    // and shows (the parts its lattice did not hold yet now cached), then the newest position
    // is taken. Cancelling each draft in turn left a drag with no image until the hand stopped
    // wherever a draft took longer than the next move (an artist's 100 armadillos at 128 cells:
    // "start 0%" through the whole drag, 5-10 ms a draft once the pattern was cached).
    if (running_ && !(interactive && runningInteractive_)) running_->cancel();
  }
  wake_.notify_all();
}

void PreviewWorker::cancel() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    hasRequest_ = false;
    pending_ = Request{};
    settling_.reset();
    if (running_) running_->cancel();
    if (ghostsRunning_) ghostsRunning_->cancel();
  }
  wake_.notify_all();  // a settling wait ends
  idle_.notify_all();
}

std::shared_ptr<const PreviewResult> PreviewWorker::takeResult() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::move(finished_);
}

PreviewStatus PreviewWorker::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

bool PreviewWorker::waitUntilIdle(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  return idle_.wait_for(lock, timeout, [this] { return !hasRequest_ && !running_ && !settling_; });
}

std::optional<PreviewWorker::Request> PreviewWorker::settlingPass(const Request& request,
                                                                  const Progress& progress) const {
  if (request.interactive || request.ownLattice || progress.cancelled() || !request.scene ||
      !request.scene->root || settleSeconds_ < 0.0)
    return std::nullopt;
  // Its full pass was the last result published, and it succeeded.
  if (lastShown_ != request.scene || shownFullResolution_ != request.resolution)
    return std::nullopt;
  const auto last = lastGrids_.find(request.resolution);
  if (last == lastGrids_.end()) return std::nullopt;
  try {
    if (last->second == Evaluator::previewGridFor(*request.scene, request.resolution, nullptr))
      return std::nullopt;
  } catch (...) {
    return std::nullopt;  // the pass said it already
  }
  Request settle = request;
  settle.ownLattice = true;
  settle.edited.clear();
  return settle;
}

void PreviewWorker::run() {
  lowerThisThreadPriority();  // the UI (and a software GL driver) first: thread_priority.h
  Evaluator evaluator(backend_);
  for (;;) {
    Request request;
    std::shared_ptr<Progress> progress;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      // A settling pass waits for the hand to rest: a request meanwhile replaces it.
      if (settling_) {
        wake_.wait_for(lock, std::chrono::duration<double>(settleSeconds_),
                       [this] { return stopping_ || hasRequest_ || !settling_; });
        if (settling_ && !hasRequest_) request = std::move(*settling_);
        settling_.reset();
      }
      if (!request.scene) {
        wake_.wait(lock, [this] { return stopping_ || hasRequest_; });
        if (stopping_) return;
        request = std::move(pending_);
        pending_ = Request{};
        hasRequest_ = false;
      }
      if (stopping_) return;
      // Taken and cancellable in one step: request() and cancel() reach it from now on.
      progress = std::make_shared<Progress>([this](const std::string& stage, double fraction) {
        std::lock_guard<std::mutex> guard(mutex_);
        status_.stage = stage;
        status_.fraction = fraction;
      });
      running_ = progress;
      runningInteractive_ = request.interactive;
      status_ = PreviewStatus{true, "start", 0.0, 0, false, Grid()};
    }
    serve(evaluator, request, *progress);
    std::optional<Request> settle = settlingPass(request, *progress);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      running_.reset();
      status_ = PreviewStatus{};
      if (!hasRequest_ && !stopping_) settling_ = std::move(settle);
    }
    idle_.notify_all();
  }
}

int draftResolutionFor(int full, int coarse, int measuredResolution, double measuredSeconds,
                       double budgetSeconds) {
  const int coarsest = std::min(full, coarse);
  if (measuredSeconds < 0.0 || measuredResolution <= 0) return coarsest;
  for (const int divisor : {1, 2, 4}) {
    const int r = full / divisor;
    if (r <= coarsest) break;
    const double scale = double(r) / measuredResolution;
    if (measuredSeconds * scale * scale < budgetSeconds) return r;
  }
  return coarsest;
}

int dragResolutionFor(int full, int coarse, const std::map<int, double>& dragSeconds,
                      double predictedFullSeconds, double budgetSeconds) {
  if (dragSeconds.empty())
    return draftResolutionFor(full, coarse, full, predictedFullSeconds, budgetSeconds);
  const auto [finestResolution, finestSeconds] = *dragSeconds.rbegin();
  const int coarsest = std::min(full, coarse);
  for (const int divisor : {1, 2, 4}) {
    const int r = full / divisor;
    if (r <= coarsest) break;
    const auto own = dragSeconds.find(r);
    const double scale = double(r) / finestResolution;
    const double seconds = own != dragSeconds.end() ? own->second : finestSeconds * scale * scale;
    if (seconds < budgetSeconds) return r;
  }
  return coarsest;
}

void PreviewWorker::serve(Evaluator& evaluator, const Request& request, Progress& progress) {
  const int full = request.resolution;
  // What a pass at `full` would cost: the larger of what the last pass that computed every node
  // (a drag of the resolution slider computes everything anew) and the last full pass (a scene
  // grown since) predict.
  double predicted = -1.0;
  for (const auto& [seconds, resolution] : {std::pair(wholeSeconds_, wholeResolution_),
                                            std::pair(lastFullSeconds_, lastFullResolution_)})
    if (seconds >= 0.0 && resolution > 0)
      predicted = std::max(predicted, seconds * std::pow(double(full) / resolution, 2.0));
  const int coarse = draftResolutionFor(full, coarse_, full, predicted, quickPassSeconds_);
  if (request.interactive) {
    std::map<int, double> trusted;
    const auto now = std::chrono::steady_clock::now();
    for (const auto& [resolution, cost] : dragCosts_)
      if (cost.seconds < quickPassSeconds_ ||
          std::chrono::duration<double>(now - cost.at).count() < kDragVerdictSeconds)
        trusted[resolution] = cost.seconds;
    const int drag = dragResolutionFor(full, coarse_, trusted, predicted, quickPassSeconds_);
    evaluatePass(evaluator, request, drag, drag < full, progress);
    return;
  }
  // A coarse pass first, unless the coarse result of this very snapshot is already shown (the
  // hand just stopped) or there is nothing coarser. A request that arrives meanwhile cancels
  // `progress`, and with it the refinement.
  // Nor when the last full pass was quick: the full result follows at once, and a coarse one
  // first would only cost a frame (on a GPU the edit then reaches the screen a frame later).
  const bool quick = lastFullSeconds_ >= 0.0 && lastFullSeconds_ < quickPassSeconds_;
  // Nor when the full result shown has the same parts (the preview's resolution raised, the
  // grid's margin changed): its image stays until the new full one; a coarse pass showed the
  // parts at 96 cells, porous, for the whole 13 s of a 768-cell pass (an artist's test).
  const bool sameParts = request.scene && shownRoot_ && request.scene->root == shownRoot_ &&
                         shownFullResolution_ >= coarse;
  if (coarse < full && lastShown_ != request.scene && !quick && !sameParts) {
    // What the cache holds whole comes at once: no coarse image of an unchanged part.
    if (evaluatePass(evaluator, request, full, false, progress, true)) return;
    if (!evaluatePass(evaluator, request, coarse, true, progress)) return;
  }
  evaluatePass(evaluator, request, full, false, progress);
}

bool PreviewWorker::evaluatePass(Evaluator& evaluator, const Request& request, int resolution,
                                 bool coarse, Progress& progress, bool onlyIfCached) {
  if (progress.cancelled()) return false;  // superseded before it began
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_ = PreviewStatus{true, "start", 0.0, resolution, false, Grid(), request.ownLattice};
  }
  auto result = std::make_shared<PreviewResult>();
  result->tag = request.tag;
  result->scene = request.scene;
  result->resolution = resolution;
  result->coarse = coarse;
  try {
    if (!computePass(evaluator, request, progress, *result, onlyIfCached)) return false;
  } catch (const Cancelled&) {
    return false;
  } catch (...) {
    if (onlyIfCached) return false;  // the full pass says it
    result->error = jobErrorText(std::current_exception(), "; lower the resolution");
  }
  lastShown_ = request.scene;
  shownRoot_ = request.scene ? request.scene->root : nullptr;
  shownFullResolution_ = coarse || !result->error.empty() ? 0 : resolution;
  // What a pass that computes costs (one served from the cache says nothing of the next).
  const double passSeconds = result->stats.seconds + result->splatSeconds;
  const bool measured = result->error.empty() && !onlyIfCached;
  if (measured && !coarse) {
    lastFullSeconds_ = passSeconds;
    lastFullResolution_ = resolution;
  }
  // A drag's pass that found parts in the cache: what the next frames of a drag cost there (a
  // first pass at a resolution, computing every part, says nothing of them).
  if (measured && request.interactive && result->stats.reused > 0)
    dragCosts_[resolution] = DragCost{passSeconds, std::chrono::steady_clock::now()};
  if (measured && result->stats.reused == 0 && result->stats.computed > 0) {
    wholeSeconds_ = passSeconds;
    wholeResolution_ = resolution;
  }
  // The ghosts shown from now on: this result's (a ghost still to finish: as last shown, or
  // moved with its part, with what it was made from).
  lastGhosts_ = std::move(passGhosts_);
  passGhosts_.clear();
  const bool ghostsToFinish = !deferredGhosts_.empty() && result->error.empty();
  std::shared_ptr<const PreviewResult> published = result;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    finished_ = std::move(result);
  }
  if (onResult_) onResult_();
  if (ghostsToFinish)
    finishGhosts(request, published);
  else if (deferredGhosts_.empty())
    ghostEvaluators_.clear();  // no ghost evaluated alone any more
  deferredGhosts_.clear();
  return true;
}

void PreviewWorker::setHostSplatLender(std::shared_ptr<HostSplatLender> lender) {
  std::lock_guard<std::mutex> lock(mutex_);
  lender_ = std::move(lender);
}

Grid ghostWindow(const Scene& scene, NodeId id, const Grid& grid) {
  const NodePtr node = findNode(scene.root, id);
  if (!node) return grid;
  const Bounds content = nodeBounds(node, scene.root, parentWorldMatrix(scene.root, id));
  if (content.empty()) return grid;
  if (withinWithRoom(content, grid)) return grid;
  // A modifier's work grows with its window's nodes (up to 27 times the grid's here): its ghost
  // stays on the result's grid.
  if (hasModifier(node)) return grid;
  // The lattice's origin moved `shift` nodes back (the grid's first node may be 0), a power of
  // two from the grid's size, so that it stays put while the scene's window changes a little
  // (the ghost's cache is keyed on its lattice): node i of `grid` is node i + shift there.
  const int reach = std::max(grid.cells.x, std::max(grid.cells.y, grid.cells.z));
  int shift = 1;
  while (shift < reach) shift *= 2;
  Grid shifted = grid;
  shifted.origin -= glm::dvec3(shift) * grid.h;
  glm::ivec3 start, cells;
  for (int a = 0; a < 3; ++a) {
    double lo = std::floor((content.min[a] - shifted.origin[a]) / grid.h) - kGuardCells;
    double hi = std::ceil((content.max[a] - shifted.origin[a]) / grid.h) + kGuardCells;
    lo = std::max(lo, double(grid.first[a] + shift - reach));
    hi = std::min(hi, double(grid.first[a] + shift + grid.cells[a] + reach));
    if (!(hi - lo >= 1.0)) return grid;  // none of it within reach (or not finite)
    start[a] = int(lo);
    cells[a] = int(hi - lo);
  }
  // No finer than kGhostMaxCells along its longest side: every other node of the lattice (and so
  // on), the window widened to whole coarse cells. A translucent ghost needs no more, and its
  // rays grow with the window's area: a box cutting half a part, reaching far beyond it, took as
  // long again as the part's own pass at 1024 cells (an artist's test).
  while (std::max(cells.x, std::max(cells.y, cells.z)) > kGhostMaxCells) {
    shifted.h *= 2.0;
    for (int a = 0; a < 3; ++a) {
      const int end = start[a] + cells[a];
      start[a] /= 2;  // >= 0: floor
      cells[a] = (end + 1) / 2 - start[a];
    }
  }
  return shifted.window(start, cells);
}

// The splats of a ghost's LDI, on the host (few; the UI uploads them).
static std::shared_ptr<const HostSplats> hostGhost(Backend& backend, const LdiHandle& ldi,
                                                   Progress& progress) {
  SplatsHandle ghost = backend.splats(ldi, progress);
  std::vector<Splat> host(ghost->count());
  if (!host.empty()) ghost->copyToHost(host.data());
  return std::make_shared<HostSplats>(std::move(host));
}

PreviewWorker::ShownGhost PreviewWorker::movedGhost(const ShownGhost& shown,
                                                    const glm::dmat4& world) {
  if (world == shown.world || !shown.splats) return shown;  // not moved (a turned part's
  // inverse would leave a rounding's move: a copy for nothing)
  const glm::dmat4 motion = world * glm::inverse(shown.world);
  bool turned = false;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      turned = turned || std::fabs(motion[c][r] - (c == r ? 1.0 : 0.0)) > 1e-12;
  const glm::dvec3 move(motion[3]);
  const double reach =
      1.0 + glm::length(glm::dvec3(world[3])) + glm::length(glm::dvec3(shown.world[3]));
  if (turned || !(glm::length(move) > 1e-12 * reach)) return shown;
  // Moved only: the same splats, moved by as much (until its own LDI is evaluated).
  std::vector<Splat> splats = shown.splats->splats();
  for (Splat& splat : splats)
    for (int a = 0; a < 3; ++a) splat.position[a] = float(double(splat.position[a]) + move[a]);
  return ShownGhost{
      std::make_shared<HostSplats>(std::move(splats)), false, 0, Grid(), world, shown.h};
}

bool PreviewWorker::finishGhosts(const Request& request,
                                 const std::shared_ptr<const PreviewResult>& shown) {
  // Cancelled by stop and cancel(), not by a newer request: that one is served next, with these
  // ghosts' evaluators warm (an edit's result is shown before its ghosts, and a drag's ghosts
  // still follow the hand). Its progress is the status's stage "ghosts", over all of them (the
  // status kept "evaluate 100%" through half a minute of a 1024-cell ghost: an artist's test).
  std::atomic<size_t> ghostsDone{0};  // read by the progress on the evaluation's threads
  const double ghostCount = double(std::max<size_t>(deferredGhosts_.size(), 1));
  auto progress =
      std::make_shared<Progress>([this, &ghostsDone, ghostCount](const std::string&, double f) {
        std::lock_guard<std::mutex> guard(mutex_);
        status_.stage = "ghosts";
        status_.fraction = (double(ghostsDone.load()) + std::clamp(f, 0.0, 1.0)) / ghostCount;
      });
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // Stopping, or cancel() since this pass began (a newer request() cancels it too, but leaves
    // one pending).
    if (stopping_ || (running_ && running_->cancelled() && !hasRequest_)) return false;
    ghostsRunning_ = progress;
  }
  // By an evaluator of their own each (sharing the main one's cache would evaluate their leaves
  // on one window and then the other on every pass; one for all ghosts would drop one ghost's
  // LDIs while evaluating the next: an evaluation keeps what it and the one before used).
  std::map<NodeId, GhostEvaluator> kept;
  auto result = std::make_shared<PreviewResult>(*shown);
  bool finished = true, changed = false;
  Stopwatch clock;
  for (const DeferredGhost& deferred : deferredGhosts_) {
    ghostsDone = size_t(&deferred - deferredGhosts_.data());
    auto found = ghostEvaluators_.find(deferred.id);
    GhostEvaluator& ghost = kept[deferred.id];
    if (found != ghostEvaluators_.end() && found->second.backend == deferred.backend)
      ghost = std::move(found->second);
    try {
      if (!ghost.evaluator) {
        ghost.backend = deferred.backend;
        ghost.evaluator = std::make_unique<Evaluator>(
            deferred.onCpu ? std::shared_ptr<Backend>(std::make_shared<CpuBackend>()) : backend_);
      }
      EvalOptions options = ghostOptions_;
      options.alone = deferred.id;
      const EvalResult evaluated =
          ghost.evaluator->evaluateOn(*request.scene, deferred.window, *progress, options);
      auto place = std::find_if(result->ghosts.begin(), result->ghosts.end(),
                                [&](const GhostSplats& g) { return g.id == deferred.id; });
      // The ghost shown stands where it was made from this very LDI (its key on this window: an
      // edit elsewhere, a rename); not merely where nothing was computed (the cache also holds
      // the state before last, which an undo comes back to).
      auto shownGhost = lastGhosts_.find(deferred.id);
      if (place != result->ghosts.end() && shownGhost != lastGhosts_.end() &&
          shownGhost->second.splats == place->splats && shownGhost->second.alone &&
          shownGhost->second.key == evaluated.rootKey &&
          shownGhost->second.window == deferred.window)
        continue;
      auto splats = hostGhost(ghost.evaluator->backend(), evaluated.root, *progress);
      lastGhosts_[deferred.id] = ShownGhost{splats,
                                            true,
                                            evaluated.rootKey,
                                            deferred.window,
                                            nodeWorldMatrix(request.scene->root, deferred.id),
                                            deferred.window.h};
      changed = true;
      if (place != result->ghosts.end()) {
        place->splats = std::move(splats);
        place->h = deferred.window.h;
      } else
        result->ghosts.push_back(GhostSplats{deferred.id, std::move(splats), deferred.window.h});
    } catch (const Cancelled&) {  // the result stands as published
      finished = false;
      break;
    } catch (...) {  // this ghost not drawn (its window's memory): the others still are, and said
      // Not the one carried either (stale, or moved from where it was).
      result->ghosts.erase(
          std::remove_if(result->ghosts.begin(), result->ghosts.end(),
                         [&](const GhostSplats& g) { return g.id == deferred.id; }),
          result->ghosts.end());
      lastGhosts_.erase(deferred.id);
      const NodePtr node = findNode(request.scene->root, deferred.id);
      result->stats.warnings.push_back(
          "the ghost of " + (node ? nodeLabel(*node) : std::string("a part")) +
          " is not drawn: " + jobErrorText(std::current_exception(), ""));
      changed = true;
    }
  }
  // Kept: the evaluators of this pass's ghosts (those not reached, where cancelled, as they
  // were); those of ghosts no longer evaluated alone go.
  for (const DeferredGhost& deferred : deferredGhosts_) {
    auto found = ghostEvaluators_.find(deferred.id);
    if (!kept.count(deferred.id) && found != ghostEvaluators_.end() && found->second.evaluator)
      kept[deferred.id] = std::move(found->second);
  }
  ghostEvaluators_ = std::move(kept);
  if (finished && changed) ghostSeconds_ = clock.seconds();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ghostsRunning_.reset();
    if (finished && changed) finished_ = result;
  }
  if (finished && changed && onResult_) onResult_();
  return finished && changed;
}

bool PreviewWorker::computePass(Evaluator& evaluator, const Request& request, Progress& progress,
                                PreviewResult& result, bool onlyIfCached) {
  EvalOptions options;
  options.resolution = result.resolution;
  options.keep = request.ghosts;
  options.skipModifiersUnderCells = result.coarse ? kCoarseModifierCells : 0.0;
  options.applyModifiers = request.edited;
  if (!request.scene->root) throw Error("the scene has no root node");
  auto last = lastGrids_.find(result.resolution);
  const Grid grid = Evaluator::previewGridFor(
      *request.scene, result.resolution,
      last == lastGrids_.end() || request.ownLattice ? nullptr : &last->second);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.busy && status_.resolution == result.resolution) {
      status_.gridKnown = true;
      status_.grid = grid;
    }
  }
  // Modifiers on a backend that cannot evaluate them: this pass on the CPU (its own evaluator,
  // so that each cache keeps LDIs of its own backend).
  Backend* backend = backend_.get();
  Evaluator* used = &evaluator;
  if (hasModifier(request.scene->root) && !backend_->evaluatesModifiers()) {
    if (!modifierEvaluator_)
      modifierEvaluator_ = std::make_unique<Evaluator>(std::make_shared<CpuBackend>());
    used = modifierEvaluator_.get();
    backend = &modifierEvaluator_->backend();
  }
  if (onlyIfCached) {
    std::optional<EvalResult> cached =
        used->evaluateCached(*request.scene, grid, progress, options);
    if (!cached) return false;
    result.stats = std::move(*cached);
  } else {
    result.stats = used->evaluateOn(*request.scene, grid, progress, options);
  }
  lastGrids_[result.resolution] = grid;
  if (used != &evaluator)
    result.stats.warnings.push_back(
        "offset, shell, round and fillet nodes are evaluated on the CPU (the " +
        backend_->description() + " backend cannot yet)");
  Stopwatch splatClock;
  result.surfels = result.stats.root->surfelCount();
  result.ldiBytes = result.stats.root->bytes();
  // The splats shown now, where this is their root on their grid (made by the same backend,
  // delivered the same way): the same handle, so the UI keeps its image.
  SplatsHandle splats;
  if (!result.coarse && lastRoot_.key == result.stats.rootKey && lastRoot_.grid == grid &&
      lastRoot_.backend == backend)
    splats = lastRoot_.splats.lock();
  if (splats && hostSplats_ && !splats->hostData()) splats.reset();  // now wanted on the host
  if (!splats) {
    splats = backend->splats(result.stats.root, progress);
    if (hostSplats_ && !splats->hostData()) {
      std::shared_ptr<HostSplatLender> lender;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        lender = lender_;
      }
      std::shared_ptr<LentHostSplats> lent =
          lender ? lender->lend(splats->count(), splats->levels()) : nullptr;
      if (lent) {
        splats->copyToHost(lent->writableData());
        splats = std::move(lent);
      } else {
        std::vector<Splat> host = splatArrays_->take(splats->count());
        splats->copyToHost(host.data());
        splats = std::make_shared<HostSplats>(std::move(host), splats->levels(), splatArrays_);
      }
    }
  }
  result.stats.root.reset();  // the cache keeps what it needs; the UI needs only the splats
  if (!result.coarse) lastRoot_ = ShownRoot{result.stats.rootKey, grid, backend, splats};
  result.splats = std::move(splats);
  // A ghost within the result's grid comes from the LDI the evaluation kept. One that reaches
  // beyond it (a cutter sticking out of its part: the grid covers the part, not its cutters) is
  // evaluated alone on a window of the same lattice that covers it, after this result is shown
  // (finishGhosts): meanwhile the result carries the ghost last shown of that node, if any.
  deferredGhosts_.clear();
  passGhosts_.clear();
  for (KeptLdi& kept : result.stats.kept) {
    const Grid own = ghostWindow(*request.scene, kept.id, grid);
    const glm::dmat4 world = nodeWorldMatrix(request.scene->root, kept.id);
    if (!(own == grid)) {
      deferredGhosts_.push_back(DeferredGhost{kept.id, own, backend, used != &evaluator});
      auto last = lastGhosts_.find(kept.id);
      if (last != lastGhosts_.end()) {
        // Moved with its part where ghosts take a while to come (a copy of every splat: where
        // they come within a frame, the one last shown stands until then).
        ShownGhost shown = ghostSeconds_ >= moveGhostAfterSeconds_ ? movedGhost(last->second, world)
                                                                   : last->second;
        result.ghosts.push_back(GhostSplats{kept.id, shown.splats, shown.h});
        passGhosts_[kept.id] = std::move(shown);
      }
      kept.ldi.reset();
      continue;
    }
    auto splats = hostGhost(*backend, kept.ldi, progress);
    result.ghosts.push_back(GhostSplats{kept.id, splats, grid.h});
    passGhosts_[kept.id] = ShownGhost{std::move(splats), false, 0, Grid(), world, grid.h};
    kept.ldi.reset();
  }
  result.stats.kept.clear();
  ghostOptions_ = EvalOptions{};
  ghostOptions_.measureRoot = false;
  ghostOptions_.skipModifiersUnderCells = options.skipModifiersUnderCells;
  result.splatSeconds = splatClock.seconds();
  return true;
}

}  // namespace strata
