#include "engine/ldi/ldi.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {

std::shared_ptr<Ldi> makeEmptyLdi(const Grid& grid) {
  auto ldi = std::make_shared<Ldi>();
  ldi->grid = grid;
  for (AxisLdi& axis : ldi->axes) {
    axis.whole = false;
    axis.window = RayWindow{};
    axis.offsets.assign(1, 0u);
  }
  return ldi;
}

RayWindow wholeWindow(const Grid& grid, int axis) {
  return RayWindow{0, 0, grid.raysU(axis), grid.raysV(axis)};
}

namespace {
// The offsets of every ray of the grid for a windowed axis: rays outside the window are empty.
std::vector<uint32_t> wholeOffsets(const Grid& grid, int axisIndex, const RayWindow& window,
                                   const std::vector<uint32_t>& windowOffsets) {
  const int raysU = grid.raysU(axisIndex), raysV = grid.raysV(axisIndex);
  std::vector<uint32_t> offsets(size_t(grid.rayCount(axisIndex)) + 1);
  uint32_t running = 0;
  size_t ray = 0;
  for (int j = 0; j < raysV; ++j) {
    for (int i = 0; i < raysU; ++i, ++ray) {
      if (window.contains(i, j)) {
        const size_t local = size_t(i - window.u0) + size_t(j - window.v0) * size_t(window.uCount);
        running = windowOffsets[local];
        offsets[ray] = running;
        running = windowOffsets[local + 1];
      } else {
        offsets[ray] = running;
      }
    }
  }
  offsets[ray] = windowOffsets.back();
  return offsets;
}
}  // namespace

std::shared_ptr<const Ldi> wholeLdi(std::shared_ptr<const Ldi> ldi) {
  if (ldi->axes[0].whole && ldi->axes[1].whole && ldi->axes[2].whole) return ldi;
  auto copy = std::make_shared<Ldi>(*ldi);
  for (int a = 0; a < 3; ++a) {
    AxisLdi& axis = copy->axes[a];
    if (axis.whole) continue;
    axis.offsets = wholeOffsets(copy->grid, a, axis.window, axis.offsets);
    axis.whole = true;
    axis.window = RayWindow{};
  }
  return copy;
}

RayShift rayShift(const Grid& grid, const Grid& window, int axis) {
  for (int k = 0; k < 3; ++k)
    if (window.first[k] < grid.first[k] ||
        window.first[k] + window.cells[k] > grid.first[k] + grid.cells[k] || window.h != grid.h ||
        window.origin != grid.origin)
      throw Error("cropping an LDI to a window outside its grid");
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  return RayShift{window.first[u] - grid.first[u], window.first[v] - grid.first[v]};
}

std::shared_ptr<Ldi> cropLdi(const std::shared_ptr<const Ldi>& ldi, const Grid& window) {
  const Ldi& in = *ldi;
  const std::shared_ptr<const Ldi> whole = wholeLdi(ldi);
  auto out = std::make_shared<Ldi>();
  out->grid = window;
  for (int a = 0; a < 3; ++a) {
    const RayShift shift = rayShift(in.grid, window, a);
    const AxisLdi& from = whole->axes[a];
    AxisLdi& to = out->axes[a];
    const int raysU = window.raysU(a), raysV = window.raysV(a), fromU = in.grid.raysU(a);
    const int64_t rays = int64_t(raysU) * raysV;
    to.offsets.resize(size_t(rays) + 1);
    uint64_t running = 0;
    for (int64_t r = 0; r < rays; ++r) {
      to.offsets[size_t(r)] = uint32_t(running);
      const int64_t s = shift.source(r, raysU, fromU);
      running += from.offsets[size_t(s) + 1] - from.offsets[size_t(s)];
    }
    checkSurfelCount(running, "a cropped LDI");
    to.offsets[size_t(rays)] = uint32_t(running);
    to.surfels.resize(size_t(running));
    parallelFor(0, rays, 4096, [&](int64_t b, int64_t e) {
      for (int64_t r = b; r < e; ++r) {
        const int64_t s = shift.source(r, raysU, fromU);
        std::copy(from.surfels.begin() + from.offsets[size_t(s)],
                  from.surfels.begin() + from.offsets[size_t(s) + 1],
                  to.surfels.begin() + to.offsets[size_t(r)]);
      }
    });
  }
  return out;
}

std::shared_ptr<Ldi> rewindowLdi(const std::shared_ptr<const Ldi>& ldi, const Grid& window) {
  const Ldi& in = *ldi;
  if (window.h != in.grid.h || window.origin != in.grid.origin)
    throw Error("rewindowing an LDI to a window of another lattice");
  auto out = std::make_shared<Ldi>();
  out->grid = window;
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const AxisLdi& from = in.axes[a];
    const RayWindow source = from.whole ? wholeWindow(in.grid, a) : from.window;
    // The source's rays in the new window's ray coordinates, and the part of them it holds.
    const int u0 = source.u0 + in.grid.first[u] - window.first[u];
    const int v0 = source.v0 + in.grid.first[v] - window.first[v];
    const int i0 = std::max(u0, 0), j0 = std::max(v0, 0);
    const int i1 = std::min(u0 + source.uCount, window.raysU(a));
    const int j1 = std::min(v0 + source.vCount, window.raysV(a));
    AxisLdi& to = out->axes[a];
    if (i1 <= i0 || j1 <= j0 || from.surfels.empty()) {
      to.whole = false;
      to.window = RayWindow{};
      to.offsets.assign(1, 0u);
      continue;
    }
    const RayWindow kept{i0, j0, i1 - i0, j1 - j0};
    if (kept.u0 == u0 && kept.v0 == v0 && kept.uCount == source.uCount &&
        kept.vCount == source.vCount) {
      to.offsets = from.offsets;  // every ray kept, in the same order
      to.surfels = from.surfels;
    } else {
      const int64_t rays = kept.rayCount();
      auto sourceRay = [&](int64_t r) {
        const int64_t i = r % kept.uCount + kept.u0 - u0, j = r / kept.uCount + kept.v0 - v0;
        return size_t(i + j * int64_t(source.uCount));
      };
      to.offsets.resize(size_t(rays) + 1);
      uint64_t running = 0;
      for (int64_t r = 0; r < rays; ++r) {
        to.offsets[size_t(r)] = uint32_t(running);
        const size_t s = sourceRay(r);
        running += from.offsets[s + 1] - from.offsets[s];
      }
      to.offsets[size_t(rays)] = uint32_t(running);
      to.surfels.resize(size_t(running));
      parallelFor(0, rays, 4096, [&](int64_t b, int64_t e) {
        for (int64_t r = b; r < e; ++r) {
          const size_t s = sourceRay(r);
          std::copy(from.surfels.begin() + from.offsets[s],
                    from.surfels.begin() + from.offsets[s + 1],
                    to.surfels.begin() + to.offsets[size_t(r)]);
        }
      });
    }
    settleAxisWindow(window, a, kept, &to);
  }
  return out;
}

void settleAxisWindow(const Grid& grid, int axisIndex, const RayWindow& window, AxisLdi* axis) {
  if (window.rayCount() * 2 > grid.rayCount(axisIndex)) {
    if (window.u0 != 0 || window.v0 != 0 || window.uCount != grid.raysU(axisIndex) ||
        window.vCount != grid.raysV(axisIndex))
      axis->offsets = wholeOffsets(grid, axisIndex, window, axis->offsets);
    axis->whole = true;
    axis->window = RayWindow{};
  } else {
    axis->whole = false;
    axis->window = window;
  }
}

void checkSurfelCount(uint64_t count, const char* what) {
  if (count > 0xffffffffull)
    throw Error(std::string(what) + ": " + std::to_string(count) +
                " surfels on one axis exceed the 2^32 limit; lower the resolution");
}

glm::dvec3 rayPoint(const Grid& grid, int axis, bool whole, const RayWindow& window, int64_t ray,
                    double depth) {
  const int u = grid.uAxis(axis), v = grid.vAxis(axis);
  const int64_t width = whole ? grid.raysU(axis) : window.uCount;
  const int64_t i = ray % width + (whole ? 0 : window.u0);
  const int64_t j = ray / width + (whole ? 0 : window.v0);
  glm::dvec3 p;
  p[axis] = grid.origin[axis] + grid.h * depth;
  p[u] = grid.origin[u] + grid.h * double(grid.first[u] + i);
  p[v] = grid.origin[v] + grid.h * double(grid.first[v] + j);
  return p;
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
    // The thinnest wall of each chunk: thickness, ray, depth (the first ray of a tie).
    std::vector<float> thinnest(size_t(chunks), INFINITY), thinnestDepth(size_t(chunks), 0.0f);
    std::vector<int64_t> thinnestRay(size_t(chunks), 0);
    parallelFor(0, rays, kGrain, [&](int64_t b, int64_t e) {
      double l = 0.0, s = 0.0;
      for (int64_t r = b; r < e; ++r) {
        float at = 0.0f;
        const float wall = rayThinnestWall(axis.surfels.data() + axis.offsets[r],
                                           axis.offsets[r + 1] - axis.offsets[r], a, &at);
        if (wall < thinnest[size_t(b / kGrain)]) {
          thinnest[size_t(b / kGrain)] = wall;
          thinnestDepth[size_t(b / kGrain)] = at;
          thinnestRay[size_t(b / kGrain)] = r;
        }
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
      if (double(thinnest[size_t(c)]) * h < m.thinnestWall) {
        m.thinnestWall = double(thinnest[size_t(c)]) * h;
        m.thinnestAt = rayPoint(ldi.grid, a, axis.whole, axis.window, thinnestRay[size_t(c)],
                                thinnestDepth[size_t(c)]);
      }
    }
    m.axisVolume[a] = totalLength * h * h * h;
    m.area += totalArea * h * h;
    m.surfels += axis.surfels.size();
  }
  m.volume = (m.axisVolume[0] + m.axisVolume[1] + m.axisVolume[2]) / 3.0;
  return m;
}

}  // namespace strata
