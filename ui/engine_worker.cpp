#include "ui/engine_worker.h"

#include <algorithm>
#include <new>

#include "engine/util/error.h"
#include "engine/util/timer.h"

namespace strata::ui {

EngineWorker::EngineWorker(std::shared_ptr<Backend> backend, int coarseResolution,
                           std::function<void()> onResult)
    : backend_(std::move(backend)),
      backendDescription_(backend_->description()),
      coarse_(std::max(coarseResolution, 8)),
      onResult_(std::move(onResult)) {
  thread_ = std::thread([this] { run(); });
}

EngineWorker::~EngineWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    if (running_) running_->cancel();
  }
  wake_.notify_all();
  thread_.join();
}

void EngineWorker::request(std::shared_ptr<const Scene> scene, int resolution, bool interactive,
                           uint64_t tag) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = Request{std::move(scene), resolution, interactive, tag};
    hasRequest_ = true;
    if (running_) running_->cancel();
  }
  wake_.notify_all();
}

void EngineWorker::cancel() {
  std::lock_guard<std::mutex> lock(mutex_);
  hasRequest_ = false;
  if (running_) running_->cancel();
}

std::shared_ptr<const PreviewResult> EngineWorker::takeResult() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::move(finished_);
}

WorkerStatus EngineWorker::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

void EngineWorker::run() {
  Evaluator evaluator(backend_);
  for (;;) {
    Request request;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || hasRequest_; });
      if (stopping_) return;
      request = std::move(pending_);
      hasRequest_ = false;
    }
    const int full = request.resolution;
    const int coarse = std::min(full, coarse_);
    if (request.interactive) {
      evaluatePass(evaluator, request, coarse, coarse < full);
      continue;
    }
    // A coarse pass first, unless the coarse result of this very snapshot is already shown
    // (the hand just stopped) or there is nothing coarser.
    if (coarse < full && lastShown_ != request.scene) {
      if (!evaluatePass(evaluator, request, coarse, true)) continue;
      std::lock_guard<std::mutex> lock(mutex_);
      if (hasRequest_ || stopping_) continue;  // superseded: skip the refinement
    }
    evaluatePass(evaluator, request, full, false);
  }
}

bool EngineWorker::evaluatePass(Evaluator& evaluator, const Request& request, int resolution,
                                bool coarse) {
  auto progress = std::make_shared<Progress>([this](const std::string& stage, double fraction) {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.stage = stage;
    status_.fraction = fraction;
  });
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (hasRequest_ || stopping_) return false;  // already superseded
    running_ = progress;
    status_ = WorkerStatus{true, "start", 0.0, resolution};
  }
  auto result = std::make_shared<PreviewResult>();
  result->tag = request.tag;
  result->scene = request.scene;
  result->resolution = resolution;
  result->coarse = coarse;
  bool cancelled = false;
  try {
    EvalOptions options;
    options.resolution = resolution;
    result->stats = evaluator.evaluate(*request.scene, options, *progress);
    Stopwatch splatClock;
    result->surfels = result->stats.root->surfelCount();
    result->ldiBytes = result->stats.root->bytes();
    SplatsHandle splats = backend_->splats(result->stats.root, *progress);
    result->stats.root.reset();  // the cache keeps what it needs; the UI needs only the splats
    if (hostSplats_ && !splats->hostData()) {
      std::vector<Splat> host(splats->count());
      splats->copyToHost(host.data());
      splats = std::make_shared<HostSplats>(std::move(host));
    }
    result->splats = std::move(splats);
    result->splatSeconds = splatClock.seconds();
  } catch (const Cancelled&) {
    cancelled = true;
  } catch (const Error& e) {
    result->error = e.what();
  } catch (const std::bad_alloc&) {
    result->error = "out of memory; lower the resolution";
  } catch (const std::exception& e) {
    result->error = std::string("unexpected error: ") + e.what();
  } catch (...) {
    result->error = "unexpected error";
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    running_.reset();
    status_ = WorkerStatus{};
    if (cancelled) return false;
    lastShown_ = request.scene;
    finished_ = std::move(result);
  }
  if (onResult_) onResult_();
  return true;
}

}  // namespace strata::ui
