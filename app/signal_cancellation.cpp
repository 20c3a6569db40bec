#include "app/signal_cancellation.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <exception>

#include "engine/util/atomic_file.h"

namespace strata {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

std::atomic<Progress*> g_active{nullptr};  // the cancellable operation, if any
std::atomic<int> g_inHandler{0};           // handlers running (on any thread)
std::atomic<int> g_signal{0};              // the first signal received
std::atomic<int> g_count{0};               // signals received
struct sigaction g_previous[3];

static_assert(std::atomic<Progress*>::is_always_lock_free, "used from a signal handler");

// Only async-signal-safe calls: write, _exit and abandonAtomicWritesForExit.
[[noreturn]] void endNow(int signal) {
  abandonAtomicWritesForExit();
  const char* text = signal == SIGTERM  ? "\nstrata: cancelled by SIGTERM\n"
                     : signal == SIGHUP ? "\nstrata: cancelled by SIGHUP\n"
                                        : "\nstrata: cancelled by SIGINT\n";
  size_t length = 0;
  while (text[length]) ++length;
  [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, text, length);
  ::_exit(128 + signal);
}

extern "C" void onCancelSignal(int signal) {
  g_inHandler.fetch_add(1);  // first: a CancellableScope ending waits for this handler
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);
  if (g_count.fetch_add(1) == 0) {
    if (Progress* active = g_active.load()) {
      active->cancel();  // an atomic store: async-signal-safe
      g_inHandler.fetch_sub(1);
      return;
    }
  }
  endNow(g_signal.load());
}

}  // namespace

SignalCancellation::SignalCancellation() {
  struct sigaction action = {};
  action.sa_handler = onCancelSignal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (int s : kSignals) sigaddset(&action.sa_mask, s);  // one handler at a time per thread
  for (size_t i = 0; i < 3; ++i) sigaction(kSignals[i], &action, &g_previous[i]);
}

SignalCancellation::~SignalCancellation() {
  for (size_t i = 0; i < 3; ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
}

CancellableScope::CancellableScope(Progress& progress)
    : uncaughtAtStart_(std::uncaught_exceptions()) {
  g_active.store(&progress);
  if (g_count.load() > 0) progress.cancel();  // a signal came before this operation began
}

CancellableScope::~CancellableScope() {
  g_active.store(nullptr);
  while (g_inHandler.load() > 0) {  // a handler on another thread may still hold the pointer
  }
  if (g_count.load() > 0 && std::uncaught_exceptions() == uncaughtAtStart_) {
    // The operation finished without seeing the cancellation; nothing polls from here on.
    std::fflush(stdout);
    std::fflush(stderr);
    endNow(g_signal.load());
  }
}

int exitCodeAfterSignals(int code) {
  const int signal = g_signal.load();
  return code == 130 && signal != 0 ? 128 + signal : code;
}

}  // namespace strata
