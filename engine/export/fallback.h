// Running out of a backend's memory without crashing: evaluation and export retry with smaller
// tiles, then on the CPU backend, and say what they did.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/eval/evaluator.h"
#include "engine/export/contour_scene.h"

namespace strata {

// Called with one line for the user each time a fallback is taken.
using FallbackNotice = std::function<void(const std::string&)>;

// Evaluates on `evaluator`'s backend; when it runs out of memory, evaluates again on a fresh
// CPU backend (returned in *used, which is set either way).
EvalResult evaluateWithFallback(Evaluator& evaluator, const Scene& scene,
                                const EvalOptions& options, Progress& progress,
                                const FallbackNotice& notice,
                                std::shared_ptr<Backend>* used = nullptr);

// Exports with `options`; when the backend runs out of memory, retries with half the tile
// size down to 64 cells, then on the CPU backend with the original tile size.
ExportMesh contourWithFallback(const Scene& scene, Evaluator& evaluator,
                               const ContourOptions& options, Progress& progress,
                               ContourReport* report, const FallbackNotice& notice);

// Contours the tiles t of `tiling` with mine(t) (contourTiles, with afterTile) on `backend`,
// or on a CPU backend (the same bits): from the start where `backend` cannot evaluate the
// scene's modifiers, and for the tiles left, the one that failed included, when it runs out of
// memory. Each switch is said through `notice` (called from this thread). For tiles shared by
// several workers or processes, whose tiling is fixed; one process alone retries with smaller
// tiles first (contourWithFallback).
void contourTilesWithFallback(const Scene& scene, std::shared_ptr<Backend> backend,
                              const ExportTiling& tiling, const std::function<bool(int)>& mine,
                              Progress& progress, ContourReport& r, std::vector<TileContour>* tiles,
                              const FallbackNotice& notice,
                              const std::function<void(int)>& afterTile);

}  // namespace strata
