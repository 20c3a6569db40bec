// The export dialog's triangle counts (estimateExportTriangles, job_estimate.h) computed on a
// background thread for one choice of resolution and simplification, so that the dialog never
// waits: it asks again when the choice changes and shows the newest finished answer.
//
// Threads: constructed, polled and destroyed on one thread (the UI's); the work runs on its own
// thread, at a lower priority, with a backend it makes there (a CUDA backend takes a moment to
// start). cancel() asks it to stop and returns at once; destruction cancels and joins (the probe
// stops at its next progress check: milliseconds; the UI keeps a cancelled job until done()).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/export/job_estimate.h"
#include "engine/util/progress.h"

namespace strata {

class TriangleEstimateJob {
 public:
  TriangleEstimateJob(std::shared_ptr<const Scene> scene, int resolution, double simplifyCells,
                      std::function<std::shared_ptr<Backend>()> makeBackend);
  ~TriangleEstimateJob();
  TriangleEstimateJob(const TriangleEstimateJob&) = delete;
  TriangleEstimateJob& operator=(const TriangleEstimateJob&) = delete;

  void cancel() { progress_.cancel(); }
  int resolution() const { return resolution_; }
  double simplifyCells() const { return simplifyCells_; }
  bool done() const { return done_.load(std::memory_order_acquire); }
  // Valid once done(): the estimate, or why there is none.
  TriangleEstimate result() const;
  std::string error() const;

 private:
  int resolution_;
  double simplifyCells_;
  Progress progress_;
  std::atomic<bool> done_{false};
  mutable std::mutex mutex_;
  TriangleEstimate result_;
  std::string error_;
  std::thread thread_;
};

}  // namespace strata
