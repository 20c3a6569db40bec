// Watertight export of a scene to a mesh file, the one pipeline behind `strata export` (and
// `strata boolean ... -o`) and the editor's Export: contour (with the out-of-memory fallbacks of
// fallback.h) -> write (engine/io/mesh_writers.h) -> check the mesh as stored and that the
// file holds it (check_written.h).
//
// The file (and, for OBJ, its MTL, together) is written atomically (engine/util/atomic_file.h):
// a failure or a cancellation while evaluating, contouring or writing leaves nothing behind and
// an existing file untouched. Once written the new file is whole and in place; a cancellation
// during the check leaves it there. A file that fails the check is kept (the check is a report,
// not an error).
//
// Synchronous; any thread. `progress` receives the stages "evaluate", "export" (one step per
// tile), "simplify" (when asked), "write <format>" and "check", and is checked between them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/eval/backend.h"
#include "engine/export/check_written.h"
#include "engine/export/contour_scene.h"
#include "engine/export/fallback.h"
#include "engine/export/simplify_mesh.h"
#include "engine/geometry/degenerate_repair.h"
#include "engine/geometry/mesh_check.h"
#include "engine/util/progress.h"

namespace strata {

struct ExportOptions : ContourOptions {
  ExportOptions() = default;
  ExportOptions(const ContourOptions& contour) : ContourOptions(contour) {}  // NOLINT: implicit
  // > 0: the contoured mesh is simplified (simplify_mesh.h) with every vertex of the
  // unsimplified surface kept within simplifyCells * h of the file's surface.
  double simplifyCells = 0.0;
  // The distributed export (distributed_export.h): process 0 writes the file in pieces
  // (streamed_export.h) as the slabs of tiles come in, never holding the whole mesh.
  bool streamed = false;
};

struct ExportReport {
  ContourReport contour;              // how the mesh was made
  SimplifyReport simplify;            // trianglesBefore == trianglesAfter == 0: not simplified
  DegenerateRepair degenerateRepair;  // triangles without area as stored, repaired before writing
  double writeSeconds = 0.0;          // writing the file
  double checkSeconds = 0.0;          // reading it back and checking it
  MeshCheck check;                    // of the file as written (check_written.h)
  std::string fileDifference;         // "" when the file holds the mesh meant (check_written.h)
  std::vector<std::string> notices;   // the fallbacks taken, in order (each also sent to notice)
  bool passed() const { return writtenCheckPassed(check, fileDifference); }
};

// Exports the visible tree of `scene` to `path` (.stl .obj .ply .3mf, see mesh_writers.h),
// evaluating on a fresh Evaluator over `backend` whose LDIs are released before the file is
// written. `notice` (may be empty) is called with one line for the user each time a fallback is
// taken. Throws strata::Error naming `path`, or Cancelled.
ExportReport exportScene(const Scene& scene, const std::string& path, const ExportOptions& options,
                         std::shared_ptr<Backend> backend, Progress& progress,
                         const FallbackNotice& notice = {});

// The same with the tiles contoured on several backends at once (contour_workers.h;
// `workersPerMemory` of them share one backend's memory); one backend: exportScene above.
ExportReport exportScene(const Scene& scene, const std::string& path, const ExportOptions& options,
                         const std::vector<std::shared_ptr<Backend>>& backends,
                         int workersPerMemory, Progress& progress,
                         const FallbackNotice& notice = {});

// exportScene's steps after contouring, on a mesh made elsewhere (distributed_export.h):
// simplified when asked (with out->contour.grid's cell size), written, checked, into *out.
void writeAndCheckExport(ExportMesh mesh, const std::string& path, const ExportOptions& options,
                         Progress& progress, ExportReport* out);

}  // namespace strata
