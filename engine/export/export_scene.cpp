#include "engine/export/export_scene.h"

#include <algorithm>
#include <utility>

#include "engine/export/check_written.h"
#include "engine/export/contour_workers.h"
#include "engine/geometry/degenerate_repair.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/timer.h"

namespace strata {

ExportReport exportScene(const Scene& scene, const std::string& path, const ExportOptions& options,
                         std::shared_ptr<Backend> backend, Progress& progress,
                         const FallbackNotice& notice) {
  ExportReport report;
  ExportMesh mesh;
  {
    Evaluator evaluator(std::move(backend));
    mesh = contourWithFallback(scene, evaluator, options, progress, &report.contour,
                               [&](const std::string& line) {
                                 report.notices.push_back(line);
                                 if (notice) notice(line);
                               });
  }  // the evaluator's cached LDIs go before the file is written
  writeAndCheckExport(std::move(mesh), path, options, progress, &report);
  return report;
}

ExportReport exportScene(const Scene& scene, const std::string& path, const ExportOptions& options,
                         const std::vector<std::shared_ptr<Backend>>& backends,
                         int workersPerMemory, Progress& progress, const FallbackNotice& notice) {
  if (backends.size() == 1) return exportScene(scene, path, options, backends[0], progress, notice);
  ExportReport report;
  ExportMesh mesh = contourSceneOnWorkers(scene, backends, options, workersPerMemory, progress,
                                          &report.contour, [&](const std::string& line) {
                                            report.notices.push_back(line);
                                            if (notice) notice(line);
                                          });
  writeAndCheckExport(std::move(mesh), path, options, progress, &report);
  return report;
}

void writeAndCheckExport(ExportMesh mesh, const std::string& path, const ExportOptions& options,
                         Progress& progress, ExportReport* out) {
  ExportReport& report = *out;
  if (mesh.mesh.triangles.empty()) throw emptyResultError(path, report.contour);
  if (const std::string why = notAFileToReadBack(path); !why.empty())
    throw Error(path + ": " + why);
  if (options.simplifyCells > 0.0)
    report.simplify = simplifyMesh(&mesh, options.simplifyCells * report.contour.grid.h, progress);
  // Triangles without area as the format stores the positions (degenerate_repair.h), repaired
  // before the file is written, so that the check finds none: part of the write's time.
  Stopwatch write;
  report.degenerateRepair =
      repairDegenerateTriangles(&mesh.mesh, storedCoordinate(path), &mesh.triangleLeaf);
  progress.check();
  // The check's half that needs no file (the mesh as the format stores it, measured) runs on a
  // thread of its own beside the write, whose end waits on the disk (check_written.h).
  MeantMeshCheck meant(path, mesh.mesh, progress);
  // Written atomically (engine/util/atomic_file.h): a cancel or a failure while writing leaves
  // the previous file(s) as they were; an OBJ and its MTL are replaced together.
  writeMeshFile(path, mesh, &progress);
  report.writeSeconds = write.seconds();

  // The new file is in place and whole from here on: a cancel during the check leaves it.
  // The check's time is what it takes beyond the write.
  Stopwatch check;
  meant.released();
  mesh = ExportMesh();
  const WrittenCheck written = checkWrittenFile(path, meant, progress);
  report.check = written.check;
  report.fileDifference = written.fileDifference;
  report.checkSeconds = check.seconds();
  // The whole export's peak: a simplification's collapses (several times the contour's memory)
  // come after the contour measured its own.
  report.contour.peakBytes = std::max(report.contour.peakBytes, peakResidentBytes());
}

}  // namespace strata
