// Progress reporting and cooperative cancellation for long operations.
//
// Threads: a Progress is shared by the thread that runs an operation (and its worker threads,
// which call check()/advance() concurrently) and the thread that may cancel it (any thread).
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <string>

#include "engine/util/error.h"

namespace strata {

class Progress {
 public:
  // Called with the current stage name and its completed fraction in [0, 1]. May be called from
  // worker threads, but never concurrently (calls are serialised by a mutex).
  using Callback = std::function<void(const std::string& stage, double fraction)>;

  Progress() = default;
  explicit Progress(Callback callback) : callback_(std::move(callback)) {}
  // A child: cancelled by its own cancel() or whenever `parent` is; reports nowhere. For work
  // that runs beside its parent's stages (on a thread of its own) and must stop with them, or
  // alone. The parent must outlive it.
  explicit Progress(const Progress* parent) : parent_(parent) {}
  // A child that reports through `callback` (a part of the parent's work, mapped onto the
  // parent's stages by the callback) and is cancelled with `parent`.
  Progress(const Progress* parent, Callback callback)
      : parent_(parent), callback_(std::move(callback)) {}

  // Asks the operation to stop; it throws Cancelled at its next check(). Any thread.
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const {
    return cancelled_.load(std::memory_order_relaxed) || (parent_ && parent_->cancelled());
  }

  // Throws Cancelled if cancel() was called. Cheap; call inside long loops.
  void check() const {
    if (cancelled()) throw Cancelled();
  }

  // Reports progress of the named stage (fraction in [0, 1]) and checks for cancellation.
  void report(const std::string& stage, double fraction) {
    check();
    if (!callback_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    callback_(stage, fraction);
  }

 private:
  std::atomic<bool> cancelled_{false};
  const Progress* parent_ = nullptr;
  Callback callback_;
  std::mutex mutex_;
};

}  // namespace strata
