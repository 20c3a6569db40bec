#include "engine/ldi/combine_ldi.h"

#include <algorithm>

#include "engine/ldi/sample_mesh.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {
constexpr int64_t kRayGrain = 8192;
// Rays with more events than this are sorted by std::stable_sort instead of by insertion: the
// same order (by depth, ties in gather order), without the quadratic worst case of a ray that
// crosses thousands of children.
constexpr int kInsertionSortLimit = 48;

RayWindow windowOf(const AxisLdi& a, const Grid& grid, int axis) {
  return a.whole ? wholeWindow(grid, axis) : a.window;
}

RayWindow unite(const RayWindow& a, const RayWindow& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  const int u0 = std::min(a.u0, b.u0), v0 = std::min(a.v0, b.v0);
  const int u1 = std::max(a.u0 + a.uCount, b.u0 + b.uCount);
  const int v1 = std::max(a.v0 + a.vCount, b.v0 + b.vCount);
  return RayWindow{u0, v0, u1 - u0, v1 - v0};
}

RayWindow intersect(const RayWindow& a, const RayWindow& b) {
  const int u0 = std::max(a.u0, b.u0), v0 = std::max(a.v0, b.v0);
  const int u1 = std::min(a.u0 + a.uCount, b.u0 + b.uCount);
  const int v1 = std::min(a.v0 + a.vCount, b.v0 + b.vCount);
  if (u1 <= u0 || v1 <= v0) return RayWindow{};
  return RayWindow{u0, v0, u1 - u0, v1 - v0};
}

// The rays where the node can have surfels: where any child has (union), where all have
// (intersection), where the first has (difference).
RayWindow outputWindow(RayOp op, const std::vector<std::shared_ptr<const Ldi>>& children,
                       const Grid& grid, int axis) {
  RayWindow w = windowOf(children[0]->axes[axis], grid, axis);
  if (op == RayOp::Difference) return w;
  for (size_t c = 1; c < children.size(); ++c) {
    const RayWindow cw = windowOf(children[c]->axes[axis], grid, axis);
    w = op == RayOp::Union ? unite(w, cw) : intersect(w, cw);
  }
  return w;
}

// Which windowed children have surfels on each ray of the output window, in child order (CSR
// over the window's local rays). Whole children are not listed: every ray visits them. Costs
// the windowed children's rays, not rays x children.
struct RayCandidates {
  std::vector<uint64_t> offsets;
  std::vector<uint32_t> children;
};

template <typename Visit>
void forEachWindowedRay(const AxisLdi& a, const RayWindow& out, Visit&& visit) {
  const RayWindow w = intersect(a.window, out);
  for (int j = w.v0; j < w.v0 + w.vCount; ++j)
    for (int i = w.u0; i < w.u0 + w.uCount; ++i) {
      const size_t local = size_t(i - a.window.u0) + size_t(j - a.window.v0) * a.window.uCount;
      if (a.offsets[local + 1] > a.offsets[local])
        visit(size_t(i - out.u0) + size_t(j - out.v0) * size_t(out.uCount));
    }
}

RayCandidates windowedCandidates(const std::vector<const AxisLdi*>& axes, const RayWindow& out) {
  RayCandidates rc;
  // All children whole (every Boolean of big parts): no lists, and no counters for every ray.
  if (std::all_of(axes.begin(), axes.end(), [](const AxisLdi* a) { return a->whole; })) return rc;
  rc.offsets.assign(size_t(out.rayCount()) + 1, 0);
  for (const AxisLdi* a : axes) {
    if (a->whole) continue;
    forEachWindowedRay(*a, out, [&](size_t ray) { ++rc.offsets[ray + 1]; });
  }
  for (size_t r = 0; r + 1 < rc.offsets.size(); ++r) rc.offsets[r + 1] += rc.offsets[r];
  rc.children.resize(size_t(rc.offsets.back()));
  std::vector<uint64_t> cursor(rc.offsets.begin(), rc.offsets.end() - 1);
  for (uint32_t c = 0; c < axes.size(); ++c) {
    if (axes[c]->whole) continue;
    forEachWindowedRay(*axes[c], out, [&](size_t ray) { rc.children[cursor[ray]++] = c; });
  }
  return rc;
}

// Appends the surfels of grid ray (i, j) of child c to events.
void appendChildRay(const AxisLdi& a, int raysU, uint32_t c, int i, int j,
                    std::vector<RayEvent>& events) {
  size_t ray;
  if (a.whole) {
    ray = size_t(i) + size_t(j) * size_t(raysU);
  } else {
    if (!a.window.contains(i, j)) return;
    ray = size_t(i - a.window.u0) + size_t(j - a.window.v0) * size_t(a.window.uCount);
  }
  for (uint32_t k = a.offsets[ray]; k < a.offsets[ray + 1]; ++k) {
    const Surfel& s = a.surfels[k];
    events.push_back(RayEvent{s.depth, s.normal, s.tag, c});
  }
}

void combineAxis(RayOp op, const std::vector<std::shared_ptr<const Ldi>>& children,
                 const Grid& grid, int axis, Progress* progress, AxisLdi* out) {
  const int childCount = int(children.size());
  std::vector<const AxisLdi*> axes;
  std::vector<uint32_t> wholeChildren;  // in child order
  for (uint32_t c = 0; c < children.size(); ++c) {
    axes.push_back(&children[c]->axes[axis]);
    if (axes.back()->whole) wholeChildren.push_back(c);
  }
  const RayWindow window = outputWindow(op, children, grid, axis);
  const RayCandidates candidates = windowedCandidates(axes, window);
  const int64_t rays = window.rayCount();
  const int raysU = grid.raysU(axis);
  const int64_t chunkCount = (rays + kRayGrain - 1) / kRayGrain;
  std::vector<RayChunkOutput> chunks(static_cast<size_t>(chunkCount));
  parallelFor(0, rays, kRayGrain, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    RayChunkOutput& chunk = chunks[size_t(b / kRayGrain)];
    chunk.counts.resize(size_t(e - b));
    std::vector<RayEvent> events;
    for (int64_t r = b; r < e; ++r) {
      const int i = window.u0 + int(r % window.uCount), j = window.v0 + int(r / window.uCount);
      // Children in child order: the whole ones merged with this ray's windowed candidates.
      events.clear();
      const uint32_t* cand = candidates.children.data();
      size_t k = candidates.offsets.empty() ? 0 : candidates.offsets[size_t(r)];
      const size_t kEnd = candidates.offsets.empty() ? 0 : candidates.offsets[size_t(r) + 1];
      size_t w = 0;
      while (w < wholeChildren.size() || k < kEnd) {
        const bool takeWhole =
            k >= kEnd || (w < wholeChildren.size() && wholeChildren[w] < cand[k]);
        const uint32_t c = takeWhole ? wholeChildren[w++] : cand[k++];
        appendChildRay(*axes[c], raysU, c, i, j, events);
      }
      const int n = int(events.size());
      if (n <= kInsertionSortLimit) {
        sortRayEvents(events.data(), n);
      } else {
        std::stable_sort(events.begin(), events.end(),
                         [](const RayEvent& x, const RayEvent& y) { return x.depth < y.depth; });
      }
      size_t at = chunk.surfels.size();
      chunk.surfels.resize(at + size_t(n));
      int written = combineRayEvents(op, childCount, events.data(), n, chunk.surfels.data() + at);
      chunk.surfels.resize(at + size_t(written));
      chunk.counts[size_t(r - b)] = uint32_t(written);
    }
  });
  assembleAxis(chunks, rays, out, "Boolean");
  settleAxisWindow(grid, axis, window, out);
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
