// The export dialog's triangle counts (estimateExportTriangles, job_estimate.h) computed on a
// background thread for one choice of resolution and simplification, so that the dialog never
// waits: it asks again when the choice changes and shows the newest finished answer.
//
// Threads: constructed, polled and destroyed on one thread (the UI's); the work runs on its own
// thread, at a lower priority, with a backend it makes there (a CUDA backend takes a moment to
// start). cancel() asks it to stop and returns at once; destruction cancels and joins (the probe
// stops at its next progress check: milliseconds; the UI keeps a cancelled job until done()).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/export/job_estimate.h"
#include "engine/jobs/background_job.h"

namespace strata {

class TriangleEstimateJob {
 public:
  TriangleEstimateJob(std::shared_ptr<const Scene> scene, int resolution, double simplifyCells,
                      std::function<std::shared_ptr<Backend>()> makeBackend);

  void cancel() { job_.cancel(); }
  int resolution() const { return resolution_; }
  double simplifyCells() const { return simplifyCells_; }
  bool done() const { return job_.done(); }
  // Valid once done(): the estimate, or why there is none.
  TriangleEstimate result() const { return job_.result(); }
  std::string error() const { return job_.error(); }

 private:
  int resolution_;
  double simplifyCells_;
  BackgroundJob<TriangleEstimate> job_;
};

}  // namespace strata
