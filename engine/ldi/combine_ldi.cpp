#include "engine/ldi/combine_ldi.h"

#include <algorithm>

#include "engine/ldi/sample_mesh.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {
constexpr int64_t kRayGrain = 8192;

void combineAxis(RayOp op, const std::vector<std::shared_ptr<const Ldi>>& children,
                 const Grid& grid, int axis, Progress* progress, AxisLdi* out) {
  const int64_t rays = grid.rayCount(axis);
  const int childCount = int(children.size());
  const int64_t chunkCount = (rays + kRayGrain - 1) / kRayGrain;
  std::vector<RayChunkOutput> chunks(static_cast<size_t>(chunkCount));
  parallelFor(0, rays, kRayGrain, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    RayChunkOutput& chunk = chunks[size_t(b / kRayGrain)];
    chunk.counts.resize(size_t(e - b));
    std::vector<RayEvent> events;
    for (int64_t r = b; r < e; ++r) {
      events.clear();
      for (int c = 0; c < childCount; ++c) {
        const AxisLdi& in = children[size_t(c)]->axes[axis];
        for (uint32_t k = in.offsets[size_t(r)]; k < in.offsets[size_t(r) + 1]; ++k) {
          const Surfel& s = in.surfels[k];
          events.push_back(RayEvent{s.depth, s.normal, s.tag, uint32_t(c)});
        }
      }
      // Each child's list is sorted; a stable sort by depth keeps equal depths in child order.
      std::stable_sort(events.begin(), events.end(),
                       [](const RayEvent& x, const RayEvent& y) { return x.depth < y.depth; });
      size_t at = chunk.surfels.size();
      chunk.surfels.resize(at + events.size());
      int written = combineRayEvents(op, childCount, events.data(), int(events.size()),
                                     chunk.surfels.data() + at);
      chunk.surfels.resize(at + size_t(written));
      chunk.counts[size_t(r - b)] = uint32_t(written);
    }
  });
  assembleAxis(chunks, rays, out, "Boolean");
}
}  // namespace

std::shared_ptr<Ldi> combineLdis(RayOp op, const std::vector<std::shared_ptr<const Ldi>>& children,
                                 const Grid& grid, Progress* progress) {
  for (const auto& c : children)
    if (!c || !(c->grid == grid)) throw Error("internal: combining LDIs of different grids");
  if (children.empty()) return makeEmptyLdi(grid);
  auto ldi = std::make_shared<Ldi>();
  ldi->grid = grid;
  for (int axis = 0; axis < 3; ++axis)
    combineAxis(op, children, grid, axis, progress, &ldi->axes[axis]);
  return ldi;
}

}  // namespace strata
