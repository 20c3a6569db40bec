#include "engine/jobs/triangle_estimate_job.h"

#include <exception>
#include <new>

#include "engine/util/error.h"
#include "engine/util/thread_priority.h"

namespace strata {

TriangleEstimateJob::TriangleEstimateJob(std::shared_ptr<const Scene> scene, int resolution,
                                         double simplifyCells,
                                         std::function<std::shared_ptr<Backend>()> makeBackend)
    : resolution_(resolution), simplifyCells_(simplifyCells) {
  thread_ = std::thread([this, scene = std::move(scene), makeBackend = std::move(makeBackend)] {
    lowerThisThreadPriority();
    TriangleEstimate estimate;
    std::string error;
    try {
      if (!makeBackend) throw Error("no backend to estimate with");
      estimate =
          estimateExportTriangles(*scene, resolution_, simplifyCells_, makeBackend(), progress_);
    } catch (const Cancelled&) {
      error = "cancelled";
    } catch (const Error& e) {
      error = e.what();
    } catch (const std::bad_alloc&) {
      error = "out of memory";
    } catch (const std::exception& e) {
      error = std::string("unexpected error: ") + e.what();
    } catch (...) {
      error = "unexpected error";
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      result_ = estimate;
      error_ = error;
    }
    done_.store(true, std::memory_order_release);
  });
}

TriangleEstimateJob::~TriangleEstimateJob() {
  progress_.cancel();
  thread_.join();
}

TriangleEstimate TriangleEstimateJob::result() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return result_;
}

std::string TriangleEstimateJob::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

}  // namespace strata
