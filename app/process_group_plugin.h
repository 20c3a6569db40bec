// The MPI group of a `--distributed` run: loads dist/'s plugin (libstrata_mpi.so, beside the
// running binary) and opens MPI_COMM_WORLD through it. Only then is Open MPI loaded: `strata`
// neither links it nor needs it otherwise.
#pragma once

#include <memory>

#include "engine/util/process_group.h"

namespace strata {

// Throws strata::Error saying what is missing: a build without MPI (no plugin), the plugin or
// Open MPI not loadable, MPI failing to start. Call once, on the main thread, before threads
// that use MPI; the group is finalised when destroyed.
std::unique_ptr<ProcessGroup> openMpiProcessGroup();

}  // namespace strata
