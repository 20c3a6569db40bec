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
#include <optional>
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
  // The scene it counts (the document's snapshot when it began: the same pointer while the
  // document is unchanged).
  const std::shared_ptr<const Scene>& scene() const { return scene_; }
  int resolution() const { return resolution_; }
  double simplifyCells() const { return simplifyCells_; }
  bool done() const { return job_.done(); }
  // Valid once done(): the estimate, or why there is none.
  TriangleEstimate result() const { return job_.result(); }
  std::string error() const { return job_.error(); }
  // The finished count of `scene` at `resolution` within `simplifyCells` (none otherwise): what
  // an export of that choice may take as its triangles (ExportGuard::counted).
  std::optional<TriangleEstimate> countOf(const std::shared_ptr<const Scene>& scene, int resolution,
                                          double simplifyCells) const {
    if (!done() || !error().empty() || scene != scene_ || resolution != resolution_ ||
        simplifyCells != simplifyCells_)
      return std::nullopt;
    return result();
  }

 private:
  std::shared_ptr<const Scene> scene_;
  int resolution_;
  double simplifyCells_;
  BackgroundJob<TriangleEstimate> job_;
};

}  // namespace strata
