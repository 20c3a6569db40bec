// What a job at a high resolution will cost, told before it starts: cells, tiles, surface,
// memory, file size and time, scaled from quick probes of the same scene at an eighth of the
// job's resolution (at least kProbeResolution) on the same backend. Surfels, triangles, LDI memory
// and (to first order) time all grow with the surface, that is with the square of the resolution;
// the probe measures the constant for this scene. Time is fitted to two probes (at half and at the
// whole probe resolution): a part fixed by the input (a big mesh's triangles) plus a part that
// grows with the surface; the modifiers' time (an offset walks every node of its window) is taken
// out of the probes and scaled by the nodes of the job's (grown) tile windows instead. Memory: the
// probe's LDIs of one tile and bytes per triangle, scaled. An estimate, good to a factor of about
// two: enough to tell a job of seconds from one of hours, or one that fits from one that cannot.
//
// Synchronous; any thread; runs the probe on `backend` (which the caller must not use
// meanwhile).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/export/contour_scene.h"
#include "engine/export/contour_workers.h"
#include "engine/util/progress.h"

namespace strata {

// Cells of the probe along the longest side, at least (jobs over 512 cells: an eighth of theirs).
constexpr int kProbeResolution = 64;
constexpr int kMaxProbeResolution = 512;
// Jobs of at most this many cells along the longest side are not probed (the probes would cost
// a noticeable part of the job itself: a scene of 100,000 small leaves samples each leaf per
// probe whatever the resolution): only their grid and tiles are set.
constexpr int kProbeAbove = 512;

struct JobEstimate {
  Grid grid;               // of the job
  int tiles = 1;           // export only
  uint64_t surfels = 0;    // of the root
  uint64_t triangles = 0;  // export only
  uint64_t peakBytes = 0;  // host memory at the peak, the process's present use included
  uint64_t fileBytes = 0;  // export only: the written file
  // Export only: the same written in pieces (streamed_export.h) on one backend: its peak, and
  // its scratch file (streamedPeakOnWorkers below: on several).
  uint64_t streamedPeakBytes = 0;
  uint64_t scratchBytes = 0;
  // Export only, streamed: its slabs (or layers of cubes) and their tiles each, the bytes of one
  // slab's tiles, and what one worker holds of the tile it evaluates (its share of the LDIs and
  // offsets).
  int streamedSlabs = 1;
  int streamedTilesPerSlab = 1;
  uint64_t streamedSlabTileBytes = 0;
  uint64_t streamedWorkerBytes = 0;
  double seconds = 0.0;              // wall time of the job on this backend
  uint64_t simplifiedTriangles = 0;  // export only, simplified: the triangles written
  bool probed = false;  // false: the job is no bigger than the probe; only grid and tiles set
  // Probed only: the closed components of the last (finest) probe's mesh and its cells along
  // the longest side; -1 and 0 when not probed (bodiesDifferSentence).
  int probeComponents = -1;
  int probeCells = 0;
};

// A probe's time on a machine that other work shares: the middle of a few runs. One run's wall
// clock carries whatever else ran meanwhile (the editor drawing, another program), and the fit
// multiplies a probe's error by the job's surface ratio (64 for a probe at an eighth): on a loaded
// 2-core machine one export of 8 to 15 s was estimated at 3 to 30 s (an artist's test). The middle
// leaves out a run slowed by a passing load, and follows a load that lasts (which slows the job
// as well; the least run would not). `run` runs the probe once and returns the seconds of its
// time to leave out (its modifiers', timed apart); it is run at least once and again while fewer
// than `maxRuns` runs took less than `budgetSeconds` in all, so only cheap probes, whose noise
// weighs most, are repeated.
struct ProbeTime {
  double seconds = 0.0;          // the middle of the runs' times less their excluded seconds
  double excludedSeconds = 0.0;  // the middle of the excluded seconds
  int runs = 0;
};
ProbeTime probeTime(const std::function<double()>& run, int maxRuns, double budgetSeconds);
constexpr int kProbeRuns = 3;
constexpr double kProbeRepeatSeconds = 0.3;

// "2 separate bodies at 1024 cells, where the estimate's probe at 128 cells made 1: ..." when an
// export of `components` closed components at `jobCells` differs from its estimate's probe, ""
// otherwise (or not probed). Parts touching at a point or along an edge, or closer than a cell,
// are joined or apart depending on the cells: a sphere resting on a box exported as one body at
// 512 cells and as two at 1024 and 2048, each "watertight", without a word (an artist's test).
// A fact of the grid, not a guess: both counts are of meshes contoured from the same scene.
std::string bodiesDifferSentence(const JobEstimate& estimate, int jobCells, int components);

// An evaluation of `scene` at `resolution` (0 = the scene's setting).
JobEstimate estimateEvaluation(const Scene& scene, int resolution,
                               const std::shared_ptr<Backend>& backend, Progress& progress,
                               int probeAbove = kProbeAbove);

// An export of `scene` to `path` (its extension picks the format's bytes per triangle) whose
// tiles may each use `memory` (contour_workers.h: workersMemory over the export's workers, which
// divides a backend's memory among the workers sharing it, --gpus N on one device): its tilings,
// in memory and streamed, are the ones the export will pick. The probes run on `backend`.
// Simplified (`simplifyCells` > 0, simplify_mesh.h), the probe's mesh is simplified too and
// timed: its time per triangle, scaled to the job's triangles, is added, with the collapses'
// memory, and the file is the simplified mesh's (its triangles growing with the resolution, not
// its square; estimateExportTriangles). The simplification was not counted: an export said
// "3 s, 1 GiB" and took 95 s and 3.1 GB on this project's 2-core machine.
struct TriangleEstimate;
// `counted`: the export dialog's count for this scene, resolution and simplification
// (estimateExportTriangles, from a finer probe), taken as the job's triangles so that the export
// window says the dialog's number (3.3 million there against 3.6 million in the dialog, for
// 3.69 million written: an artist's test), and not worked out again for a simplification.
JobEstimate estimateExport(const Scene& scene, const ContourOptions& options,
                           const std::string& path, const std::shared_ptr<Backend>& backend,
                           const WorkersMemory& memory, Progress& progress,
                           int probeAbove = kProbeAbove, double simplifyCells = 0.0,
                           const TriangleEstimate* counted = nullptr);
// The same on `backend` alone.
JobEstimate estimateExport(const Scene& scene, const ContourOptions& options,
                           const std::string& path, const std::shared_ptr<Backend>& backend,
                           Progress& progress, int probeAbove = kProbeAbove,
                           double simplifyCells = 0.0, const TriangleEstimate* counted = nullptr);

// The streamed export's peak on `workers` backends (--gpus): each evaluates a tile of its own,
// and they hold the tiles of up to streamedSlabsAhead slabs ahead of the merge.
uint64_t streamedPeakOnWorkers(const JobEstimate& estimate, int workers);
// The estimate of the same export written in pieces on `workers` workers: its own tiles (where
// probed), streamedPeakOnWorkers plus `heldBytes` (a distributed process 0's tiles held) as the
// peak, and the scratch file counted with the file.
JobEstimate streamedEstimate(const JobEstimate& estimate, int workers, uint64_t heldBytes = 0);

// The triangles an export at `resolution` (0 = the scene's) will write, unsimplified and
// simplified within `simplifyCells` cells (0: not simplified), for the export dialog and the
// export job alike (one number in both: they differed by 57%, an artist's test): one probe
// contoured at half the resolution (at least kProbeResolution, at most 256 cells, the job itself
// where it is no finer) and simplified at the same tolerance in cells, and where the job is finer
// a second probe at half that, simplified too (simplifiedAtResolution). Unsimplified triangles
// grow with the surface, the square of the resolution. Throws Cancelled.
struct TriangleEstimate {
  uint64_t triangles = 0;
  uint64_t simplified = 0;  // 0 when not simplified
  // The finer probe's simplification: seconds per triangle it started from (0 when not
  // simplified), for the job's time.
  double simplifySecondsPerTriangle = 0.0;
};
TriangleEstimate estimateExportTriangles(const Scene& scene, int resolution, double simplifyCells,
                                         const std::shared_ptr<Backend>& backend,
                                         Progress& progress);

// Simplified triangles at `jobCells` from `count` at `cells` and `coarseCount` at `coarseCells`
// (the same tolerance in cells): the count grows as the power of the resolution the two
// measured, between 0 (flat faces: a box's 12 triangles at any resolution) and 2 (a surface
// that keeps every triangle). A curved surface's count does not grow with the resolution, as a
// linear rule took it: the bunny simplified within 0.25 cells had 2,214, 3,512, 4,664, 6,268 and
// 10,622 triangles at 64, 128, 256, 512 and 1024 cells; from 128 and 256 this puts 1024 at 8,226
// (-23%), where the linear rule from 256 said 18,000 (+70%) and the job's probe at 128 28,889.
uint64_t simplifiedAtResolution(uint64_t coarseCount, int coarseCells, uint64_t count, int cells,
                                int jobCells);

// A size for the user: "13.2 GiB", "512 bytes".
std::string bytesText(double bytes);
// A duration for the user: "4 s" (at least 1), "3 min", "1.5 hours", "3 days".
std::string durationText(double seconds);

// One line for the user: "4096 x 3600 x 3080 cells, 1,024 tiles, about 52 million triangles,
// 13 GiB of memory, a 2.6 GB file, 3 minutes".
std::string describeEstimate(const JobEstimate& estimate);

// Why the job cannot run here ("" when it can): more memory than `availableMemory` bytes, or a
// file larger than `freeDisk` bytes (0 = unknown: not checked).
std::string estimateRefusal(const JobEstimate& estimate, uint64_t availableMemory,
                            uint64_t freeDisk);

// Whether the estimate is worth telling before starting: over 10 s, 64 tiles or 2 GiB.
bool estimateWorthTelling(const JobEstimate& estimate);

}  // namespace strata
