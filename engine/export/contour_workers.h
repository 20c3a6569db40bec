// An export's tiles contoured on several backends at once (`strata export --gpus N`): one worker
// thread per backend takes the next tile no worker has taken, so tiles go to whichever device
// frees up first; several backends on one GPU overlap one tile's host-side contouring with
// another's device work. The tiles are then merged as one process merges them (meshFromTiles):
// the mesh is the one contourScene makes, vertex for vertex.
//
// Threads: the workers call their backends (one thread each) and the engine's parallelFor;
// `progress` gets the stage "export" (tiles done over all workers, from any worker, serialised
// by Progress) and is checked between tiles and, through each worker's own Progress, inside
// them. A worker whose backend runs out of memory goes on with its tiles on the CPU backend (the
// same bits) and says so through `notice`; any other failure stops every worker after its tile
// and is rethrown here.
#pragma once

#include <memory>
#include <vector>

#include "engine/eval/backend.h"
#include "engine/export/contour_scene.h"
#include "engine/export/fallback.h"

namespace strata {

// `workersPerMemory`: how many of the backends share one backend's memory (workers on one GPU),
// for sizing tiles (exportTiling over the smallest memoryAvailable() divided by it).
ExportMesh contourSceneOnWorkers(const Scene& scene,
                                 const std::vector<std::shared_ptr<Backend>>& backends,
                                 const ContourOptions& options, int workersPerMemory,
                                 Progress& progress, ContourReport* report,
                                 const FallbackNotice& notice = {});

}  // namespace strata
