// Background work that yields to the user: the editor's engine threads (the preview worker, a
// background export) run at a lower CPU priority than the UI thread and the GL driver's threads,
// so that on a machine with few cores (a software GL driver draws on the CPU too) frames stay
// smooth while the engine works, and the engine still gets every cycle the UI leaves.
//
// Threads: affects the calling thread only, and the threads it creates from then on (Linux
// threads inherit their creator's nice value). parallelFor keeps one pool of threads per nice
// value of its callers, started by such a caller: a lowered thread's loops run at its priority.
#pragma once

namespace strata {

// The calling thread's nice value (Linux threads have their own; 0 elsewhere, or when it cannot
// be read).
int thisThreadNiceValue();

// Raises the calling thread's nice value by `steps` (Linux; elsewhere nothing). Returns whether
// it changed.
bool lowerThisThreadPriority(int steps = 10);

}  // namespace strata
