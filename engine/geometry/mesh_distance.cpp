#include "engine/geometry/mesh_distance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <vector>

#include <glm/geometric.hpp>

#include "engine/geometry/triangle_grid.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

// A triangle is halved at most this many times over (2^-20 of its size after 60; the accuracy
// ends it long before, but for non-finite corners).
constexpr int kMaxDepth = 60;

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
  // The farthest a point of the triangle can be from its nearest corner: the circumradius of
  // an acute triangle, else half the longest edge.
  const double e0 = glm::dot(q[1].p - q[0].p, q[1].p - q[0].p);
  const double e1 = glm::dot(q[2].p - q[1].p, q[2].p - q[1].p);
  const double e2 = glm::dot(q[0].p - q[2].p, q[0].p - q[2].p);
  const double longest2 = std::max({e0, e1, e2});
  const double area2 = glm::dot(glm::cross(q[1].p - q[0].p, q[2].p - q[0].p),
                                glm::cross(q[1].p - q[0].p, q[2].p - q[0].p));  // (2 area)^2
  const bool obtuse = 2.0 * longest2 >= e0 + e1 + e2;  // the longest squared >= the other two
  const double cover = obtuse || !(area2 > 0.0)
                           ? 0.5 * std::sqrt(longest2)
                           : std::sqrt(e0 * e1 * e2 / (4.0 * area2));  // abc / (4 area)
  double bound = std::max({q[0].d, q[1].d, q[2].d}) + std::min(cover, std::sqrt(longest2));
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

// The flat-region bound, for a closed surface `to`: when every triangle listed near S (the grid's
// cells S passes through: all those within reach of it) faces within 60 degrees of the plane P
// of the triangle nearest to S's first corner and lies within eta of P, the surface there is one
// sheet over P (a closed surface has no edge; a step, a groove or a sheet facing the other way
// would need triangles that fail the test), so each point of S has a point of it within
// |s_P| + eta, and the signed distance s_P is affine: largest at a corner. INFINITY when the
// test fails or cannot improve on `better`.
double flatBound(const Corner (&q)[3], const TriangleGrid& to, double better) {
  constexpr long kCellLimit = 512;
  const uint32_t base = q[0].at;
  if (base == UINT32_MAX) return INFINITY;
  const glm::dvec3 a = to.corner(base, 0);
  glm::dvec3 normal = glm::cross(to.corner(base, 1) - a, to.corner(base, 2) - a);
  const double length = glm::length(normal);
  if (!(length > 0.0) || !std::isfinite(length)) return INFINITY;
  normal /= length;
  double corners = 0.0;
  for (const Corner& c : q) corners = std::max(corners, std::abs(glm::dot(c.p - a, normal)));
  double eta = 0.0;
  // eta must stay below it: the sheet is known within reach of the piece, and the argument
  // reaches from a corner's nearest point, up to sqrt(3) corner distances sideways of it.
  const double slack = std::min(better, 0.5 * to.reach()) - corners;
  if (!(slack > 0.0)) return INFINITY;
  const bool flat = to.visitNear(q[0].p, q[1].p, q[2].p, kCellLimit, [&](uint32_t t) {
    const glm::dvec3 p0 = to.corner(t, 0), p1 = to.corner(t, 1), p2 = to.corner(t, 2);
    const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
    const double n2 = glm::dot(n, n);
    const double facing = glm::dot(n, normal);
    if (!(facing > 0.0 && facing * facing >= 0.25 * n2)) return false;  // beyond 60 degrees
    eta = std::max({eta, std::abs(glm::dot(p0 - a, normal)), std::abs(glm::dot(p1 - a, normal)),
                    std::abs(glm::dot(p2 - a, normal))});
    return eta < slack;
  });
  return flat ? corners + eta : INFINITY;
}

// The largest distance of `from`'s points to the surface `to` (found through its grid), found
// and bounded; each capped at the grid's reach. `closed`: `to` is a closed surface (flatBound).
OneWay measureOneWay(const TriangleMesh& from, const TriangleGrid& to, bool closed, double accuracy,
                     double enough, Progress& progress, const char* stage, double fractionFrom,
                     double fractionTo) {
  // The corners first: their largest distance is where splitting stops for every triangle.
  const int64_t vertices = int64_t(from.positions.size());
  std::vector<Corner> corners(from.positions.size());
  std::vector<uint8_t> used(from.positions.size(), 0);  // a vertex no triangle uses is no point
  for (const auto& tri : from.triangles)
    for (uint32_t v : tri) used[v] = 1;
  parallelFor(0, vertices, 1 << 12, [&](int64_t first, int64_t last) {
    progress.check();
    for (int64_t v = first; v < last; ++v) {
      Corner& c = corners[size_t(v)];
      c.p = from.positions[size_t(v)];
      c.d = used[size_t(v)] ? to.nearest(c.p, &c.at) : 0.0;
      if (!used[size_t(v)]) c.at = UINT32_MAX;
    }
  });
  double floor = enough;
  for (const Corner& c : corners) floor = std::max(floor, c.d);

  const int64_t count = int64_t(from.triangles.size());
  constexpr int64_t kBlock = 1 << 12;
  const int64_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<OneWay> perBlock(static_cast<size_t>(blocks));
  std::atomic<int64_t> done{0};
  std::mutex reporting;  // the fraction reported never goes back
  int64_t reported = 0;
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
          double bound = triangleBound(q, to);
          if (closed && bound > floor && bound - found > accuracy)
            bound = std::min(bound, flatBound(q, to, bound));
          if (!std::isfinite(bound)) {  // a non-finite corner: nothing is proven
            result.bound = std::max(result.bound, to.reach());
            result.capped = true;
            continue;
          }
          if (bound <= floor || bound - found <= accuracy || item.depth >= kMaxDepth) {
            result.bound = std::max(result.bound, bound);
            continue;
          }
          // Halved across its longest edge (a sliver along a curved surface splits in length
          // only).
          int k = 0;
          double longest2 = -1.0;
          for (int e = 0; e < 3; ++e) {
            const glm::dvec3 d = q[(e + 1) % 3].p - q[e].p;
            if (glm::dot(d, d) > longest2) {
              longest2 = glm::dot(d, d);
              k = e;
            }
          }
          Corner mid;
          mid.p = 0.5 * (q[k].p + q[(k + 1) % 3].p);
          mid.d = to.nearest(mid.p, &mid.at);
          result.capped = result.capped || mid.d >= to.reach();
          ++result.samples;
          const int depth = item.depth + 1;
          stack.push_back({{q[k], mid, q[(k + 2) % 3]}, depth});
          stack.push_back({{mid, q[(k + 1) % 3], q[(k + 2) % 3]}, depth});
        }
      }
      perBlock[size_t(block)] = result;
      const int64_t finished = done.fetch_add(1) + 1;
      if ((finished & 15) == 0 && !progress.cancelled()) {
        std::lock_guard<std::mutex> lock(reporting);
        if (finished > reported) {
          reported = finished;
          progress.report(stage, fractionFrom + (fractionTo - fractionFrom) * double(finished) /
                                                    double(blocks));
        }
      }
    }
  });
  OneWay total;
  for (size_t v = 0; v < corners.size(); ++v) {
    if (!used[v]) continue;
    const Corner& c = corners[v];
    ++total.samples;
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

SurfaceDeviation measureDeviation(const TriangleMesh& a, const TriangleMesh& b, bool closed,
                                  double accuracy, double cap, double enough, Progress& progress,
                                  const char* stage, const TriangleGrid* aGrid, double from,
                                  double to) {
  SurfaceDeviation deviation;
  deviation.accuracy = accuracy;
  if (a.empty() || b.empty() || !(accuracy > 0.0) || !(cap > 0.0)) return deviation;
  OneWay ab, ba;
  {
    const TriangleGrid bGrid(b.positions, b.triangles, cap, &progress);
    ab =
        measureOneWay(a, bGrid, closed, accuracy, enough, progress, stage, from, 0.5 * (from + to));
  }
  if (aGrid) {
    ba = measureOneWay(b, *aGrid, closed, accuracy, enough, progress, stage, 0.5 * (from + to), to);
  } else {
    const TriangleGrid grid(a.positions, a.triangles, cap, &progress);
    ba = measureOneWay(b, grid, closed, accuracy, enough, progress, stage, 0.5 * (from + to), to);
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
