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

// A triangle is split at most this many times over (2^-20 of its size; the accuracy ends it
// long before, but for non-finite corners).
constexpr int kMaxDepth = 20;

struct OneWay {
  double largest = 0.0;  // at a point
  double bound = 0.0;    // proven
  size_t samples = 0;
  bool capped = false;
};

struct Corner {
  glm::dvec3 p;
  double d;     // distance to the other surface (capped at its reach)
  uint32_t at;  // the nearest triangle there, UINT32_MAX beyond reach
};

// The proven largest distance of a point of triangle (q0, q1, q2) from the surface in `to`.
double triangleBound(const Corner (&q)[3], const TriangleGrid& to) {
  const double longest = std::sqrt(std::max({glm::dot(q[1].p - q[0].p, q[1].p - q[0].p),
                                             glm::dot(q[2].p - q[1].p, q[2].p - q[1].p),
                                             glm::dot(q[0].p - q[2].p, q[0].p - q[2].p)}));
  double bound = std::max({q[0].d, q[1].d, q[2].d}) + longest / std::sqrt(3.0);
  for (int k = 0; k < 3; ++k) {
    const uint32_t t = q[k].at;
    if (t == UINT32_MAX || (k > 0 && t == q[0].at) || (k > 1 && t == q[1].at)) continue;
    double onTriangle = q[k].d;  // the distance to t at corner k (t is nearest there)
    for (int m = 0; m < 3 && onTriangle < bound; ++m)
      if (m != k) onTriangle = std::max(onTriangle, to.distanceTo(q[m].p, t));
    bound = std::min(bound, onTriangle);
  }
  return bound;
}

// The largest distance of `from`'s points to the surface `to` (found through its grid), found
// and bounded; each capped at the grid's reach.
OneWay measureOneWay(const TriangleMesh& from, const TriangleGrid& to, double accuracy,
                     double enough, Progress& progress, const char* stage, double fractionFrom,
                     double fractionTo) {
  // The corners first: their largest distance is where splitting stops for every triangle.
  const int64_t vertices = int64_t(from.positions.size());
  std::vector<Corner> corners(from.positions.size());
  parallelFor(0, vertices, 1 << 12, [&](int64_t first, int64_t last) {
    progress.check();
    for (int64_t v = first; v < last; ++v) {
      Corner& c = corners[size_t(v)];
      c.p = from.positions[size_t(v)];
      c.d = to.nearest(c.p, &c.at);
    }
  });
  double floor = enough;
  for (const Corner& c : corners) floor = std::max(floor, c.d);

  const int64_t count = int64_t(from.triangles.size());
  constexpr int64_t kBlock = 1 << 12;
  const int64_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<OneWay> perBlock(static_cast<size_t>(blocks));
  std::atomic<int64_t> done{0};
  parallelFor(0, blocks, 1, [&](int64_t first, int64_t last) {
    struct Item {
      Corner q[3];
      int depth;
    };
    std::vector<Item> stack;
    for (int64_t block = first; block < last; ++block) {
      progress.check();
      OneWay result;
      const int64_t end = std::min(count, (block + 1) * kBlock);
      for (int64_t t = block * kBlock; t < end; ++t) {
        const auto& tri = from.triangles[size_t(t)];
        stack.push_back({{corners[tri[0]], corners[tri[1]], corners[tri[2]]}, 0});
        while (!stack.empty()) {
          const Item item = stack.back();
          stack.pop_back();
          const Corner(&q)[3] = item.q;
          const double found = std::max({q[0].d, q[1].d, q[2].d});
          result.largest = std::max(result.largest, found);
          if (found >= to.reach()) {  // capped: the true distance is beyond what we measure
            result.bound = std::max(result.bound, to.reach());
            continue;
          }
          const double bound = triangleBound(q, to);
          if (bound <= floor || bound - found <= accuracy || item.depth >= kMaxDepth ||
              !std::isfinite(bound)) {
            result.bound = std::max(result.bound, std::isfinite(bound) ? bound : to.reach());
            continue;
          }
          Corner mid[3];
          for (int k = 0; k < 3; ++k) {
            mid[k].p = 0.5 * (q[k].p + q[(k + 1) % 3].p);
            mid[k].d = to.nearest(mid[k].p, &mid[k].at);
            result.capped = result.capped || mid[k].d >= to.reach();
          }
          result.samples += 3;
          const int depth = item.depth + 1;
          stack.push_back({{q[0], mid[0], mid[2]}, depth});
          stack.push_back({{mid[0], q[1], mid[1]}, depth});
          stack.push_back({{mid[2], mid[1], q[2]}, depth});
          stack.push_back({{mid[0], mid[1], mid[2]}, depth});
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
  total.samples = corners.size();
  for (const Corner& c : corners) {
    total.largest = std::max(total.largest, c.d);
    total.capped = total.capped || c.d >= to.reach();
  }
  for (const OneWay& r : perBlock) {
    total.largest = std::max(total.largest, r.largest);
    total.bound = std::max(total.bound, r.bound);
    total.samples += r.samples;
    total.capped = total.capped || r.capped;
  }
  total.bound = std::max(total.bound, total.largest);
  return total;
}

}  // namespace

SurfaceDeviation measureDeviation(const TriangleMesh& a, const TriangleMesh& b, double accuracy,
                                  double cap, double enough, Progress& progress, const char* stage,
                                  const TriangleGrid* aGrid, double from, double to) {
  SurfaceDeviation deviation;
  deviation.accuracy = accuracy;
  if (a.empty() || b.empty() || !(accuracy > 0.0) || !(cap > 0.0)) return deviation;
  OneWay ab, ba;
  {
    const TriangleGrid bGrid(b.positions, b.triangles, cap);
    ab = measureOneWay(a, bGrid, accuracy, enough, progress, stage, from, 0.5 * (from + to));
  }
  if (aGrid) {
    ba = measureOneWay(b, *aGrid, accuracy, enough, progress, stage, 0.5 * (from + to), to);
  } else {
    const TriangleGrid grid(a.positions, a.triangles, cap);
    ba = measureOneWay(b, grid, accuracy, enough, progress, stage, 0.5 * (from + to), to);
  }
  deviation.aToB = ab.largest;
  deviation.bToA = ba.largest;
  deviation.aToBBound = ab.bound;
  deviation.bToABound = ba.bound;
  deviation.samples = ab.samples + ba.samples;
  deviation.capped = ab.capped || ba.capped;
  return deviation;
}

}  // namespace strata
