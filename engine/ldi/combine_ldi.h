// CPU Booleans of LDIs, ray by ray (the reference; gpu/ldi/combine_ldi.cuh is its CUDA twin and
// shares combineRayEvents from shared_math.h).
#pragma once

#include <memory>
#include <vector>

#include "engine/ldi/ldi.h"
#include "engine/util/progress.h"

namespace strata {

// Combines the children's LDIs (all on the same grid, clean lists) with an n-ary operation:
// union (inside any), intersection (inside all), difference (inside the first and none of the
// others). With no children the result is empty. Runs on all worker threads.
std::shared_ptr<Ldi> combineLdis(RayOp op, const std::vector<std::shared_ptr<const Ldi>>& children,
                                 const Grid& grid, Progress* progress = nullptr);

}  // namespace strata
