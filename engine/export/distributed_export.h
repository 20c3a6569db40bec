// An export whose tiles are shared among the processes of a group (`mpirun -np N strata export
// SCENE -o OUT --distributed`): process 0 picks the tiling (exportTiling with its backend's
// memory) and tells the others; process r evaluates and contours the tiles t with
// t % N == r on its own backend (CUDA where it has a GPU, else its CPU cores); the others send
// each tile to process 0 as soon as it is contoured (posted: the transfer overlaps the tiles
// left, and the sender keeps no tile it has posted), which merges them with its own
// (meshFromTiles), writes the file and checks it. Tiles are keyed on the global lattice, so the
// file is the one a single process writes, byte for byte.
//
// Progress: process 0 reports "export" over all tiles (the others' tiles counted as they
// arrive, read between its own tiles and while it waits). Failures: a process that fails sends
// its message to process 0 before it throws; process 0 throws strata::Error naming the process
// and its message. The caller ends the group then (ProcessGroup::abort), so no process waits
// for one that has gone; a process killed outright is the launcher's to report (mpirun ends the
// job). The file is written atomically by process 0 only: a failure anywhere leaves no file.
//
// Process 0 holds every tile's vertices and triangles at once, as a single-process export does;
// with options.streamed it writes the file in pieces instead (streamed_export.h), a slab as soon
// as all its tiles are in, and holds the tiles of the slabs not complete yet: at most
// distributedSlabsAhead of them, however far one process falls behind the others. Each process
// starts a tile only in the first distributedSlabsAhead slabs not merged yet (process 0 says
// how many it merged each time the count grows, and answers each process's last tiles with a
// word that it has them, so that no process leaves before reading what was sent to it; a
// failure on process 0 tells the others to stop). The process that holds back the oldest
// slab never waits, so the export takes no longer than its slowest process's share.
#pragma once

#include <memory>
#include <string>

#include "engine/eval/backend.h"
#include "engine/export/export_scene.h"
#include "engine/export/fallback.h"
#include "engine/util/process_group.h"
#include "engine/util/progress.h"

namespace strata {

struct DistributedShare {
  int processes = 1;
  int tiles = 0;               // tiles of the whole export
  int ownTiles = 0;            // given to this process (t % processes == rank)
  double seconds = 0;          // this process's evaluate + contour of its tiles
  double allTilesSeconds = 0;  // process 0: until every process's tiles were in
  int mostSlabsHeld = 0;       // process 0, streamed: the most slabs whose tiles waited at once
};

// How many slabs, from the oldest not merged yet, the processes of a streamed distributed export
// may work in (and process 0 hold tiles of): two rounds of `processes` tiles, in slabs of
// `tilesPerSlab`. Two rounds, so that a process that finished its tile goes on with its next one
// while the round before is still coming in.
int distributedSlabsAhead(int processes, int tilesPerSlab);

// Runs this process's part of the export. On process 0 returns the export's report (contour
// counters summed over all processes) and writes `path`; on the others returns their own
// contour counters, writes nothing. `share` (may be null) says what this process did; `notice`
// gets this process's fallbacks (fallback.h: contourTilesWithFallback).
// Call on every process of `group` with the same scene, path and options.
ExportReport exportSceneDistributed(const Scene& scene, const std::string& path,
                                    const ExportOptions& options, std::shared_ptr<Backend> backend,
                                    ProcessGroup& group, Progress& progress,
                                    DistributedShare* share = nullptr,
                                    const FallbackNotice& notice = {});

}  // namespace strata
