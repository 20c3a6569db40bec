// What every background job shares: the one wording of a job's failure (jobErrorText), and a
// job that computes one answer on a thread of its own (BackgroundJob), as the export dialog's
// triangle estimate and the selection's measure do.
//
// Threads: a BackgroundJob is constructed, polled and destroyed on one thread (the UI's); the
// work runs on its own thread at a lower priority. cancel() asks it to stop and returns at
// once; the destructor cancels and joins (the work stops at its next progress check).
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "engine/util/progress.h"
#include "engine/util/thread_priority.h"

namespace strata {

// The message for the exception `e` a job ended with: "cancelled", a strata::Error's own text,
// "out of memory" followed by `outOfMemoryAdvice` ("; lower the resolution"), or "unexpected
// error: ...".
std::string jobErrorText(std::exception_ptr e, const std::string& outOfMemoryAdvice = "");

template <typename Result>
class BackgroundJob {
 public:
  // Starts `work` on its own thread; it reports to and checks the job's progress.
  explicit BackgroundJob(std::function<Result(Progress&)> work) {
    thread_ = std::thread([this, work = std::move(work)] {
      lowerThisThreadPriority();
      Result answer{};
      std::string error;
      try {
        answer = work(progress_);
      } catch (...) {
        error = jobErrorText(std::current_exception());
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        result_ = std::move(answer);
        error_ = std::move(error);
      }
      done_.store(true, std::memory_order_release);
    });
  }
  ~BackgroundJob() {
    progress_.cancel();
    thread_.join();
  }
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  void cancel() { progress_.cancel(); }
  bool done() const { return done_.load(std::memory_order_acquire); }
  // Valid once done(): the answer, or why there is none ("" when there is one).
  Result result() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return result_;
  }
  std::string error() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
  }

 private:
  Progress progress_;
  std::atomic<bool> done_{false};
  mutable std::mutex mutex_;
  Result result_{};
  std::string error_;
  std::thread thread_;  // last: started once everything it uses exists
};

}  // namespace strata
