// The engine thread of the editor: evaluates scene snapshots in the background so that the UI
// never waits on the engine (libfive Studio's scheduling).
//
//   - The UI thread hands immutable snapshots (std::shared_ptr<const Scene>) with the requested
//     resolution; only the latest request survives, and a new one cancels the running
//     evaluation (Progress::cancel).
//   - An interactive request (the user is dragging) is evaluated only at a coarse resolution,
//     min(requested, coarseResolution); the request made when the hand stops refines it. A
//     calm request for a new scene shows the coarse result first, then the full one.
//   - Results are finished, immutable values (std::shared_ptr<const PreviewResult>): the root's
//     splats (Backend::splats: made where the backend keeps its LDIs, on the device for CUDA)
//     and the evaluation's statistics. The UI thread copies device splats into GL through
//     CUDA-GL interop, or uploads host splats; when it cannot take device splats it says so
//     (setHostSplats(true)) and the worker copies them to the host first.
//   - No GL here. The worker catches everything and reports it in the result's `error`.
//
// Threads: request(), takeResult(), status() from the UI thread (never blocking for longer than
// a mutex hand-over); evaluation on the worker thread, which owns the Evaluator and its cache.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/document/scene.h"
#include "engine/eval/evaluator.h"
#include "engine/ldi/splats.h"

namespace strata::ui {

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
  std::string error;                   // empty on success

  size_t splatCount() const { return splats ? splats->count() : 0; }
  bool ok() const { return splats != nullptr; }
};

struct WorkerStatus {
  bool busy = false;
  std::string stage;      // of the running evaluation ("sample", "boolean", ...)
  double fraction = 0.0;  // of that stage
  int resolution = 0;     // of the running pass
};

class EngineWorker {
 public:
  // `backend` is used by the worker thread alone from now on. `onResult`, when given, is called
  // on the worker thread each time a result is ready (e.g. to wake the UI's event loop).
  explicit EngineWorker(std::shared_ptr<Backend> backend, int coarseResolution = 96,
                        std::function<void()> onResult = {});
  ~EngineWorker();  // cancels the running evaluation and joins
  EngineWorker(const EngineWorker&) = delete;
  EngineWorker& operator=(const EngineWorker&) = delete;

  // Replaces any pending request and cancels the running one.
  void request(std::shared_ptr<const Scene> scene, int resolution, bool interactive, uint64_t tag);
  // Drops the pending request and cancels the running one (e.g. nothing is left to show).
  void cancel();
  // The newest finished result not taken yet, or null.
  std::shared_ptr<const PreviewResult> takeResult();
  WorkerStatus status() const;
  // Whether results must carry host splats (default) or may keep them where the backend made
  // them (the UI copies device splats through CUDA-GL interop). Any thread.
  void setHostSplats(bool host) { hostSplats_ = host; }
  const std::string& backendDescription() const { return backendDescription_; }

 private:
  struct Request {
    std::shared_ptr<const Scene> scene;
    int resolution = 0;
    bool interactive = false;
    uint64_t tag = 0;
  };
  void run();
  // Evaluates one pass; returns false when cancelled.
  bool evaluatePass(Evaluator& evaluator, const Request& request, int resolution, bool coarse);

  std::shared_ptr<Backend> backend_;
  std::string backendDescription_;
  int coarse_;
  std::function<void()> onResult_;
  std::atomic<bool> hostSplats_{true};

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  bool hasRequest_ = false;
  Request pending_;
  std::shared_ptr<Progress> running_;
  std::shared_ptr<const PreviewResult> finished_;
  WorkerStatus status_;
  std::shared_ptr<const Scene> lastShown_;  // worker thread only
  std::thread thread_;
};

}  // namespace strata::ui
