// A CPU backend with a gate in front of sampleMesh, for tests of the background jobs: with the
// gate closed, the thread that samples a leaf waits there, so "an evaluation is running" is a
// fact the test can wait for (waitUntilHeld), not a guess about timing.
//
// Threads: sampleMesh on the job's thread (and nowhere else at once); the rest from the test's.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>

#include "engine/eval/cpu_backend.h"

namespace strata::test {

class GatedBackend : public CpuBackend {
 public:
  // What a call waiting at the closed gate does when its progress is cancelled.
  enum class OnCancel {
    Leave,  // leave the gate at once (throwing Cancelled), as a long loop that checks would
    Stay,   // stay until open(), then throw Cancelled: the job is busy for as long as the test
            // wants, whatever is cancelled meanwhile
  };

  std::string description() const override { return "gated test backend"; }

  // From now on, calls wait at the gate; the first `letThrough` of them pass it first.
  void close(OnCancel onCancel = OnCancel::Leave, int letThrough = 0) {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    onCancel_ = onCancel;
    letThrough_ = letThrough;
  }
  void open() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = false;
    }
    changed_.notify_all();
  }
  // Waits until a call is held at the gate; false after `timeout`.
  bool waitUntilHeld(std::chrono::seconds timeout = std::chrono::seconds(60)) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, timeout, [this] { return held_ > 0; });
  }
  int arrivals() const {  // sampleMesh calls so far
    std::lock_guard<std::mutex> lock(mutex_);
    return arrivals_;
  }
  int sampled() const {  // sampleMesh calls that finished with an LDI
    std::lock_guard<std::mutex> lock(mutex_);
    return sampled_;
  }

  LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                       uint32_t leafId, Progress& progress) override {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ++arrivals_;
      if (closed_ && letThrough_ > 0) {
        --letThrough_;
      } else if (closed_) {
        ++held_;
        changed_.notify_all();
        // Cancellation sets a flag and notifies no one: look at it now and then.
        while (closed_ && !(onCancel_ == OnCancel::Leave && progress.cancelled()))
          changed_.wait_for(lock, std::chrono::milliseconds(2));
        --held_;
      }
    }
    progress.check();
    LdiHandle ldi = CpuBackend::sampleMesh(mesh, objectToWorld, grid, leafId, progress);
    std::lock_guard<std::mutex> lock(mutex_);
    ++sampled_;
    return ldi;
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool closed_ = false;
  OnCancel onCancel_ = OnCancel::Leave;
  int letThrough_ = 0;
  int held_ = 0;
  int arrivals_ = 0;
  int sampled_ = 0;
};

}  // namespace strata::test
