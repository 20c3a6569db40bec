#include "app/terminal_progress.h"

#include <unistd.h>

#include <cstdio>

namespace strata {

TerminalProgress::TerminalProgress(bool quiet)
    : progress_([this, quiet](const std::string& stage, double fraction) {
        if (quiet || !isatty(STDERR_FILENO)) return;
        std::lock_guard<std::mutex> lock(mutex_);
        const int width = 30;
        int filled = int(fraction * width + 0.5);
        std::fprintf(stderr, "\r%-10s [", stage.c_str());
        for (int i = 0; i < width; ++i) std::fputc(i < filled ? '#' : '.', stderr);
        std::fprintf(stderr, "] %3d%%  (Ctrl-C cancels)", int(fraction * 100 + 0.5));
        std::fflush(stderr);
        drawn_ = true;
      }) {}

TerminalProgress::~TerminalProgress() {
  finish();
}

void TerminalProgress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) std::fprintf(stderr, "\r%70s\r", "");
  drawn_ = false;
}

}  // namespace strata
