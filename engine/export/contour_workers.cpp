#include "engine/export/contour_workers.h"

#include <algorithm>

#include "engine/util/error.h"

namespace strata {

TileWorkers::TileWorkers(const Scene& scene, const std::vector<std::shared_ptr<Backend>>& backends,
                         const ExportTiling& tiling, Progress& progress,
                         const FallbackNotice& notice, MayTake mayTake, TileDone tileDone)
    : scene_(scene),
      backends_(backends),
      tiling_(tiling),
      progress_(progress),
      stop_(&progress),
      notice_(notice),
      mayTake_(std::move(mayTake)),
      tileDone_(std::move(tileDone)),
      taken_(new std::atomic<bool>[size_t(std::max(1, tiling.count()))]),
      reports_(backends.size()),
      contours_(backends.size()) {
  if (backends_.empty()) throw Error("internal: an export on no backend");
  for (int t = 0; t < tiling_.count(); ++t) taken_[size_t(t)] = false;
  try {
    for (size_t w = 0; w < backends_.size(); ++w) threads_.emplace_back([this, w] { work(w); });
  } catch (...) {  // a thread that could not start: the others stopped before this throws
    stop();
    for (auto& t : threads_) t.join();
    throw;
  }
}

TileWorkers::~TileWorkers() {
  stop();
  for (auto& t : threads_)
    if (t.joinable()) t.join();
}

void TileWorkers::work(size_t w) {
  // The worker's own progress: its evaluations' stages are not the export's; it stops with the
  // export, or when another worker failed.
  Progress workerProgress(&stop_);
  int pending = -1;  // a tile this worker took and has not finished
  const auto claim = [&](int t) {
    workerProgress.check();
    if (t == pending) return true;  // the tile again, on the CPU after running out of memory
    if (taken_[size_t(t)].load()) return false;
    if (mayTake_) mayTake_(t, workerProgress);
    workerProgress.check();
    bool expected = false;
    if (!taken_[size_t(t)].compare_exchange_strong(expected, true)) return false;
    pending = t;
    return true;
  };
  std::vector<TileContour>& mine = contours_[w];
  const auto finished = [&](int t) {
    pending = -1;
    if (tileDone_) {
      std::vector<TileContour> tile = std::move(mine);
      mine.clear();
      tileDone_(t, std::move(tile));
    }
    progress_.report("export", double(++done_) / tiling_.count());
  };
  const FallbackNotice said = [&](const std::string& line) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (notice_) notice_(line);
  };
  try {
    contourTilesWithFallback(scene_, backends_[w], tiling_, claim, workerProgress, reports_[w],
                             &mine, said, finished);
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!failure_ && !progress_.cancelled()) failure_ = std::current_exception();
    }
    stop();
  }
}

void TileWorkers::join(ContourReport* report, std::vector<TileContour>* contours) {
  for (auto& t : threads_) t.join();
  if (progress_.cancelled()) throw Cancelled();
  if (failure_) std::rethrow_exception(failure_);
  ContourReport& r = *report;
  r.grid = tiling_.grid;
  r.tileCells = tiling_.tileCells;
  r.tiles = tiling_.count();
  for (size_t w = 0; w < backends_.size(); ++w) {
    const ContourReport& wr = reports_[w];
    // Evaluate and contour: the longest worker's (the wall time of that part of the export).
    r.evaluateSeconds = std::max(r.evaluateSeconds, wr.evaluateSeconds);
    r.contourSeconds = std::max(r.contourSeconds, wr.contourSeconds);
    r.modifySeconds = std::max(r.modifySeconds, wr.modifySeconds);
    r.modifiedNodes += wr.modifiedNodes;
    addTileCounts(wr, &r);
    for (TileContour& t : contours_[w]) contours->push_back(std::move(t));
    contours_[w].clear();
  }
}

WorkersMemory workersMemory(const std::vector<std::shared_ptr<Backend>>& backends,
                            int workersPerMemory) {
  if (backends.empty()) throw Error("internal: an export on no backend");
  WorkersMemory m;
  m.bytes = backends[0]->memoryAvailable();
  for (const auto& b : backends) {
    m.bytes = std::min(m.bytes, b->memoryAvailable());
    m.offsetBytesPerNode = std::max(m.offsetBytesPerNode, b->offsetBytesPerNode());
  }
  m.bytes /= uint64_t(std::max(1, workersPerMemory));
  return m;
}

ExportMesh contourSceneOnWorkers(const Scene& scene,
                                 const std::vector<std::shared_ptr<Backend>>& backends,
                                 const ContourOptions& options, int workersPerMemory,
                                 Progress& progress, ContourReport* report,
                                 const FallbackNotice& notice) {
  ContourReport local;
  ContourReport& r = report ? *report : local;
  r = ContourReport();
  const WorkersMemory memory = workersMemory(backends, workersPerMemory);
  const ExportTiling tiling = exportTiling(scene, options, memory.bytes, memory.offsetBytesPerNode);
  std::vector<TileContour> all;
  {
    TileWorkers workers(scene, backends, tiling, progress, notice);
    workers.join(&r, &all);
  }
  return meshFromTiles(scene, std::move(all), progress, r);
}

}  // namespace strata
