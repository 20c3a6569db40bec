#include "engine/geometry/mesh_distance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "engine/geometry/triangle_grid.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr int kMaxSteps = 4096;

struct OneWay {
  double largest = 0.0;
  size_t samples = 0;
  bool capped = false;
};

// The largest distance of samples of `from` to the surface `to` (found through its grid), each
// capped at the grid's reach.
OneWay measureOneWay(const TriangleMesh& from, const TriangleGrid& to, double spacing,
                     Progress& progress, const char* stage, double fractionFrom,
                     double fractionTo) {
  const int64_t count = int64_t(from.triangles.size());
  constexpr int64_t kBlock = 1 << 12;
  const int64_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<OneWay> perBlock(static_cast<size_t>(blocks));
  std::atomic<int64_t> done{0};
  parallelFor(0, blocks, 1, [&](int64_t first, int64_t last) {
    for (int64_t block = first; block < last; ++block) {
      progress.check();
      OneWay result;
      const int64_t end = std::min(count, (block + 1) * kBlock);
      for (int64_t t = block * kBlock; t < end; ++t) {
        const auto& tri = from.triangles[size_t(t)];
        const glm::dvec3 p0 = from.positions[tri[0]], p1 = from.positions[tri[1]],
                         p2 = from.positions[tri[2]];
        const double longest = std::sqrt(std::max(
            {glm::dot(p1 - p0, p1 - p0), glm::dot(p2 - p1, p2 - p1), glm::dot(p0 - p2, p0 - p2)}));
        // At most kMaxSteps per edge (a triangle 4096 spacings long is sampled more coarsely).
        const double steps = std::ceil(longest / spacing);  // NaN for a non-finite corner: 1
        const int n = steps >= 1.0 ? int(std::min(steps, double(kMaxSteps))) : 1;
        for (int i = 0; i <= n; ++i)
          for (int j = 0; i + j <= n; ++j) {
            const glm::dvec3 p = p0 + (p1 - p0) * (double(i) / n) + (p2 - p0) * (double(j) / n);
            const double d = to.nearest(p);
            result.largest = std::max(result.largest, d);
            result.capped = result.capped || d >= to.reach();
            ++result.samples;
          }
      }
      perBlock[size_t(block)] = result;
      const int64_t finished = done.fetch_add(1) + 1;
      if ((finished & 15) == 0 && !progress.cancelled())
        progress.report(
            stage, fractionFrom + (fractionTo - fractionFrom) * double(finished) / double(blocks));
    }
  });
  OneWay total;
  for (const OneWay& r : perBlock) {
    total.largest = std::max(total.largest, r.largest);
    total.samples += r.samples;
    total.capped = total.capped || r.capped;
  }
  return total;
}

}  // namespace

SurfaceDeviation measureDeviation(const TriangleMesh& a, const TriangleMesh& b, double spacing,
                                  double cap, Progress& progress, const char* stage,
                                  const TriangleGrid* aGrid, double from, double to) {
  SurfaceDeviation deviation;
  deviation.spacing = spacing;
  if (a.empty() || b.empty() || !(spacing > 0.0) || !(cap > 0.0)) return deviation;
  OneWay ab, ba;
  {
    const TriangleGrid bGrid(b.positions, b.triangles, cap);
    ab = measureOneWay(a, bGrid, spacing, progress, stage, from, 0.5 * (from + to));
  }
  if (aGrid) {
    ba = measureOneWay(b, *aGrid, spacing, progress, stage, 0.5 * (from + to), to);
  } else {
    const TriangleGrid grid(a.positions, a.triangles, cap);
    ba = measureOneWay(b, grid, spacing, progress, stage, 0.5 * (from + to), to);
  }
  deviation.aToB = ab.largest;
  deviation.bToA = ba.largest;
  deviation.samples = ab.samples + ba.samples;
  deviation.capped = ab.capped || ba.capped;
  return deviation;
}

}  // namespace strata
