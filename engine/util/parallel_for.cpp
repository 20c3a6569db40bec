#include "engine/util/parallel_for.h"
#include "engine/util/thread_priority.h"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <map>
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
  return usableCores();
}
}  // namespace

int usableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n >= 1) return n;
  }
  return onlineCores();
}

int onlineCores() {
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

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

namespace {

// One parallelFor call: its chunks, handed out by `next`, to the calling thread and to pool
// workers (at most maxThreads at once, the caller included).
struct Job {
  const std::function<void(int64_t, int64_t)>* body = nullptr;
  int64_t begin = 0, end = 0, grain = 1, chunks = 0;
  int maxThreads = 1;
  int active = 0;  // threads inside the job (under the pool's mutex)
  std::atomic<int64_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex errorMutex;
  std::exception_ptr error;

  bool hasWork() const { return next.load(std::memory_order_relaxed) < chunks; }
  // Runs chunks until none is left (or one failed).
  void work() {
    for (;;) {
      if (failed.load(std::memory_order_relaxed)) return;
      const int64_t c = next.fetch_add(1);
      if (c >= chunks) return;
      const int64_t b = begin + c * grain;
      try {
        (*body)(b, std::min(end, b + grain));
      } catch (...) {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (!error) error = std::current_exception();
        failed.store(true);
        return;
      }
    }
  }
};

// Threads kept for parallelFor, started as first needed (spawning threads for every call cost
// more than the work of a small call on a many-core host). One pool per nice value of the
// threads that call it, its threads started by such a caller (they inherit its nice value): the
// editor's background engine threads (thread_priority.h) keep their loops at their own lower
// priority, the UI thread's at its own. Never destroyed: the threads wait on the condition
// variable until the process ends, so no static destructor can find a pool gone.
class Pool {
 public:
  static Pool& forThisThread() {
    static std::mutex registry;
    static std::map<int, Pool*>* pools = new std::map<int, Pool*>();
    const int nice = thisThreadNiceValue();
    std::lock_guard<std::mutex> lock(registry);
    Pool*& pool = (*pools)[nice];
    if (!pool) pool = new Pool();
    return *pool;
  }

  void run(Job& job) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      while (int(threads_.size()) < job.maxThreads - 1) threads_.emplace_back([this] { loop(); });
      job.active = 1;  // the caller
      jobs_.push_back(&job);
    }
    wake_.notify_all();
    job.work();
    std::unique_lock<std::mutex> lock(mutex_);
    jobs_.erase(std::find(jobs_.begin(), jobs_.end(), &job));  // no one joins any more
    --job.active;
    left_.wait(lock, [&] { return job.active == 0; });
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      Job* job = nullptr;
      wake_.wait(lock, [&] {
        for (Job* j : jobs_)
          if (j->active < j->maxThreads && j->hasWork()) {
            job = j;
            return true;
          }
        return false;
      });
      ++job->active;
      lock.unlock();
      job->work();
      lock.lock();
      if (--job->active == 0) left_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;  // a job arrived
  std::condition_variable left_;  // a thread left a job
  std::vector<Job*> jobs_;        // jobs still handing out chunks
  std::vector<std::thread> threads_;
};

}  // namespace

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
  Job job;
  job.body = &body;
  job.begin = begin;
  job.end = end;
  job.grain = grain;
  job.chunks = chunks;
  job.maxThreads = threads;
  Pool::forThisThread().run(job);
  if (job.error) std::rethrow_exception(job.error);
}

}  // namespace strata
