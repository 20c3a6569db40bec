#include "engine/export/fallback.h"

#include "engine/eval/cpu_backend.h"
#include "engine/util/error.h"

namespace strata {

EvalResult evaluateWithFallback(Evaluator& evaluator, const Scene& scene,
                                const EvalOptions& options, Progress& progress,
                                const FallbackNotice& notice, std::shared_ptr<Backend>* used) {
  try {
    EvalResult r = evaluator.evaluate(scene, options, progress);
    if (used) *used = nullptr;
    return r;
  } catch (const BackendOutOfMemory& e) {
    evaluator.clearCache();
    if (notice)
      notice(evaluator.backend().description() + " ran out of memory (" + e.what() +
             "); evaluating on the CPU instead");
    auto cpu = std::make_shared<CpuBackend>();
    Evaluator fallback(cpu);
    EvalResult r = fallback.evaluate(scene, options, progress);
    if (used) *used = cpu;
    return r;
  }
}

ExportMesh contourWithFallback(const Scene& scene, Evaluator& evaluator,
                               const ContourOptions& options, Progress& progress,
                               ContourReport* report, const FallbackNotice& notice) {
  ContourReport local;
  if (!report) report = &local;  // the tile size tried, for halving it
  if (hasModifier(scene.root) && !evaluator.backend().evaluatesModifiers()) {
    if (notice)
      notice("offset, shell, round and fillet nodes are evaluated on the CPU (the " +
             evaluator.backend().description() + " backend cannot yet)");
    Evaluator cpu(std::make_shared<CpuBackend>());
    return contourScene(scene, cpu, options, progress, report);
  }
  ContourOptions attempt = options;
  for (;;) {
    try {
      return contourScene(scene, evaluator, attempt, progress, report);
    } catch (const BackendOutOfMemory& e) {
      evaluator.clearCache();
      const int tried = report->tileCells > 0 ? report->tileCells : attempt.tileCells;
      if (tried / 2 < 64) break;
      attempt.tileCells = tried / 2;
      if (notice)
        notice(evaluator.backend().description() + " ran out of memory; retrying with tiles of " +
               std::to_string(attempt.tileCells) + " cells");
    }
  }
  if (notice)
    notice(evaluator.backend().description() +
           " ran out of memory even with tiles of 64 cells; exporting on the CPU instead");
  Evaluator cpu(std::make_shared<CpuBackend>());
  return contourScene(scene, cpu, options, progress, report);
}

void contourTilesWithFallback(const Scene& scene, std::shared_ptr<Backend> backend,
                              const ExportTiling& tiling, const std::function<bool(int)>& mine,
                              Progress& progress, ContourReport& r, std::vector<TileContour>* tiles,
                              const FallbackNotice& notice,
                              const std::function<void(int)>& afterTile) {
  if (hasModifier(scene.root) && !backend->evaluatesModifiers()) {
    if (notice)
      notice("offset, shell, round and fillet nodes are evaluated on the CPU (the " +
             backend->description() + " backend cannot yet)");
    backend = std::make_shared<CpuBackend>();
  }
  std::vector<bool> done(size_t(tiling.count()), false);
  const auto left = [&](int t) { return !done[size_t(t)] && mine(t); };
  const auto finished = [&](int t) {
    done[size_t(t)] = true;
    afterTile(t);
  };
  try {
    Evaluator evaluator(backend);
    contourTiles(scene, evaluator, tiling, left, progress, r, tiles, finished);
  } catch (const BackendOutOfMemory& e) {
    if (notice)
      notice(backend->description() + " ran out of memory (" + e.what() +
             "); its tiles go on on the CPU");
    Evaluator cpu(std::make_shared<CpuBackend>());
    contourTiles(scene, cpu, tiling, left, progress, r, tiles, finished);
  }
}

}  // namespace strata
