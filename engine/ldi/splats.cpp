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

std::vector<Splat> buildSplats(const Ldi& ldi, SplatLevels* levels) {
  const SplatFrame frame = splatFrame(ldi.grid);
  std::vector<Splat> splats;
  splats.reserve(ldi.surfelCount() / 3 + 16);
  SplatLevels ends;
  for (int level = kSplatLevels - 1; level >= 0; --level) {
    for (int axis = 0; axis < 3; ++axis) {
      const AxisLdi& a = ldi.axes[axis];
      const int raysU = ldi.grid.raysU(axis);
      for (int64_t local = 0; local + 1 < int64_t(a.offsets.size()); ++local) {
        // The grid's ray index of this stored ray (the same for a whole axis).
        const int64_t ray = a.whole ? local
                                    : (a.window.u0 + local % a.window.uCount) +
                                          (a.window.v0 + local / a.window.uCount) * int64_t(raysU);
        if (splatRayLevel(frame, axis, ray) != level) continue;
        for (uint32_t k = a.offsets[size_t(local)]; k < a.offsets[size_t(local) + 1]; ++k)
          if (surfelMakesSplat(a.surfels[k], axis))
            splats.push_back(splatOf(frame, axis, ray, a.surfels[k]));
      }
    }
    ends.end[level] = splats.size();
  }
  if (levels) *levels = ends;
  return splats;
}

void HostSplats::copyToHost(Splat* out) const {
  if (!splats_.empty()) std::memcpy(out, splats_.data(), splats_.size() * sizeof(Splat));
}

}  // namespace strata
