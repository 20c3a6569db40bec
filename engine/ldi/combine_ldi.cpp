#include "engine/ldi/combine_ldi.h"

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
  std::vector<AxisLdiView> views;
  for (const auto& c : children)
    views.push_back(AxisLdiView{c->axes[axis].offsets.data(), c->axes[axis].surfels.data()});
  const int64_t chunkCount = (rays + kRayGrain - 1) / kRayGrain;
  std::vector<RayChunkOutput> chunks(static_cast<size_t>(chunkCount));
  parallelFor(0, rays, kRayGrain, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    RayChunkOutput& chunk = chunks[size_t(b / kRayGrain)];
    chunk.counts.resize(size_t(e - b));
    std::vector<RayEvent> events;
    for (int64_t r = b; r < e; ++r) {
      events.resize(size_t(rayEventCount(views.data(), childCount, r)));
      const int n = gatherRayEvents(views.data(), childCount, r, events.data());
      size_t at = chunk.surfels.size();
      chunk.surfels.resize(at + size_t(n));
      int written = combineRayEvents(op, childCount, events.data(), n, chunk.surfels.data() + at);
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
