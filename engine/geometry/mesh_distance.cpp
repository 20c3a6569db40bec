#include "engine/geometry/mesh_distance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "engine/geometry/box_tree.h"
#include "engine/geometry/triangle_distance.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr int kMaxSteps = 4096;

struct OneWay {
  double largest = 0.0;
  size_t samples = 0;
  bool capped = false;
};

// The largest distance of samples of `from` to `to`, each capped at `cap`.
OneWay measureOneWay(const TriangleMesh& from, const TriangleMesh& to, double spacing, double cap,
                     Progress& progress, const char* stage, double progressBase) {
  // Boxes of `to` grown by the cap: the triangles within `cap` of a point are among those whose
  // grown box holds it.
  std::vector<Bounds> boxes(to.triangles.size());
  parallelFor(0, int64_t(to.triangles.size()), 1 << 14, [&](int64_t begin, int64_t end) {
    for (int64_t t = begin; t < end; ++t) {
      Bounds box;
      for (uint32_t v : to.triangles[t]) box.include(to.positions[v]);
      box.min -= glm::dvec3(cap);
      box.max += glm::dvec3(cap);
      boxes[t] = box;
    }
  });
  const BoxTree tree(boxes);
  const double cap2 = cap * cap;
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
        const auto& tri = from.triangles[t];
        const glm::dvec3 p0 = from.positions[tri[0]], p1 = from.positions[tri[1]],
                         p2 = from.positions[tri[2]];
        const double longest = std::sqrt(std::max(
            {glm::dot(p1 - p0, p1 - p0), glm::dot(p2 - p1, p2 - p1), glm::dot(p0 - p2, p0 - p2)}));
        // At most kMaxSteps per edge (a triangle 4096 spacings long is sampled more coarsely).
        const int n = int(std::clamp(std::ceil(longest / spacing), 1.0, double(kMaxSteps)));
        for (int i = 0; i <= n; ++i)
          for (int j = 0; i + j <= n; ++j) {
            const double u = double(i) / n, v = double(j) / n;
            const glm::dvec3 p = p0 + u * (p1 - p0) + v * (p2 - p0);
            double best = cap2;
            bool found = false;
            tree.forEachContaining(p, [&](uint32_t k) {
              const auto& other = to.triangles[k];
              const double d2 = pointTriangleDistanceSquared(
                  p, to.positions[other[0]], to.positions[other[1]], to.positions[other[2]]);
              if (d2 <= best) {
                best = d2;
                found = true;
              }
            });
            result.largest = std::max(result.largest, std::sqrt(best));
            result.capped = result.capped || !found;
            ++result.samples;
          }
      }
      perBlock[size_t(block)] = result;
      const int64_t finished = done.fetch_add(1) + 1;
      if ((finished & 15) == 0 && !progress.cancelled())
        progress.report(stage, progressBase + 0.5 * double(finished) / double(blocks));
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
                                  double cap, Progress& progress, const char* stage) {
  SurfaceDeviation deviation;
  deviation.spacing = spacing;
  if (a.empty() || b.empty() || !(spacing > 0.0) || !(cap > 0.0)) return deviation;
  const OneWay ab = measureOneWay(a, b, spacing, cap, progress, stage, 0.0);
  const OneWay ba = measureOneWay(b, a, spacing, cap, progress, stage, 0.5);
  deviation.aToB = ab.largest;
  deviation.bToA = ba.largest;
  deviation.samples = ab.samples + ba.samples;
  deviation.capped = ab.capped || ba.capped;
  return deviation;
}

}  // namespace strata
