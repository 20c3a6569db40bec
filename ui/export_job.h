// Export in the background: contourScene + writeMeshFile on a snapshot, then the written file is
// read back raw (readMeshFileRaw, no repairs) and checked (checkMesh), as `strata export` does.
//
// Threads: start/status/cancel from the UI thread; the work runs on the job's own thread with
// its own backend (a backend serves one thread at a time, and the preview worker has its own).
// The thread catches everything and reports it in the status.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/geometry/mesh_check.h"
#include "engine/util/progress.h"

namespace strata::ui {

struct ExportStatus {
  bool running = false;
  bool finished = false;   // ended (succeeded, failed or cancelled)
  bool succeeded = false;  // written and re-read
  bool cancelled = false;
  std::string stage;
  double fraction = 0.0;
  std::string error;
  std::string notice;  // a fallback taken (smaller tiles, the CPU), "" when none
  std::string path;
  MeshCheck check;  // of the file as written (valid when succeeded)
  double seconds = 0.0;
  int resolution = 0;
};

class ExportJob {
 public:
  // Starts exporting `scene` at `resolution` (cells along the longest side) to `path` (a
  // writable format of engine/io/mesh_formats.h, picked by its extension).
  ExportJob(std::shared_ptr<const Scene> scene, std::string path, int resolution,
            std::shared_ptr<Backend> backend);
  ~ExportJob();  // cancels and joins
  ExportJob(const ExportJob&) = delete;
  ExportJob& operator=(const ExportJob&) = delete;

  ExportStatus status() const;
  void cancel() { progress_->cancel(); }

 private:
  void run(std::shared_ptr<const Scene> scene, std::shared_ptr<Backend> backend);

  mutable std::mutex mutex_;
  ExportStatus status_;
  std::shared_ptr<Progress> progress_;
  std::thread thread_;
};

}  // namespace strata::ui
