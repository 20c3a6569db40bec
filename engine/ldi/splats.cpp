#include "engine/ldi/splats.h"

#include <algorithm>
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

std::vector<Splat> SplatArrayPool::take(size_t count) {
  std::vector<Splat> array;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // The smallest kept array that holds `count`.
    size_t best = kept_.size();
    for (size_t i = 0; i < kept_.size(); ++i)
      if (kept_[i].capacity() >= count &&
          (best == kept_.size() || kept_[i].capacity() < kept_[best].capacity()))
        best = i;
    if (best < kept_.size()) {
      array = std::move(kept_[best]);
      kept_.erase(kept_.begin() + std::ptrdiff_t(best));
    }
  }
  array.resize(count);  // within a kept array's capacity: no new memory
  return array;
}

void SplatArrayPool::give(std::vector<Splat>&& splats) {
  if (splats.capacity() == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (kept_.size() < kKept) {
    kept_.push_back(std::move(splats));
    return;
  }
  // Full: the largest arrays stay (a later result needs at most as much as the largest so far).
  auto smallest = std::min_element(kept_.begin(), kept_.end(), [](const auto& a, const auto& b) {
    return a.capacity() < b.capacity();
  });
  if (smallest->capacity() < splats.capacity()) *smallest = std::move(splats);
}

void HostSplats::copyToHost(Splat* out) const {
  if (!splats_.empty()) std::memcpy(out, splats_.data(), splats_.size() * sizeof(Splat));
}

Bounds splatBounds(const SplatResource& splats) {
  Bounds b;
  const size_t n = splats.count();
  if (n == 0) return b;
  std::vector<Splat> copy;
  const Splat* data = splats.hostData();
  if (!data) {
    copy.resize(n);
    splats.copyToHost(copy.data());
    data = copy.data();
  }
  for (size_t i = 0; i < n; ++i)
    b.include(glm::dvec3(data[i].position[0], data[i].position[1], data[i].position[2]));
  return b;
}

}  // namespace strata
