#include "app/terminal_progress.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

namespace strata {
namespace {
Progress* volatile g_active = nullptr;
volatile std::sig_atomic_t g_interrupts = 0;

extern "C" void onInterrupt(int) {
  g_interrupts = g_interrupts + 1;
  if (g_interrupts > 1) std::_Exit(130);
  if (g_active) g_active->cancel();  // an atomic store: async-signal-safe
}
}  // namespace

TerminalProgress::TerminalProgress(bool quiet)
    : progress_([this, quiet](const std::string& stage, double fraction) {
        if (quiet || !isatty(STDERR_FILENO)) return;
        const int width = 30;
        int filled = int(fraction * width + 0.5);
        std::fprintf(stderr, "\r%-10s [", stage.c_str());
        for (int i = 0; i < width; ++i) std::fputc(i < filled ? '#' : '.', stderr);
        std::fprintf(stderr, "] %3d%%  (Ctrl-C cancels)", int(fraction * 100 + 0.5));
        std::fflush(stderr);
        drawn_ = true;
      }) {
  g_active = &progress_;
  std::signal(SIGINT, onInterrupt);
}

TerminalProgress::~TerminalProgress() {
  finish();
  std::signal(SIGINT, SIG_DFL);
  g_active = nullptr;
}

void TerminalProgress::finish() {
  if (drawn_) std::fprintf(stderr, "\r%70s\r", "");
  drawn_ = false;
}

}  // namespace strata
