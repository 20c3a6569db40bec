#include "engine/export/export_scene.h"

#include "engine/util/atomic_file.h"

#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/error.h"
#include "engine/util/timer.h"

namespace strata {

ExportReport exportScene(const Scene& scene, const std::string& path, const ContourOptions& options,
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
  // Written atomically (engine/util/atomic_file.h): a cancel or a failure while writing leaves
  // the previous file(s) as they were; an OBJ and its MTL are replaced together.
  Stopwatch write;
  writeMeshFile(path, mesh, &progress);
  report.writeSeconds = write.seconds();
  mesh = ExportMesh();

  // The new file is in place and whole from here on: a cancel during the check leaves it.
  progress.report("check", 0.0);
  Stopwatch check;
  TriangleMesh written;
  {
    const InputLimitLifted ownFile;  // the file just written: no input limit refuses it
    written = readMeshFileRaw(path);
  }
  progress.report("check", 0.5);
  report.check = checkMesh(written);
  report.checkSeconds = check.seconds();
  progress.report("check", 1.0);
  return report;
}

}  // namespace strata
