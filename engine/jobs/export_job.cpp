#include "engine/jobs/export_job.h"

#include <new>

#include "engine/export/export_scene.h"
#include "engine/util/error.h"
#include "engine/util/timer.h"

namespace strata {

ExportJob::ExportJob(std::shared_ptr<const Scene> scene, std::string path,
                     const ContourOptions& options, std::shared_ptr<Backend> backend,
                     Listener onChange)
    : onChange_(std::move(onChange)) {
  status_.running = true;
  status_.path = std::move(path);
  status_.resolution = options.resolution;
  status_.stage = "start";
  progress_ = std::make_shared<Progress>([this](const std::string& stage, double fraction) {
    update([&](ExportStatus& s) {
      s.stage = stage;
      s.fraction = fraction;
    });
  });
  thread_ = std::thread([this, scene = std::move(scene), options, backend = std::move(backend)] {
    run(scene, options, backend);
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

void ExportJob::run(std::shared_ptr<const Scene> scene, ContourOptions options,
                    std::shared_ptr<Backend> backend) {
  Stopwatch clock;
  const std::string path = status().path;
  ExportStatus result;
  try {
    ExportReport report = exportScene(
        *scene, path, options, std::move(backend), *progress_,
        [&](const std::string& line) { update([&](ExportStatus& s) { s.notice = line; }); });
    result.succeeded = true;
    result.check = report.check;
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
  update([&](ExportStatus& s) {
    s.running = false;
    s.finished = true;
    s.succeeded = result.succeeded;
    s.cancelled = result.cancelled;
    s.error = result.error;
    s.check = result.check;
    s.seconds = clock.seconds();
  });
}

}  // namespace strata
