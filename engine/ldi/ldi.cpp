#include "engine/ldi/ldi.h"

#include <cmath>
#include <string>

#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {

std::shared_ptr<Ldi> makeEmptyLdi(const Grid& grid) {
  auto ldi = std::make_shared<Ldi>();
  ldi->grid = grid;
  for (int a = 0; a < 3; ++a) ldi->axes[a].offsets.assign(grid.rayCount(a) + 1, 0u);
  return ldi;
}

void checkSurfelCount(uint64_t count, const char* what) {
  if (count > 0xffffffffull)
    throw Error(std::string(what) + ": " + std::to_string(count) +
                " surfels on one axis exceed the 2^32 limit; lower the resolution");
}

LdiMeasure measureLdi(const Ldi& ldi) {
  LdiMeasure m;
  const double h = ldi.grid.h;
  constexpr int64_t kGrain = 4096;
  for (int a = 0; a < 3; ++a) {
    const AxisLdi& axis = ldi.axes[a];
    const int64_t rays = int64_t(axis.offsets.size()) - 1;
    // Per-chunk partial sums, added in chunk order afterwards: the result does not depend on
    // how chunks were scheduled.
    const int64_t chunks = (rays + kGrain - 1) / kGrain;
    std::vector<double> length(size_t(chunks), 0.0), area(size_t(chunks), 0.0);
    parallelFor(0, rays, kGrain, [&](int64_t b, int64_t e) {
      double l = 0.0, s = 0.0;
      for (int64_t r = b; r < e; ++r) {
        for (uint32_t k = axis.offsets[r]; k < axis.offsets[r + 1]; ++k) {
          const Surfel& surfel = axis.surfels[k];
          l += surfelEnters(surfel.tag) ? -double(surfel.depth) : double(surfel.depth);
          float n[3];
          decodeNormal(surfel.normal, n);
          s += 1.0 / (std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]));
        }
      }
      length[size_t(b / kGrain)] = l;
      area[size_t(b / kGrain)] = s;
    });
    double totalLength = 0.0, totalArea = 0.0;
    for (int64_t c = 0; c < chunks; ++c) {
      totalLength += length[size_t(c)];
      totalArea += area[size_t(c)];
    }
    m.axisVolume[a] = totalLength * h * h * h;
    m.area += totalArea * h * h;
    m.surfels += axis.surfels.size();
  }
  m.volume = (m.axisVolume[0] + m.axisVolume[1] + m.axisVolume[2]) / 3.0;
  return m;
}

}  // namespace strata
