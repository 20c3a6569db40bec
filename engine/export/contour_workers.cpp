#include "engine/export/contour_workers.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "engine/util/error.h"

namespace strata {

ExportMesh contourSceneOnWorkers(const Scene& scene,
                                 const std::vector<std::shared_ptr<Backend>>& backends,
                                 const ContourOptions& options, int workersPerMemory,
                                 Progress& progress, ContourReport* report,
                                 const FallbackNotice& notice) {
  if (backends.empty()) throw Error("internal: an export on no backend");
  ContourReport local;
  ContourReport& r = report ? *report : local;
  r = ContourReport();
  uint64_t memory = backends[0]->memoryAvailable(), perNode = 0;
  for (const auto& b : backends) {
    memory = std::min(memory, b->memoryAvailable());
    perNode = std::max(perNode, b->offsetBytesPerNode());
  }
  const ExportTiling tiling =
      exportTiling(scene, options, memory / uint64_t(std::max(1, workersPerMemory)), perNode);
  const int count = tiling.count();
  std::unique_ptr<std::atomic<bool>[]> taken(new std::atomic<bool>[size_t(count)]);
  for (int t = 0; t < count; ++t) taken[size_t(t)] = false;
  std::atomic<int> done{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;  // guards failure and notice
  std::exception_ptr failure;
  const size_t workers = backends.size();
  std::vector<ContourReport> reports(workers);
  std::vector<std::vector<TileContour>> tiles(workers);

  const auto work = [&](size_t w) {
    // The worker's own progress: its evaluations' stages are not the export's; it stops when the
    // export is cancelled.
    Progress workerProgress([&](const std::string&, double) {
      if (progress.cancelled() || stop) workerProgress.cancel();
    });
    int pending = -1;  // a tile this worker took and has not finished
    const auto claim = [&](int t) {
      if (progress.cancelled() || stop) workerProgress.cancel();
      if (t == pending) return true;
      bool expected = false;
      if (!taken[size_t(t)].compare_exchange_strong(expected, true)) return false;
      pending = t;
      return true;
    };
    const auto finished = [&](int) {
      pending = -1;
      progress.report("export", double(++done) / count);
    };
    // Fallback notices from any worker, one at a time.
    const FallbackNotice said = [&](const std::string& line) {
      std::lock_guard<std::mutex> lock(mutex);
      if (notice) notice(line);
    };
    try {
      contourTilesWithFallback(scene, backends[w], tiling, claim, workerProgress, reports[w],
                               &tiles[w], said, finished);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> threads;
  for (size_t w = 1; w < workers; ++w) threads.emplace_back(work, w);
  work(0);
  for (auto& t : threads) t.join();
  if (progress.cancelled()) throw Cancelled();
  if (failure) std::rethrow_exception(failure);

  r.grid = tiling.grid;
  r.tileCells = tiling.tileCells;
  r.tiles = count;
  std::vector<TileContour> all;
  for (size_t w = 0; w < workers; ++w) {
    const ContourReport& wr = reports[w];
    // Evaluate and contour: the longest worker's (the wall time of that part of the export).
    r.evaluateSeconds = std::max(r.evaluateSeconds, wr.evaluateSeconds);
    r.contourSeconds = std::max(r.contourSeconds, wr.contourSeconds);
    addTileCounts(wr, &r);
    for (TileContour& t : tiles[w]) all.push_back(std::move(t));
    tiles[w].clear();
  }
  return meshFromTiles(scene, std::move(all), progress, r);
}

}  // namespace strata
