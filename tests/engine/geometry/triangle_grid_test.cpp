// TriangleGrid: its answers (distances and the nearest triangle) match a loop over every triangle,
// for points near and far from a random soup of triangles of mixed sizes (a few large ones among
// many small).
#include "engine/geometry/triangle_grid.h"

#include <gtest/gtest.h>

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
