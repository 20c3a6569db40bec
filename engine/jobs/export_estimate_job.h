// The export dialog's triangle counts (estimateExportTriangles, job_estimate.h) and the export's
// whole estimate from them (estimateExport: time and memory, for jobs above kProbeAbove cells)
// computed on a background thread for one choice of file, resolution and simplification, so
// that the dialog never waits: it asks again when the choice changes and shows the newest
// finished answer. The time and memory were told only once the export ran, and a short one
// ended before they could be read (an artist's test).
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

// The dialog's answer: the counts, and the export's estimate taking them as its triangles.
struct DialogEstimate {
  TriangleEstimate triangles;
  JobEstimate job;
};

class ExportEstimateJob {
 public:
  // `path`: the file the export would write (its format sets the file's bytes).
  ExportEstimateJob(std::shared_ptr<const Scene> scene, const std::string& path, int resolution,
                    double simplifyCells, std::function<std::shared_ptr<Backend>()> makeBackend);

  void cancel() { job_.cancel(); }
  // The scene it counts (the document's snapshot when it began: the same pointer while the
  // document is unchanged).
  const std::shared_ptr<const Scene>& scene() const { return scene_; }
  int resolution() const { return resolution_; }
  double simplifyCells() const { return simplifyCells_; }
  bool done() const { return job_.done(); }
  // Valid once done(): the counts, or why there is none.
  TriangleEstimate result() const { return job_.result().triangles; }
  // Valid once done() without an error: the export's estimate (JobEstimate::probed false for a
  // job of kProbeAbove cells or fewer: no time or memory).
  JobEstimate jobEstimate() const { return job_.result().job; }
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
  // The finished estimate of the export of `scene` to `path` at `resolution` within
  // `simplifyCells` (none otherwise, or where it probed nothing): what that export may take
  // instead of probing again (ExportGuard::estimated). `path` must be of the format it was made
  // for (the same extension, in any case): the format sets the file's bytes. The probes were
  // made twice, a few tenths of a second each time, once for the dialog and again at Export.
  std::optional<JobEstimate> estimateOf(const std::shared_ptr<const Scene>& scene,
                                        const std::string& path, int resolution,
                                        double simplifyCells) const;

 private:
  std::shared_ptr<const Scene> scene_;
  std::string path_;
  int resolution_;
  double simplifyCells_;
  BackgroundJob<DialogEstimate> job_;
};

}  // namespace strata
