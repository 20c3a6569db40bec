// An export's tiles contoured on several backends at once (`strata export --gpus N`): one worker
// thread per backend takes the next tile no worker has taken, so tiles go to whichever device
// frees up first; several backends on one GPU overlap one tile's host-side contouring with
// another's device work.
//
// Threads: the workers call their backends (one thread each) and the engine's parallelFor;
// `progress` gets the stage "export" (tiles done over all workers, from any worker, serialised
// by Progress) and is checked between tiles and, through each worker's own Progress, inside
// them. A worker whose backend runs out of memory goes on with its tiles on the CPU backend (the
// same bits) and says so through `notice` (one call at a time); any other failure stops every
// worker after its tile and is rethrown by join().
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "engine/eval/backend.h"
#include "engine/export/contour_scene.h"
#include "engine/export/fallback.h"

namespace strata {

// The workers of one export over `tiling` (sized by the caller for the backends' memory), one
// thread each, started by the constructor. Before a worker takes a tile no worker has taken yet
// it calls mayTake(t, stopping) (may be empty; it may block until the tile's turn comes, and
// should return soon once stopping.cancelled(): the worker's own Progress, cancelled with the
// export, by stop() or when another worker failed); each tile it finishes it hands to tileDone(t,
// contours) (the tile's contours, moved; may be empty: without it the contours stay with the
// worker until join() collects them). Both are called from the worker threads, concurrently. The
// destructor stops the workers (after their tile) and joins them.
class TileWorkers {
 public:
  using MayTake = std::function<void(int tile, const Progress& stopping)>;
  using TileDone = std::function<void(int tile, std::vector<TileContour> contours)>;

  TileWorkers(const Scene& scene, const std::vector<std::shared_ptr<Backend>>& backends,
              const ExportTiling& tiling, Progress& progress, const FallbackNotice& notice,
              MayTake mayTake = {}, TileDone tileDone = {});
  ~TileWorkers();
  TileWorkers(const TileWorkers&) = delete;
  TileWorkers& operator=(const TileWorkers&) = delete;

  // True once the export was cancelled, a worker failed or stop() was called. Any thread.
  bool stopping() const { return stop_.cancelled(); }
  // Stops the workers after their tile. Any thread.
  void stop() { stop_.cancel(); }
  // Waits for every worker; throws Cancelled if the export was cancelled, else the first
  // worker's failure. Then *report gets the workers' counts (evaluate and contour: the longest
  // worker's seconds) and *contours every tile not handed to tileDone. Once, from the thread
  // that made the workers.
  void join(ContourReport* report, std::vector<TileContour>* contours);

 private:
  void work(size_t worker);

  const Scene& scene_;
  const std::vector<std::shared_ptr<Backend>> backends_;
  const ExportTiling tiling_;
  Progress& progress_;
  Progress stop_;  // cancelled with progress_, or by stop()
  const FallbackNotice notice_;
  const MayTake mayTake_;
  const TileDone tileDone_;
  std::unique_ptr<std::atomic<bool>[]> taken_;
  std::atomic<int> done_{0};
  std::mutex mutex_;  // guards failure_ and calls of notice_
  std::exception_ptr failure_;
  std::vector<ContourReport> reports_;
  std::vector<std::vector<TileContour>> contours_;
  std::vector<std::thread> threads_;
};

// The whole mesh from tiles contoured on `backends` (TileWorkers), merged as one process merges
// them (meshFromTiles): the mesh contourScene makes, vertex for vertex. `workersPerMemory`: how
// many of the backends share one backend's memory (workers on one GPU), for sizing tiles
// (exportTiling over the smallest memoryAvailable() divided by it; workersTiling below).
ExportMesh contourSceneOnWorkers(const Scene& scene,
                                 const std::vector<std::shared_ptr<Backend>>& backends,
                                 const ContourOptions& options, int workersPerMemory,
                                 Progress& progress, ContourReport* report,
                                 const FallbackNotice& notice = {});

// The memory a tile of workers on `backends` may use (the smallest backend's divided by
// workersPerMemory), and the bytes per node of a modifier's offset (the largest backend's).
struct WorkersMemory {
  uint64_t bytes = 0;
  uint64_t offsetBytesPerNode = 0;
};
WorkersMemory workersMemory(const std::vector<std::shared_ptr<Backend>>& backends,
                            int workersPerMemory);

}  // namespace strata
