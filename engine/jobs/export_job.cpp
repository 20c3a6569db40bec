#include "engine/jobs/export_job.h"

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <new>
#include <optional>

#include "engine/export/drop_specks.h"
#include "engine/export/export_scene.h"
#include "engine/export/job_estimate.h"
#include "engine/export/streamed_export.h"
#include "engine/jobs/background_job.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/thread_priority.h"
#include "engine/util/timer.h"

namespace strata {

double overallExportFraction(const std::string& stage, double fraction, bool simplifying,
                             int tiles) {
  struct Part {
    const char* prefix;
    double from, to;
  };
  // Where each stage ends on the bar; a simplification takes most of it where it runs, and
  // none where it does not.
  struct Ends {
    double estimate, exportAll, merge, simplify, write;
  };
  const Ends ends =
      simplifying ? Ends{0.03, 0.28, 0.3, 0.9, 0.93} : Ends{0.05, 0.65, 0.7, 0.7, 0.8};
  // "evaluate" and "contour" are the first tile's (the evaluation and the contour of a job of
  // one tile: the bar sat at "evaluate 10%" through a long one, an artist's test); "export" is
  // every tile's, the first included, so it starts where "evaluate" does.
  const double firstTile = (ends.exportAll - ends.estimate) / double(std::max(1, tiles));
  const double evaluated = ends.estimate + 0.8 * firstTile;
  const Part parts[] = {{"estimate", 0.0, ends.estimate},
                        {"evaluate", ends.estimate, evaluated},
                        {"contour", evaluated, ends.estimate + firstTile},
                        {"export", ends.estimate, ends.exportAll},
                        {"merge", ends.exportAll, ends.merge},
                        {"simplify", ends.merge, ends.simplify},
                        {"write", ends.simplify, ends.write},
                        {"check", ends.write, 1.0}};
  const double f = std::clamp(fraction, 0.0, 1.0);
  for (const Part* part = std::begin(parts); part != std::end(parts); ++part)
    if (stage.rfind(part->prefix, 0) == 0)  // (the ends exactly: one stage's end, the next's start)
      return f >= 1.0 ? part->to : std::min(part->to, part->from + (part->to - part->from) * f);
  return 0.0;  // "start" and anything unknown
}

ExportJob::ExportJob(std::shared_ptr<const Scene> scene, std::string path,
                     const ExportOptions& options, std::shared_ptr<Backend> backend,
                     Listener onChange, ExportGuard guard)
    : onChange_(std::move(onChange)) {
  status_.running = true;
  status_.path = std::move(path);
  status_.resolution = options.resolution;
  status_.simplifyCells = options.simplifyCells;
  status_.stage = "start";
  const bool simplifying = options.simplifyCells > 0.0;
  progress_ =
      std::make_shared<Progress>([this, simplifying](const std::string& stage, double fraction) {
        update([&](ExportStatus& s) {
          s.stage = stage;
          s.stageFraction = fraction;
          s.fraction = std::max(s.fraction,
                                overallExportFraction(stage, fraction, simplifying, tiles_.load()));
        });
      });
  thread_ =
      std::thread([this, scene = std::move(scene), options, backend = std::move(backend), guard] {
        lowerThisThreadPriority();  // the editor stays smooth while it exports: thread_priority.h
        run(scene, options, backend, guard);
      });
}

ExportJob::~ExportJob() {
  progress_->cancel();
  thread_.join();
}

ExportStatus ExportJob::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

void ExportJob::update(const std::function<void(ExportStatus&)>& change) {
  ExportStatus copy;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    change(status_);
    if (onChange_) copy = status_;
  }
  if (onChange_) onChange_(copy);
}

void ExportJob::run(std::shared_ptr<const Scene> scene, ExportOptions options,
                    std::shared_ptr<Backend> backend, ExportGuard guard) {
  Stopwatch clock;
  const std::string path = status().path;
  ExportStatus result;
  // The file as it was before the job (none, or its time of last writing): a cancel tells from
  // it whether the new file was already put in place.
  const auto stamp = [&path] {
    std::error_code error;
    const auto time = std::filesystem::last_write_time(path, error);
    return error ? std::optional<std::filesystem::file_time_type>() : std::optional(time);
  };
  const std::optional<std::filesystem::file_time_type> before = stamp();
  try {
    progress_->report("estimate", 0.0);
    // The probes report as the one stage "estimate", never going back (each probe and a
    // simplification's probe report from 0 again), and stop as soon as the job is cancelled:
    // the job's progress is their parent, which every check() reads (the simplification's
    // probe checks far more often than it reports).
    double estimated = 0.0;
    Progress probe(progress_.get(), [this, &estimated](const std::string&, double fraction) {
      estimated = std::max(estimated, std::min(fraction, 0.99));
      progress_->report("estimate", estimated);  // throws Cancelled once the job is cancelled
    });
    const JobEstimate estimate =
        guard.estimated
            ? *guard.estimated
            : estimateExport(*scene, options, path, backend, probe, kProbeAbove,
                             options.simplifyCells, guard.counted ? &*guard.counted : nullptr);
    const uint64_t memory = guard.memoryBytes ? guard.memoryBytes : availableMemoryBytes();
    const uint64_t disk = freeDiskBytesForFile(path);
    tiles_ = std::max(1, estimate.tiles);
    std::string refusal = estimateRefusal(estimate, memory, disk);
    // Where the whole mesh would not fit the memory but its pieces would: written in pieces.
    JobEstimate shown = estimate;
    bool inPieces = false;
    if (!refusal.empty() && estimate.probed && streamedExportRefusal(path, options).empty()) {
      const JobEstimate pieces = streamedEstimate(estimate, 1);
      if (estimateRefusal(pieces, memory, disk).empty()) {
        refusal.clear();
        shown = pieces;
        inPieces = true;
        tiles_ = std::max(1, pieces.tiles);
      }
    }
    update([&](ExportStatus& s) {
      if (estimate.probed)
        s.estimate =
            describeEstimate(shown) +
            (inPieces ? "; written in pieces: the whole mesh would not fit in memory" : "");
      s.inPieces = inPieces;
    });
    if (!refusal.empty() && !guard.insist) {
      const glm::ivec3 c = estimate.grid.cells;
      result.refused = true;
      throw Error("the export at " + std::to_string(std::max(c.x, std::max(c.y, c.z))) + " cells " +
                  refusal + ". Lower the resolution, or export anyway");
    }
    const FallbackNotice notice = [&](const std::string& line) {
      update([&](ExportStatus& s) { s.notice = line; });
    };
    ExportReport report =
        inPieces
            ? exportSceneStreamed(*scene, path, options, std::move(backend), *progress_, notice)
            : exportScene(*scene, path, options, std::move(backend), *progress_, notice);
    result.succeeded = true;
    result.simplify = report.simplify;
    result.check = report.check;
    result.fileDifference = report.fileDifference;
    result.warnings = report.contour.warnings;
    // What was left out as too small for the cells, said as the command line says it (the
    // export window said only "watertight, 1 component(s)" where a part had been left out:
    // an artist's test).
    if (const std::string specks = droppedSpecksSentence(report.contour.droppedSpecks);
        !specks.empty())
      result.warnings.push_back(specks);
    // Bodies joined or apart by the cells alone (a sphere resting on a box: one body at 512
    // cells, two at 1024, without a word: an artist's test).
    const glm::ivec3 cells = report.contour.grid.cells;
    if (const std::string bodies = bodiesDifferSentence(
            estimate, std::max(cells.x, std::max(cells.y, cells.z)), report.check.components);
        !bodies.empty())
      result.warnings.push_back(bodies);
  } catch (const Cancelled&) {
    result.cancelled = true;
    const std::optional<std::filesystem::file_time_type> after = stamp();
    result.cancelledAfterWrite = after && after != before;
    result.cancelledKeptFile = before && after == before;
  } catch (...) {
    result.error = jobErrorText(std::current_exception(), "; export at a lower resolution");
  }
  update([&](ExportStatus& s) {
    s.running = false;
    s.finished = true;
    s.succeeded = result.succeeded;
    s.cancelled = result.cancelled;
    s.cancelledAfterWrite = result.cancelledAfterWrite;
    s.cancelledKeptFile = result.cancelledKeptFile;
    s.error = result.error;
    s.refused = result.refused;
    s.check = result.check;
    s.simplify = result.simplify;
    s.fileDifference = result.fileDifference;
    s.warnings = result.warnings;
    s.seconds = clock.seconds();
  });
}

}  // namespace strata
