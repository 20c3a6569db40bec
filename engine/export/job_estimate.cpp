#include "engine/export/job_estimate.h"
#include "engine/export/streamed_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/eval/evaluator.h"
#include "engine/export/check_streamed.h"
#include "engine/export/simplify_mesh.h"
#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_formats.h"
#include "engine/ldi/offset_math.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/timer.h"

namespace strata {
namespace {

// Host memory of an export besides the LDIs of the tile being evaluated: per output triangle of
// the whole mesh (merged, written, checked), and again per triangle of one tile (its contour's
// own arrays while it is made). Measured 2026-11-25: six exports at 1024 and 2048 cells, one to
// eight tiles, on a 2-core machine (CPU backend; peaks of 0.53 to 2.06 GB) fit 80 bytes
// within -9% to +18%; on a 16-core host (CUDA) armadillo - bunny and the rebuilt scaffold at
// 4096 cells (54-64 tiles, 72-78 M triangles) took 113-116 bytes a triangle: 100 is between.
constexpr double kExportBytesPerTriangle = 100.0;
constexpr double kTileBytesPerTriangle = 80.0;
// A streamed export (streamed_export.h) holds, beside a slab's tiles and its merged piece (the
// bytes above per triangle of the slab), a set and a count per vertex of the whole mesh (about
// half a vertex a triangle) and the check's two words per facet; its scratch file holds per
// vertex a key, a position and an id, per triangle three indices and a byte (vertices of the
// slabs' shared layers twice).
constexpr double kStreamedBytesPerTriangle = 14.0;
constexpr double kScratchBytesPerTriangle = 36.0;
// A streamed PLY (indexed, coloured by leaf) holds besides, per vertex of the whole mesh, its
// index in the file, its colour and a byte of state (8 bytes: 4 a triangle), and spills each
// triangle's leaf (4 bytes); its check holds corners as doubles.
constexpr double kStreamedIndexedBytesPerTriangle = 4.0;
constexpr double kScratchLeafBytesPerTriangle = 4.0;
// Simplifying (simplify_mesh.h), per triangle of the unsimplified mesh, beside the export's own:
// OpenMesh's halfedge mesh of each chunk, the quadrics, the heap and the grid of the unsimplified
// surface. Measured 2026-11-30 on this 2-core machine: the demo at 1024 cells (5.1 M triangles)
// peaked at 3.08 GB simplified against 0.67 GB not (470 bytes a triangle), armadillo - bunny at
// 768 (2.5 M) at 2.01 GB against 0.32 GB (670 bytes).
constexpr double kSimplifyBytesPerTriangle = 560.0;
// Writing and checking, per triangle (they are not in the probes' times): measured 0.12 to
// 0.18 microseconds on this 2-core machine in the same six exports.
constexpr double kWriteCheckSecondsPerTriangle = 2e-7;

// How much more surface the job samples than the probe: the square of their cell sizes' ratio.
double scaleFrom(const Grid& probe, const Grid& job) {
  const double ratio = probe.h / job.h;
  return ratio * ratio;
}

std::string countText(double n) {
  char text[64];
  if (n >= 1e9)
    std::snprintf(text, sizeof(text), "%.1f billion", n / 1e9);
  else if (n >= 1e6)
    std::snprintf(text, sizeof(text), "%.1f million", n / 1e6);
  else
    std::snprintf(text, sizeof(text), "%.0f", n);
  return text;
}

// Time of a job from two probes: a part that does not grow with the resolution (per input
// triangle: transforms, projections; per node), paid once per tile, and a part that grows with
// the surface. Fitted to the probes (one tile each) at x = 1 (kProbeResolution) and x = xSmall
// (half of it) in units of the probe's surface, then taken at xJob with `tiles` tiles.
double fitSeconds(double tSmall, double xSmall, double tProbe, double xJob, int tiles) {
  double perSurface = xSmall < 1.0 ? (tProbe - tSmall) / (1.0 - xSmall) : tProbe;
  perSurface = std::max(0.0, perSurface);
  double fixed = tProbe - perSurface;
  if (fixed < 0.0) {
    fixed = 0.0;
    perSurface = tProbe;
  }
  return fixed * std::max(1, tiles) + perSurface * xJob;
}

int longestSide(const Grid& g) {
  return std::max(g.cells.x, std::max(g.cells.y, g.cells.z));
}

// The probe's resolution for a job of `jobCells` along its longest side: kProbeResolution, or
// an eighth of the job where that is finer. A job extrapolated from a much coarser probe
// multiplies the probes' noise and fixed costs by its surface ratio: probes at 32 and 64 cells
// put the demo's export at 1024 cells at 13 s on this 2-core machine where it takes 2.6 s.
// An eighth costs about 1/64 of the job's surface work; at most kMaxProbeResolution (a probe of
// a 16384-cell job would otherwise be a job of its own).
int probeResolutionFor(int jobCells) {
  return std::clamp((jobCells / 8 + 1) / 2 * 2, kProbeResolution, kMaxProbeResolution);
}

// What one probe measured: its grid, and of its time the modifiers' (offsets, shells, roundings)
// with the nodes of the windows they ran on.
struct ProbeRun {
  Grid grid;
  double modifySeconds = 0.0;
  double modifiedNodes = 0.0;
};

// Nodes of a window of `cells` (Grid::nodeCount for a window that is not a grid).
double nodesOf(const glm::dvec3& cells) {
  return (cells.x + 1.0) * (cells.y + 1.0) * (cells.z + 1.0);
}

// The export dialog's probe for a job of `jobCells`: the job itself up to
// kMaxTriangleProbeResolution (small and cheap: the count is the export's), else half of it, at
// most kMaxTriangleProbeResolution. Parts thinner than a few probe cells lose surface at coarse
// probes: an artist's pen holder (3 mm walls in 100 mm) probed at 64 cells put its export at 256
// cells at 267,000 triangles where it wrote 391,700 (-32%); probed at 128 at 377,000 (-4%), and
// at 512 cells 1.51 M for 1.65 M (-9%, -35% from 64 cells); the bone scaffold's pores, at 128
// cells probed at 64, 32,000 for 57,916 (an artist's test). Above the ceiling it costs about a
// quarter of the export's surface work, on the dialog's background thread.
constexpr int kMaxTriangleProbeResolution = 256;
int triangleProbeResolution(int jobCells) {
  if (jobCells <= kMaxTriangleProbeResolution) return jobCells;
  return std::clamp(jobCells / 2, kProbeResolution, kMaxTriangleProbeResolution);
}

// Runs `probe` (returns a ProbeRun) at half and at the whole probe resolution, timing each;
// returns the fitted seconds of the job on `job` in `tiles` tiles whose modifiers run on
// `jobModifiedNodes` nodes in all. Two laws: a modifier's distance transform walks every node
// of its window (its time grows with the cube of the resolution: measured 7.4x, 9.5x, 11.8x
// per doubling for a rounded part from 64 to 512 cells), the rest follows the surface (the
// square). Fitting both to the surface law put that part's export at 1024 cells at 8 s where it
// took 58 s; so the modifiers' time is taken out of both probes, the rest fitted as before, and
// the whole probe's modifier time scaled by the nodes.
// Each probe is timed as the middle of a few runs (probeTime); the last run is at the whole
// probe resolution (the caller keeps what it measured).
template <typename Probe>
double timeFromProbes(const Grid& job, int tiles, double jobModifiedNodes, Probe&& probe) {
  const int resolution = probeResolutionFor(longestSide(job));
  ProbeRun smallRun, run;
  const ProbeTime small = probeTime(
      [&] {
        smallRun = probe(resolution / 2);
        return smallRun.modifySeconds;
      },
      kProbeRuns, kProbeRepeatSeconds);
  const ProbeTime whole = probeTime(
      [&] {
        run = probe(resolution);
        return run.modifySeconds;
      },
      kProbeRuns, kProbeRepeatSeconds);
  const double modify =
      run.modifiedNodes > 0.0 ? whole.excludedSeconds * jobModifiedNodes / run.modifiedNodes : 0.0;
  return fitSeconds(std::max(0.0, small.seconds), scaleFrom(run.grid, smallRun.grid),
                    std::max(0.0, whole.seconds), scaleFrom(run.grid, job), tiles) +
         modify;
}

}  // namespace

ProbeTime probeTime(const std::function<double()>& run, int maxRuns, double budgetSeconds) {
  std::vector<double> rests, excluded;
  Stopwatch spent;
  while (int(rests.size()) < std::max(1, maxRuns)) {
    Stopwatch clock;
    excluded.push_back(run());
    rests.push_back(clock.seconds() - excluded.back());
    if (spent.seconds() >= budgetSeconds) break;
  }
  // The middle one (of an even count the lower middle: of two, the smaller).
  const auto middle = [](std::vector<double> v) {
    const auto m = v.begin() + std::ptrdiff_t((v.size() - 1) / 2);
    std::nth_element(v.begin(), m, v.end());
    return *m;
  };
  ProbeTime t;
  t.seconds = middle(rests);
  t.excludedSeconds = middle(excluded);
  t.runs = int(rests.size());
  return t;
}

JobEstimate estimateEvaluation(const Scene& scene, int resolution,
                               const std::shared_ptr<Backend>& backend, Progress& progress,
                               int probeAbove) {
  JobEstimate e;
  e.grid = Evaluator::gridFor(scene, resolution);
  const Grid probeGrid = Evaluator::gridFor(scene, kProbeResolution);
  // No bigger than the probe: nothing to probe.
  if (probeGrid.h <= e.grid.h * 1.5 || longestSide(e.grid) <= probeAbove) return e;
  const uint64_t present = residentBytes();  // before the probes, which add their own
  EvalResult r;
  try {
    e.seconds = timeFromProbes(e.grid, 1, double(e.grid.nodeCount()), [&](int resolution) {
      Evaluator probe(backend);
      EvalOptions options;
      options.resolution = resolution;
      r = probe.evaluate(scene, options, progress);
      return ProbeRun{r.grid, r.modifySeconds, double(r.grid.nodeCount())};
    });
  } catch (const BackendOutOfMemory&) {
    return e;  // not probed (seconds unset): the evaluation itself falls back to the CPU
  }
  const double scale = scaleFrom(r.grid, e.grid);
  e.probed = true;
  e.surfels = uint64_t(double(r.measure.surfels) * scale);
  // Every node's LDI is kept (the cache): the probe's cache, scaled, on top of what the
  // process holds now (LDIs on a device take none of the host's).
  e.peakBytes = present + (backend->keepsLdisOnHost() ? uint64_t(double(r.cacheBytes) * scale) : 0);
  return e;
}

JobEstimate estimateExport(const Scene& scene, const ContourOptions& options,
                           const std::string& path, const std::shared_ptr<Backend>& backend,
                           Progress& progress, int probeAbove, double simplifyCells,
                           const TriangleEstimate* counted) {
  return estimateExport(scene, options, path, backend, workersMemory({backend}, 1), progress,
                        probeAbove, simplifyCells, counted);
}

JobEstimate estimateExport(const Scene& scene, const ContourOptions& options,
                           const std::string& path, const std::shared_ptr<Backend>& backend,
                           const WorkersMemory& memory, Progress& progress, int probeAbove,
                           double simplifyCells, const TriangleEstimate* counted) {
  JobEstimate e;
  e.grid = Evaluator::gridFor(scene, options.resolution);
  const ExportTiling tiling = exportTiling(scene, options, memory.bytes, memory.offsetBytesPerNode);
  e.tiles = tiling.count();
  const Grid probeGrid = Evaluator::gridFor(scene, kProbeResolution);
  if (probeGrid.h <= e.grid.h * 1.5 || longestSide(e.grid) <= probeAbove) return e;
  // Held now, before the probes, which add their own (not the process's peak so far, which
  // counts what an earlier job let go).
  const uint64_t present = residentBytes();
  ContourReport report;
  size_t probeTriangles = 0;
  TriangleMesh lastProbe;
  double seconds = 0.0;
  // The job's modifiers run on each tile's grown window (once where that is the whole grid).
  const glm::dvec3 window = grownTileCells(e.grid, tiling.tileCells, tiling.halo);
  const glm::dvec3 whole(e.grid.cells);
  const double jobModifiedNodes =
      window == whole ? double(e.grid.nodeCount()) : nodesOf(window) * double(std::max(1, e.tiles));
  try {
    seconds = timeFromProbes(e.grid, e.tiles, jobModifiedNodes, [&](int resolution) {
      Evaluator probe(backend);
      ContourOptions probeOptions;
      probeOptions.resolution = resolution;  // tiles sized to the backend's memory, as the job's
      report = ContourReport();
      ExportMesh mesh = contourScene(scene, probe, probeOptions, progress, &report);
      probeTriangles = mesh.mesh.triangles.size();
      lastProbe = std::move(mesh.mesh);  // its components counted after the timing
      return ProbeRun{report.grid, report.modifySeconds, report.modifiedNodes};
    });
  } catch (const BackendOutOfMemory&) {
    return e;  // not probed: the export itself retries with smaller tiles or on the CPU
  }
  const double scale = scaleFrom(report.grid, e.grid);
  e.probed = true;
  e.probeComponents = checkMesh(lastProbe).components;  // as the export's check counts them
  e.probeCells = longestSide(report.grid);
  e.surfels = uint64_t(double(report.surfels) * scale);
  e.triangles = counted && counted->triangles > 0 ? counted->triangles
                                                  : uint64_t(double(probeTriangles) * scale);
  // One tile at a time (the cache is cleared between tiles): its share of the LDIs (where the
  // backend keeps them on the host) and of the contour's arrays, beside the mesh of every tile.
  const double tiles = double(std::max(1, e.tiles));
  const double ldiBytes = backend->keepsLdisOnHost() ? double(report.tileLdiBytes) * scale : 0.0;
  const double tileBytes = (ldiBytes + double(e.triangles) * kTileBytesPerTriangle) / tiles;
  // A modifier's distance transform over the tile's grown window, where the backend works on
  // the host (engine/ldi/offset_math.h).
  double offsetBytes = 0.0;
  if (tiling.halo > 0 && backend->keepsLdisOnHost()) {
    const glm::dvec3 window = grownTileCells(e.grid, tiling.tileCells, tiling.halo);
    offsetBytes =
        double(kHostOffsetBytesPerNode) * (window.x + 3) * (window.y + 3) * (window.z + 3);
  }
  e.peakBytes =
      present + uint64_t(tileBytes + offsetBytes + double(e.triangles) * kExportBytesPerTriangle);
  // Streamed: its own tiling (streamedTiling), the tiles' arrays and piece of the slab being
  // merged and a worker's slab ahead of it (where it has no slabs, the whole export's figures);
  // a PLY (`indexed`) numbers and colours its vertices before it writes them.
  const MeshFormat* format = meshFormatFor(path, MeshAccess::Write);
  const bool indexed = lowerExtension(path) == "ply";
  ExportTiling streamedTiles = tiling;
  try {
    streamedTiles = streamedTiling(scene, options, memory.bytes, memory.offsetBytesPerNode);
  } catch (const Error&) {
  }
  const double slabs = double(std::max(1, streamedTiles.counts.z));
  const double streamedScale = tiles / double(std::max(1, streamedTiles.count()));
  // One worker: the tile it evaluates, and the tiles of the slab it contours ahead of the one
  // being merged (streamedSlabsAhead).
  e.streamedSlabs = int(slabs);
  e.streamedTilesPerSlab = std::max(1, streamedTiles.counts.x * streamedTiles.counts.y);
  e.streamedWorkerBytes = uint64_t(ldiBytes / tiles * streamedScale + offsetBytes);
  e.streamedSlabTileBytes = uint64_t(double(e.triangles) * kTileBytesPerTriangle / slabs);
  e.streamedPeakBytes =
      present + e.streamedWorkerBytes +
      uint64_t(streamedSlabsAhead(1, e.streamedSlabs)) * e.streamedSlabTileBytes +
      uint64_t(double(e.triangles) * ((kTileBytesPerTriangle + kExportBytesPerTriangle) / slabs +
                                      kStreamedBytesPerTriangle)) +
      streamedCheckBytes(e.grid, e.triangles, indexed);
  e.scratchBytes = uint64_t(double(e.triangles) * kScratchBytesPerTriangle);
  if (indexed) {
    e.streamedPeakBytes += uint64_t(double(e.triangles) * kStreamedIndexedBytesPerTriangle);
    e.scratchBytes += uint64_t(double(e.triangles) * kScratchLeafBytesPerTriangle);
  }
  e.fileBytes = uint64_t(double(e.triangles) * (format ? format->bytesPerTriangle : 50.0));
  e.seconds = seconds + kWriteCheckSecondsPerTriangle * double(e.triangles);
  if (simplifyCells > 0.0 && probeTriangles > 0) {
    // The export dialog's count (estimateExportTriangles: the same probes, the same number), its
    // simplification's time per triangle scaled to the job's triangles.
    const TriangleEstimate simplified =
        counted && counted->simplified > 0
            ? *counted
            : estimateExportTriangles(scene, options.resolution, simplifyCells, backend, progress);
    e.seconds += simplified.simplifySecondsPerTriangle * double(e.triangles);
    e.peakBytes += uint64_t(double(e.triangles) * kSimplifyBytesPerTriangle);
    e.simplifiedTriangles = std::min(e.triangles, simplified.simplified);
    e.fileBytes =
        uint64_t(double(e.simplifiedTriangles) * (format ? format->bytesPerTriangle : 50.0));
  }
  return e;
}

uint64_t streamedPeakOnWorkers(const JobEstimate& e, int workers) {
  workers = std::max(1, workers);
  const int more =
      streamedSlabsAhead(workers, e.streamedSlabs) - streamedSlabsAhead(1, e.streamedSlabs);
  return e.streamedPeakBytes + uint64_t(workers - 1) * e.streamedWorkerBytes +
         uint64_t(more) * e.streamedSlabTileBytes;
}

JobEstimate streamedEstimate(const JobEstimate& estimate, int workers, uint64_t heldBytes) {
  JobEstimate pieces = estimate;
  if (pieces.probed) pieces.tiles = std::max(1, pieces.streamedSlabs * pieces.streamedTilesPerSlab);
  pieces.peakBytes = streamedPeakOnWorkers(estimate, workers) + heldBytes;
  pieces.fileBytes += pieces.scratchBytes;
  return pieces;
}

TriangleEstimate estimateExportTriangles(const Scene& scene, int resolution, double simplifyCells,
                                         const std::shared_ptr<Backend>& backend,
                                         Progress& progress) {
  const Grid grid = Evaluator::gridFor(scene, resolution);
  const int jobCells = longestSide(grid);
  const int probeResolution = triangleProbeResolution(jobCells);
  // One probe contoured (and simplified) at `cells` in one tile: its grid's longest side and
  // its triangles, unsimplified and simplified.
  struct Probed {
    int cells = 0;
    uint64_t triangles = 0, simplified = 0;
    double simplifySeconds = 0.0;
  };
  auto probeAt = [&](int cells) {
    Evaluator probe(backend);
    ContourOptions options;
    options.resolution = cells;
    options.tileCells = cells * 2;  // one tile
    ContourReport report;
    ExportMesh mesh = contourScene(scene, probe, options, progress, &report);
    Probed p{longestSide(report.grid), mesh.mesh.triangles.size(), 0, 0.0};
    if (simplifyCells > 0.0 && !mesh.mesh.triangles.empty()) {
      Stopwatch clock;
      p.simplified = simplifyMesh(&mesh, simplifyCells * report.grid.h, progress).trianglesAfter;
      p.simplifySeconds = clock.seconds();
    }
    return p;
  };
  const Probed fine = probeAt(probeResolution);
  const double linear = double(jobCells) / double(std::max(1, fine.cells));
  TriangleEstimate e;
  e.triangles = uint64_t(double(fine.triangles) * linear * linear);
  if (simplifyCells <= 0.0 || fine.triangles == 0) return e;
  e.simplifySecondsPerTriangle = fine.simplifySeconds / double(fine.triangles);
  if (fine.cells >= jobCells) {  // the probe is the job
    e.simplified = fine.simplified;
    return e;
  }
  // How the simplified count grows, measured between this probe and one at half its cells.
  const Probed coarse = probeAt(std::max(probeResolution / 2, kProbeResolution / 2));
  e.simplified =
      std::min(e.triangles, simplifiedAtResolution(coarse.simplified, coarse.cells, fine.simplified,
                                                   fine.cells, jobCells));
  return e;
}

std::string bodiesDifferSentence(const JobEstimate& estimate, int jobCells, int components) {
  if (!estimate.probed || estimate.probeComponents < 0 || components == estimate.probeComponents)
    return "";
  const auto bodies = [](int n) {
    return std::to_string(n) + (n == 1 ? " body" : " separate bodies");
  };
  return bodies(components) + " at " + std::to_string(jobCells) +
         " cells, where the estimate's probe of the same scene at " +
         std::to_string(estimate.probeCells) + " cells made " +
         std::to_string(estimate.probeComponents) +
         ": where parts touch at a point or along an edge, lie closer than a cell or are a few "
         "cells across, the cells decide what joins, what parts and what shows. Overlap parts "
         "meant to be one body; keep parts meant apart more than a cell apart";
}

uint64_t simplifiedAtResolution(uint64_t coarseCount, int coarseCells, uint64_t count, int cells,
                                int jobCells) {
  if (count == 0 || cells <= 0 || jobCells <= cells) return count;
  double exponent = 1.0;
  if (coarseCount > 0 && coarseCells > 0 && coarseCells < cells)
    exponent = std::clamp(std::log(double(count) / double(coarseCount)) /
                              std::log(double(cells) / double(coarseCells)),
                          0.0, 2.0);
  return uint64_t(std::llround(double(count) * std::pow(double(jobCells) / cells, exponent)));
}

std::string bytesText(double bytes) {
  char text[64];
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 5) {
    bytes /= 1024.0;
    ++u;
  }
  std::snprintf(text, sizeof(text), u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return text;
}

std::string durationText(double s) {
  char text[64];
  if (s < 60.0)
    std::snprintf(text, sizeof(text), "%.0f s", std::max(1.0, s));
  else if (s < 3600.0)
    std::snprintf(text, sizeof(text), "%.0f min", s / 60.0);
  else if (s < 86400.0 * 2)
    std::snprintf(text, sizeof(text), "%.1f hours", s / 3600.0);
  else
    std::snprintf(text, sizeof(text), "%.0f days", s / 86400.0);
  return text;
}

std::string describeEstimate(const JobEstimate& e) {
  std::string s = std::to_string(e.grid.cells.x) + " x " + std::to_string(e.grid.cells.y) + " x " +
                  std::to_string(e.grid.cells.z) + " cells";
  if (e.tiles > 1) s += ", " + countText(e.tiles) + " tiles";
  if (!e.probed) return s;
  if (e.triangles > 0 && e.simplifiedTriangles > 0)
    s += ", about " + countText(double(e.triangles)) + " triangles simplified to about " +
         countText(double(e.simplifiedTriangles));
  else if (e.triangles > 0)
    s += ", about " + countText(double(e.triangles)) + " triangles";
  else
    s += ", about " + countText(double(e.surfels)) + " surfels";
  s += ", " + bytesText(double(e.peakBytes)) + " of memory";
  if (e.fileBytes > 0) s += ", a " + bytesText(double(e.fileBytes)) + " file";
  s += ", " + durationText(e.seconds);
  return s;
}

std::string estimateRefusal(const JobEstimate& e, uint64_t availableMemory, uint64_t freeDisk) {
  if (!e.probed) return "";
  if (availableMemory > 0 && e.peakBytes > availableMemory)
    return "needs about " + bytesText(double(e.peakBytes)) + " of memory and " +
           bytesText(double(availableMemory)) + " are available";
  if (freeDisk > 0 && e.fileBytes > freeDisk)
    return "writes a file of about " + bytesText(double(e.fileBytes)) + " and the disk has " +
           bytesText(double(freeDisk)) + " free";
  return "";
}

bool estimateWorthTelling(const JobEstimate& e) {
  return e.probed && (e.seconds > 10.0 || e.tiles > 64 || e.peakBytes > (uint64_t(2) << 30));
}

}  // namespace strata
