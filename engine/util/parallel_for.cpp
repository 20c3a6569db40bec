#include "engine/util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace strata {
namespace {
std::atomic<int> g_override{0};

int defaultWorkers() {
  if (const char* env = std::getenv("STRATA_THREADS")) {
    int n = std::atoi(env);
    if (n >= 1) return n;
  }
  unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}
}  // namespace

int workerCount() {
  int n = g_override.load();
  if (n > 0) return n;
  // Read once: hardware_concurrency() reads /sys on every call, which cost more than sampling a
  // small leaf does.
  static const int workers = defaultWorkers();
  return workers;
}

void setWorkerCount(int threads) {
  g_override.store(std::max(0, threads));
}

void parallelFor(int64_t begin, int64_t end, int64_t grain,
                 const std::function<void(int64_t, int64_t)>& body) {
  if (end <= begin) return;
  grain = std::max<int64_t>(1, grain);
  const int64_t chunks = (end - begin + grain - 1) / grain;
  const int threads = static_cast<int>(std::min<int64_t>(workerCount(), chunks));
  if (threads <= 1) {
    for (int64_t b = begin; b < end; b += grain) body(b, std::min(end, b + grain));
    return;
  }
  std::atomic<int64_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto worker = [&]() {
    for (;;) {
      if (failed.load(std::memory_order_relaxed)) return;
      int64_t c = next.fetch_add(1);
      if (c >= chunks) return;
      int64_t b = begin + c * grain;
      try {
        body(b, std::min(end, b + grain));
      } catch (...) {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (!error) error = std::current_exception();
        failed.store(true);
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace strata
