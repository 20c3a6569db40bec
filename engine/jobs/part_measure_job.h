// The volume, area, bounds and thinnest wall of one part of a scene (the editor's Diagnostics
// shows the selection's), evaluated on a background thread so that the UI never waits: the part
// alone (partScene), placed as in the scene, on its own grid of `resolution` cells along its
// longest side.
//
// Threads: as BackgroundJob (background_job.h), with a backend it makes on its thread; the UI
// keeps a cancelled job until done(), as the export dialog's estimates.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/jobs/background_job.h"

namespace strata {

struct PartMeasure {
  LdiMeasure measure;  // scene units (LdiMeasure: volume, area, thinnest wall)
  double h = 0.0;      // the cell size it was measured at
};

// The scene of part `id` alone: the part under copies of its ancestors' transforms (so that it
// lies where the scene puts it; a pattern's first copy, as the editor shows it), with the rest of
// the tree hidden beside it (instances inside the part still find their targets). Throws
// strata::Error when `id` is not in the scene.
Scene partScene(const Scene& scene, NodeId id);

class PartMeasureJob {
 public:
  PartMeasureJob(std::shared_ptr<const Scene> scene, NodeId id, int resolution,
                 std::function<std::shared_ptr<Backend>()> makeBackend);

  void cancel() { job_.cancel(); }
  NodeId id() const { return id_; }
  bool done() const { return job_.done(); }
  // Valid once done(): the measure, or why there is none.
  PartMeasure result() const { return job_.result(); }
  std::string error() const { return job_.error(); }

 private:
  NodeId id_;
  BackgroundJob<PartMeasure> job_;
};

}  // namespace strata
