// Progress on the terminal, and the operation that SIGINT, SIGTERM and SIGHUP cancel, for the
// command line.
#pragma once

#include <mutex>

#include "app/signal_cancellation.h"
#include "engine/util/progress.h"

namespace strata {

// A Progress that draws a one-line bar on stderr (only when stderr is a terminal and not quiet)
// and that the signals cancel while it exists (a CancellableScope, app/signal_cancellation.h):
// the first signal asks the running operation to stop, a second one ends the process. Only one
// may exist at a time.
class TerminalProgress {
 public:
  explicit TerminalProgress(bool quiet);
  ~TerminalProgress();
  Progress& progress() { return progress_; }
  // Clears the bar line (call before printing results). Any thread (a worker's notice).
  void finish();

 private:
  std::mutex mutex_;  // guards drawn_ and the bar's line: drawn and cleared from any thread
  bool drawn_ = false;
  Progress progress_;
  CancellableScope cancellable_{progress_};
};

}  // namespace strata
