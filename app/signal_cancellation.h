// SIGINT, SIGTERM and SIGHUP as cancellation of the whole command: the same for all three.
//
// main() keeps a SignalCancellation alive around every command. When one of the signals arrives:
//   - while a cancellable operation runs (a CancellableScope is alive: the progress bar's
//     Progress), the operation is cancelled: it throws Cancelled at its next check, temporary
//     files are removed as it unwinds, and the command ends with "cancelled" and 128 + the
//     signal's number (exitCodeAfterSignals);
//   - otherwise (a mesh being loaded, a report being written, the editor), or at a second signal,
//     the process ends at once from the handler: the temporary files of atomic writes in flight
//     are removed (abandonAtomicWritesForExit, engine/util/atomic_file.h), a line saying so goes
//     to stderr, and it exits with 128 + the signal's number.
// Exit codes: 130 (SIGINT, Ctrl-C), 143 (SIGTERM), 129 (SIGHUP): "cancelled", as shells report a
// process ended by that signal. SIGKILL cannot be caught; the leftovers it makes are removed by
// the next write of the same file.
#pragma once

#include "engine/util/progress.h"

namespace strata {

// Installs the handlers (sigaction, SA_RESTART) for its lifetime and restores the previous ones
// after. One at a time, on the main thread.
class SignalCancellation {
 public:
  SignalCancellation();
  ~SignalCancellation();
  SignalCancellation(const SignalCancellation&) = delete;
  SignalCancellation& operator=(const SignalCancellation&) = delete;
};

// While alive, a signal cancels `progress` instead of ending the process. One at a time. When it
// ends normally (not by an exception) after a signal that its operation did not notice, the
// process ends then, as if no operation had been running.
class CancellableScope {
 public:
  explicit CancellableScope(Progress& progress);
  ~CancellableScope();
  CancellableScope(const CancellableScope&) = delete;
  CancellableScope& operator=(const CancellableScope&) = delete;

 private:
  int uncaughtAtStart_;
};

// 128 + the first signal received when `code` says cancelled (130) and a signal was the cause;
// `code` otherwise.
int exitCodeAfterSignals(int code);

}  // namespace strata
