// The volume, area, bounds and thinnest wall of one part of a scene (the editor's Diagnostics
// shows the selection's), evaluated on a background thread so that the UI never waits: the part
// alone (partScene), placed as in the scene, on its own grid of `resolution` cells along its
// longest side.
//
// Threads: constructed, polled and destroyed on one thread (the UI's); the work runs on its own
// thread at a lower priority with a backend it makes there. cancel() returns at once; the
// destructor cancels and joins (the UI keeps a cancelled job until done(), as the export
// dialog's estimates).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/util/progress.h"

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
  ~PartMeasureJob();
  PartMeasureJob(const PartMeasureJob&) = delete;
  PartMeasureJob& operator=(const PartMeasureJob&) = delete;

  void cancel() { progress_.cancel(); }
  NodeId id() const { return id_; }
  const Scene* scene() const { return scene_.get(); }
  bool done() const { return done_.load(std::memory_order_acquire); }
  // Valid once done(): the measure, or why there is none.
  PartMeasure result() const;
  std::string error() const;

 private:
  std::shared_ptr<const Scene> scene_;
  NodeId id_;
  Progress progress_;
  std::atomic<bool> done_{false};
  mutable std::mutex mutex_;
  PartMeasure result_;
  std::string error_;
  std::thread thread_;
};

}  // namespace strata
