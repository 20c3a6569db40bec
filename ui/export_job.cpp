#include "ui/export_job.h"

#include <new>

#include "engine/export/contour_scene.h"
#include "engine/export/fallback.h"
#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/error.h"
#include "engine/util/timer.h"

namespace strata::ui {

ExportJob::ExportJob(std::shared_ptr<const Scene> scene, std::string path, int resolution,
                     std::shared_ptr<Backend> backend) {
  status_.running = true;
  status_.path = std::move(path);
  status_.resolution = resolution;
  status_.stage = "start";
  progress_ = std::make_shared<Progress>([this](const std::string& stage, double fraction) {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.stage = stage;
    status_.fraction = fraction;
  });
  thread_ = std::thread([this, scene, backend] { run(scene, backend); });
}

ExportJob::~ExportJob() {
  progress_->cancel();
  thread_.join();
}

ExportStatus ExportJob::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

void ExportJob::run(std::shared_ptr<const Scene> scene, std::shared_ptr<Backend> backend) {
  Stopwatch clock;
  std::string path;
  int resolution;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    path = status_.path;
    resolution = status_.resolution;
  }
  ExportStatus result;
  try {
    ContourOptions options;
    options.resolution = resolution;
    MeshCheck check;
    {
      // Out of memory: smaller tiles, then the CPU, as on the command line (fallback.h).
      Evaluator evaluator(backend);
      ExportMesh mesh = contourWithFallback(*scene, evaluator, options, *progress_, nullptr,
                                            [&](const std::string& line) {
                                              std::lock_guard<std::mutex> lock(mutex_);
                                              status_.notice = line;
                                            });
      writeMeshFile(path, mesh, progress_.get());
    }
    progress_->report("check", 0.0);
    check = checkMesh(readMeshFileRaw(path));
    result.succeeded = true;
    result.check = check;
  } catch (const Cancelled&) {
    result.cancelled = true;
  } catch (const Error& e) {
    result.error = e.what();
  } catch (const std::bad_alloc&) {
    result.error = "out of memory; export at a lower resolution";
  } catch (const std::exception& e) {
    result.error = std::string("unexpected error: ") + e.what();
  } catch (...) {
    result.error = "unexpected error";
  }
  std::lock_guard<std::mutex> lock(mutex_);
  status_.running = false;
  status_.finished = true;
  status_.succeeded = result.succeeded;
  status_.cancelled = result.cancelled;
  status_.error = result.error;
  status_.check = result.check;
  status_.seconds = clock.seconds();
}

}  // namespace strata::ui
