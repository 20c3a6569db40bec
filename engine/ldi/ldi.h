// Layered depth images on the host: for each of the three axes, every ray's surfels sorted by
// depth, stored as key-data pairs compacted into CSR (per-ray offsets + one surfel array).
// Memory grows with the surface, not the volume, and there is no layer limit.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/ldi/grid.h"
#include "engine/ldi/shared_math.h"

namespace strata {

// The surfels of one axis. offsets has rayCount(axis) + 1 entries; the surfels of ray r are
// surfels[offsets[r] .. offsets[r + 1]), sorted by depth, alternating enter / exit, starting
// with an enter (a "clean" list).
struct AxisLdi {
  std::vector<uint32_t> offsets;
  std::vector<Surfel> surfels;

  size_t bytes() const {
    return offsets.capacity() * sizeof(uint32_t) + surfels.capacity() * sizeof(Surfel);
  }
};

struct Ldi {
  Grid grid;
  std::array<AxisLdi, 3> axes;

  size_t surfelCount() const {
    return axes[0].surfels.size() + axes[1].surfels.size() + axes[2].surfels.size();
  }
  size_t bytes() const { return axes[0].bytes() + axes[1].bytes() + axes[2].bytes(); }
};

// An LDI with no surfels on the grid (every offset zero).
std::shared_ptr<Ldi> makeEmptyLdi(const Grid& grid);

// Volume and area of the solid an LDI describes, in scene units.
//   volume: per axis, the summed inside length of all rays times h^2; the three axes averaged
//   area:   each surfel stands for h^2 / |n|_1 of surface (the three axes together sample a
//           patch with normal n at density |n|_1 / h^2)
struct LdiMeasure {
  double volume = 0.0;
  std::array<double, 3> axisVolume{0.0, 0.0, 0.0};
  double area = 0.0;
  size_t surfels = 0;
};
LdiMeasure measureLdi(const Ldi& ldi);

// Throws strata::Error when a surfel count no longer fits the 32-bit offsets.
void checkSurfelCount(uint64_t count, const char* what);

}  // namespace strata
