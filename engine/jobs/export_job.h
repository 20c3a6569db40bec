// Export in the background: exportScene (engine/export/export_scene.h, the pipeline of `strata
// export`) on a scene snapshot, on the job's own thread. A cancelled or failed export leaves
// nothing behind and an existing file untouched.
//
// Threads: construct, status(), cancel() and destroy from any one owning thread (the editor's
// UI thread); the work runs on the job's own thread with its own backend (a backend serves one
// thread at a time, and the preview worker has its own). The thread catches everything and
// reports it in the status.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/export/check_written.h"
#include "engine/export/export_scene.h"
#include "engine/export/job_estimate.h"
#include "engine/geometry/mesh_check.h"
#include "engine/util/progress.h"

namespace strata {

struct ExportStatus {
  bool running = false;
  bool finished = false;   // ended (succeeded, failed or cancelled)
  bool succeeded = false;  // written, re-read and checked
  bool cancelled = false;
  // Cancelled once the file was written: the new file is in place, whole, but was not checked
  // (the check after the write leaves it there: export_scene.h). The window said "nothing was
  // written" beside a complete 286 MiB file (an artist's test).
  bool cancelledAfterWrite = false;
  // Cancelled before the write, over a file that was there: that file is as it was (the window
  // said only "nothing was written", and an artist checked the old file's checksum to be sure).
  bool cancelledKeptFile = false;
  // "start", "estimate", "evaluate", "contour" (the first tile's), "export", "merge",
  // "simplify", "write <format>", "check"
  std::string stage;
  // The whole job done, in [0, 1]: the stages as parts of one bar (overallExportFraction);
  // never goes back while the job runs.
  double fraction = 0.0;
  double stageFraction = 0.0;  // the current stage's own fraction
  std::string error;
  std::string notice;  // the last fallback taken (smaller tiles, the CPU), "" when none
  // What the export will cost (export/job_estimate.h), "" for a job too small to probe.
  std::string estimate;
  // The estimate did not fit (memory or disk; error says which) and the job was not insisted
  // on: nothing was done. Start it again with insist to export anyway.
  bool refused = false;
  // Written in pieces (streamed_export.h, as `strata export --stream`: the same file): the whole
  // mesh would not fit the memory, its pieces do (STL or PLY, not simplified).
  bool inPieces = false;
  std::string path;
  MeshCheck check;             // of the file as written (valid when succeeded)
  std::string fileDifference;  // "" when the file holds the mesh meant (check_written.h)
  bool checkPassed() const { return writtenCheckPassed(check, fileDifference); }
  double seconds = 0.0;
  int resolution = 0;
  double simplifyCells = 0.0;  // as asked (0: not simplified)
  SimplifyReport simplify;     // valid when succeeded and simplifyCells > 0
  // What the evaluation said of the scene at the export's resolution (valid when succeeded):
  // parts too small or too thin for its cells, a part shrunk away (ContourReport::warnings).
  std::vector<std::string> warnings;
};

// Where a stage's own `fraction` falls on the job's one bar: each stage a fixed part, in the
// order they run, larger for the stages that take longer (contouring; simplifying when asked).
// "evaluate" and "contour" are the first of the job's `tiles` (contour_scene.h), "export" all of
// them: a job of one tile fills most of the bar while it evaluates.
double overallExportFraction(const std::string& stage, double fraction, bool simplifying,
                             int tiles = 1);

// When an export may start (see job_estimate.h).
struct ExportGuard {
  bool insist = false;       // start even when the estimate does not fit
  uint64_t memoryBytes = 0;  // memory the job may use; 0: what the system has available
  // The export dialog's triangle count for this scene and choice (estimateExport's `counted`):
  // the job's estimate says the same number.
  std::optional<TriangleEstimate> counted;
  // The export dialog's whole estimate for this scene, choice and format (probed: time, memory,
  // tiles; ExportEstimateJob::estimateOf): taken as the job's own instead of probing again.
  std::optional<JobEstimate> estimated;
};

class ExportJob {
 public:
  // Called on the job's thread with the new status after each change (stage, fraction, notice,
  // the end), outside the job's lock. Keep it short and do not throw: it runs inside the
  // export's progress reporting.
  using Listener = std::function<void(const ExportStatus&)>;

  // Starts exporting `scene` with `options` (resolution: cells along the longest side, 0 = the
  // scene's; tile size) to `path` (.stl .obj .ply .3mf). A job above kProbeAbove cells is first
  // estimated (stage "estimate"); one that cannot fit the memory (guard.memoryBytes) or the disk
  // is refused unless guard.insist.
  ExportJob(std::shared_ptr<const Scene> scene, std::string path, const ExportOptions& options,
            std::shared_ptr<Backend> backend, Listener onChange = {}, ExportGuard guard = {});
  ~ExportJob();  // cancels and joins
  ExportJob(const ExportJob&) = delete;
  ExportJob& operator=(const ExportJob&) = delete;

  ExportStatus status() const;
  // Asks the export to stop at its next check; it ends with status().cancelled. Any thread.
  void cancel() { progress_->cancel(); }

 private:
  void run(std::shared_ptr<const Scene> scene, ExportOptions options,
           std::shared_ptr<Backend> backend, ExportGuard guard);
  // Applies `change` to the status under the lock, then tells the listener.
  void update(const std::function<void(ExportStatus&)>& change);

  Listener onChange_;
  mutable std::mutex mutex_;
  ExportStatus status_;
  std::atomic<int> tiles_{1};  // the job's tiles, once estimated (overallExportFraction)
  std::shared_ptr<Progress> progress_;
  std::thread thread_;
};

}  // namespace strata
