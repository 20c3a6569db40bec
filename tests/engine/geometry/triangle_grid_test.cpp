// TriangleGrid: its answers (distances and the nearest triangle) match a loop over every triangle,
// for points near and far from a random soup of triangles of mixed sizes (a few large ones among
// many small).
#include "engine/geometry/triangle_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/geometry/triangle_distance.h"

namespace strata::test {
namespace {

TEST(TriangleGrid, MatchesALoopOverEveryTriangle) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<glm::dvec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  for (int t = 0; t < 400; ++t) {
    const double size = t % 50 == 0 ? 0.6 : 0.04;
    const glm::dvec3 at(unit(random), unit(random), unit(random));
    const uint32_t b = uint32_t(positions.size());
    for (int k = 0; k < 3; ++k)
      positions.push_back(at + size * glm::dvec3(unit(random), unit(random), unit(random)));
    triangles.push_back({b, b + 1, b + 2});
  }
  const double reach = 0.05;
  const TriangleGrid grid(positions, triangles, reach);
  for (int q = 0; q < 2000; ++q) {
    const glm::dvec3 p(1.2 * unit(random) - 0.1, 1.2 * unit(random) - 0.1,
                       1.2 * unit(random) - 0.1);
    double best = INFINITY;
    for (const auto& t : triangles)
      best = std::min(best, std::sqrt(pointTriangleDistanceSquared(
                                p, positions[t[0]], positions[t[1]], positions[t[2]])));
    EXPECT_DOUBLE_EQ(grid.nearest(p), std::min(best, reach)) << q;
    // The index names a triangle at that distance, or none beyond the reach.
    uint32_t index = 0;
    const double d = grid.nearest(p, &index);
    if (best < reach) {
      ASSERT_LT(index, triangles.size()) << q;
      EXPECT_DOUBLE_EQ(grid.distanceTo(p, index), d) << q;
    } else {
      EXPECT_EQ(index, UINT32_MAX) << q;
    }
    EXPECT_EQ(grid.within(p, 0.02), best <= 0.02) << q;
    EXPECT_EQ(grid.within(p, reach), best <= reach) << q;
    // A hint, right or wrong, changes nothing but where the search starts; a found triangle is
    // handed back in it.
    uint32_t hint = uint32_t(q % int(triangles.size()));
    EXPECT_EQ(grid.within(p, 0.02, &hint), best <= 0.02) << q;
    if (best <= 0.02) {
      EXPECT_LE(grid.distanceTo(p, hint), 0.02) << q;
    }
  }
}

// The distance by an independent route: the plane where the point projects inside the
// triangle (barycentric weights from a 2x2 solve), else the nearest edge.
double referenceDistanceSquared(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                const glm::dvec3& c) {
  const glm::dvec3 u = b - a, v = c - a, w = p - a;
  const double uu = glm::dot(u, u), uv = glm::dot(u, v), vv = glm::dot(v, v);
  const double det = uu * vv - uv * uv;
  const double s = (vv * glm::dot(w, u) - uv * glm::dot(w, v)) / det;
  const double t = (uu * glm::dot(w, v) - uv * glm::dot(w, u)) / det;
  if (s >= 0.0 && t >= 0.0 && s + t <= 1.0) {
    const glm::dvec3 q = a + s * u + t * v;
    return glm::dot(p - q, p - q);
  }
  return std::min({pointSegmentDistanceSquared(p, a, b), pointSegmentDistanceSquared(p, b, c),
                   pointSegmentDistanceSquared(p, c, a)});
}

TEST(TriangleDistance, MatchesAnIndependentRouteInsideOutsideAndFar) {
  // Well-shaped, skinny and needle triangles; points near the face (inside and beyond each
  // edge and corner), on the edges, and far off.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int inside = 0;
  for (int k = 0; k < 300; ++k) {
    const double skinny = k % 3 == 0 ? 1.0 : k % 3 == 1 ? 1e-2 : 1e-4;
    const glm::dvec3 a(unit(random), unit(random), unit(random));
    const glm::dvec3 b = a + glm::dvec3(1.0 + unit(random), 0.3 * unit(random), 0.3 * unit(random));
    const glm::dvec3 c =
        a + 0.5 * (b - a) + skinny * glm::dvec3(0.2 * unit(random), 1.0, 0.2 * unit(random));
    const TriangleDistance prepared(a, b, c);
    for (int q = 0; q < 200; ++q) {
      const double s = 0.5 + 0.8 * unit(random), t = 0.5 + 0.8 * unit(random);
      const double off = q % 4 == 0 ? 50.0 : 0.05;
      const glm::dvec3 p = a + s * (b - a) + t * (c - a) - (q % 2) * 0.5 * s * (c - a) +
                           off * glm::dvec3(unit(random), unit(random), unit(random));
      const double reference = referenceDistanceSquared(p, a, b, c);
      const double got = prepared.squared(p);
      EXPECT_NEAR(got, reference, 1e-9 * (1.0 + reference)) << k << " " << q;
      EXPECT_EQ(got, prepared.squaredByRegions(p)) << k << " " << q;  // the same bits
      inside += reference < 0.0025 ? 1 : 0;
    }
  }
  EXPECT_GT(inside, 1000);  // the face's own region was exercised, not only edges and corners
  // Slivers, and points a hair inside their long edges, where the regions' rounding decides
  // between the edge and the plane: the same bits as the regions.
  for (int k = 0; k < 200; ++k) {
    const glm::dvec3 a(unit(random), unit(random), unit(random));
    const glm::dvec3 b = a + glm::dvec3(1.0, 0.2 * unit(random), 0.2 * unit(random));
    const glm::dvec3 c = a + 0.5 * (b - a) + 1e-6 * glm::dvec3(unit(random), 1.0, unit(random));
    const TriangleDistance prepared(a, b, c);
    for (int q = 0; q < 200; ++q) {
      const double s = 0.5 + 0.45 * unit(random), t = std::ldexp(1.0, -(q % 40)) * 1e-2;
      const glm::dvec3 p = a + s * (b - a) + t * (c - a) - 0.5 * t * (b - a) +
                           1e-9 * glm::dvec3(unit(random), unit(random), unit(random));
      EXPECT_EQ(prepared.squared(p), prepared.squaredByRegions(p)) << k << " " << q;
    }
  }
}

TEST(TriangleDistance, DegenerateTrianglesAreTheirEdges) {
  // All three corners on a line: the distance to the segment they span.
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared({1.5, 1, 0}, a, b, c), 1.0);
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared({3, 0, 0}, a, b, c), 1.0);
  // A point: the distance to it.
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared({0, 0, 2}, a, a, a), 4.0);
}

}  // namespace
}  // namespace strata::test
