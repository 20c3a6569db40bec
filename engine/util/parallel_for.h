// A minimal fork-join loop over an index range on all hardware threads.
//
// parallelFor(begin, end, grain, body) calls body(chunkBegin, chunkEnd) on disjoint chunks of at
// most `grain` indices, from up to workerCount() threads, and returns when all are done. The
// first exception thrown by a body (Cancelled included) stops handing out chunks and is
// rethrown on the calling thread. The calling thread works too; the others come from a pool of
// threads kept for the process (started as first needed), so a call costs a wake-up, not a
// thread start. Calls may nest and may come from several threads at once.
#pragma once

#include <cstdint>
#include <functional>

namespace strata {

// Number of threads parallelFor uses: setWorkerCount's, else STRATA_THREADS if set (>= 1) when
// first asked, else usableCores().
int workerCount();
// The cores this process may run on (its CPU affinity: fewer than the machine's where a launcher
// such as mpirun bound it), and the cores the machine has online.
int usableCores();
int onlineCores();
// Overrides the worker count for this process (1 = serial). 0 restores the default.
void setWorkerCount(int threads);

void parallelFor(int64_t begin, int64_t end, int64_t grain,
                 const std::function<void(int64_t, int64_t)>& body);

}  // namespace strata
