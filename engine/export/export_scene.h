// Watertight export of a scene to a mesh file, the one pipeline behind `strata export` (and
// `strata boolean ... -o`) and the editor's Export: contour (with the out-of-memory fallbacks of
// fallback.h) -> write (engine/io/mesh_writers.h) -> read the file back raw and check it
// (readMeshFileRaw, checkMesh) -> commit.
//
// The file (and, for OBJ, its MTL) is written into a hidden staging folder beside `path`
// (".<name>.export-XXXXXX"), re-read and checked there, and only then renamed over `path`. A
// failure or a cancellation at any stage (evaluate, contour, write, check) therefore leaves
// nothing behind and an existing file untouched; a file that fails the check is still committed
// (the check is a report, not an error). Error messages name `path`, never the staging folder.
//
// Synchronous; any thread. `progress` receives the stages "evaluate", "export" (one step per
// tile), "write <format>" and "check", and is checked between them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/eval/backend.h"
#include "engine/export/contour_scene.h"
#include "engine/export/fallback.h"
#include "engine/geometry/mesh_check.h"
#include "engine/util/progress.h"

namespace strata {

struct ExportReport {
  ContourReport contour;             // how the mesh was made
  double writeSeconds = 0.0;         // writing the file
  double checkSeconds = 0.0;         // reading it back and checking it
  MeshCheck check;                   // of the file as written, re-read without repairs
  std::vector<std::string> notices;  // the fallbacks taken, in order (each also sent to notice)
};

// Exports the visible tree of `scene` to `path` (.stl .obj .ply .3mf, see mesh_writers.h),
// evaluating on a fresh Evaluator over `backend` whose LDIs are released before the file is
// written. `notice` (may be empty) is called with one line for the user each time a fallback is
// taken. Throws strata::Error naming `path`, or Cancelled.
ExportReport exportScene(const Scene& scene, const std::string& path, const ContourOptions& options,
                         std::shared_ptr<Backend> backend, Progress& progress,
                         const FallbackNotice& notice = {});

}  // namespace strata
