#include "engine/ldi/splats.h"

#include <cstring>

namespace strata {

SplatFrame splatFrame(const Grid& grid) {
  SplatFrame f{};
  for (int a = 0; a < 3; ++a) {
    f.origin[a] = grid.origin[a];
    f.first[a] = grid.first[a];
    f.raysU[a] = grid.raysU(a);
  }
  f.h = grid.h;
  return f;
}

std::vector<Splat> buildSplats(const Ldi& ldi) {
  const SplatFrame frame = splatFrame(ldi.grid);
  std::vector<Splat> splats;
  splats.reserve(ldi.surfelCount() / 3 + 16);
  for (int axis = 0; axis < 3; ++axis) {
    const AxisLdi& a = ldi.axes[axis];
    for (int64_t ray = 0; ray + 1 < int64_t(a.offsets.size()); ++ray)
      for (uint32_t k = a.offsets[size_t(ray)]; k < a.offsets[size_t(ray) + 1]; ++k)
        if (surfelMakesSplat(a.surfels[k], axis))
          splats.push_back(splatOf(frame, axis, ray, a.surfels[k]));
  }
  return splats;
}

void HostSplats::copyToHost(Splat* out) const {
  if (!splats_.empty()) std::memcpy(out, splats_.data(), splats_.size() * sizeof(Splat));
}

}  // namespace strata
