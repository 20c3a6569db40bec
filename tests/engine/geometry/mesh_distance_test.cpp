// measureDeviation: two parallel squares a known distance apart measure that distance both
// ways; a square off the edge of the other measures its farthest corner; a hole in the other
// surface, far from every corner, is found and bounded; a flat region of a closed surface is
// bounded with few points, but a dent in it is still found; one beyond the search radius is
// flagged as capped; the result does not depend on the thread count.
#include "engine/geometry/mesh_distance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/geometry/triangle_distance.h"
#include "engine/util/parallel_for.h"

namespace strata::test {
namespace {

TriangleMesh square(double z, double size, glm::dvec3 shift = glm::dvec3(0.0)) {
  TriangleMesh m;
  m.positions = {glm::dvec3(0, 0, z) + shift, glm::dvec3(size, 0, z) + shift,
                 glm::dvec3(size, size, z) + shift, glm::dvec3(0, size, z) + shift};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(MeshDistance, ParallelSquaresAreTheirGapApart) {
  Progress progress;
  const SurfaceDeviation d =
      measureDeviation(square(0, 1), square(0.125, 1), false, 0.1, 1.0, 0.0, progress);
  EXPECT_NEAR(d.aToB, 0.125, 1e-12);
  EXPECT_NEAR(d.bToA, 0.125, 1e-12);
  EXPECT_NEAR(d.aToBBound, 0.125, 1e-12);  // one plane: exact, nothing split
  EXPECT_NEAR(d.bound(), 0.125, 1e-12);
  EXPECT_FALSE(d.capped);
  EXPECT_EQ(d.samples, 8u);
}

// A frame: the unit square with the square hole [0.5 - r, 0.5 + r]^2 cut out, in z = 0.
TriangleMesh frame(double r) {
  TriangleMesh m;
  const double lo = 0.5 - r, hi = 0.5 + r;
  m.positions = {{0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},
                 {lo, lo, 0}, {hi, lo, 0}, {hi, hi, 0}, {lo, hi, 0}};
  for (uint32_t k = 0; k < 4; ++k) {
    const uint32_t next = (k + 1) % 4;
    m.triangles.push_back({k, next, 4 + next});
    m.triangles.push_back({k, 4 + next, 4 + k});
  }
  return m;
}

TEST(MeshDistance, AHoleFarFromEveryCornerIsFoundAndBounded) {
  Progress progress;
  // The square's corners all lie on the frame; its centre is 0.1 from the frame's inner edge.
  const double accuracy = 0.002;
  const SurfaceDeviation d =
      measureDeviation(square(0, 1), frame(0.1), false, accuracy, 1.0, 0.0, progress);
  EXPECT_LE(d.aToB, 0.1 + 1e-12);
  EXPECT_GE(d.aToB, 0.1 - accuracy);
  EXPECT_GE(d.aToBBound, 0.1 - 1e-12);  // a proven bound: never below the true value
  EXPECT_LE(d.aToBBound, d.aToB + accuracy + 1e-12);
  EXPECT_NEAR(d.bToA, 0.0, 1e-12);  // the frame lies on the square
  EXPECT_NEAR(d.bToABound, 0.0, 1e-12);
}

TEST(MeshDistance, ASquareBeyondTheOthersEdgeMeasuresItsFarthestPoint) {
  Progress progress;
  // b continues past a's edge by 0.5 along x, in the same plane.
  const SurfaceDeviation d =
      measureDeviation(square(0, 1), square(0, 1, {0.5, 0, 0}), false, 0.05, 2.0, 0.0, progress);
  EXPECT_NEAR(d.aToB, 0.5, 1e-12);
  EXPECT_NEAR(d.bToA, 0.5, 1e-12);
  EXPECT_GE(d.bound(), 0.5 - 1e-12);
  EXPECT_LE(d.bound(), 0.5 + 0.05 + 1e-12);
}

TEST(MeshDistance, FartherThanTheCapIsFlagged) {
  Progress progress;
  const SurfaceDeviation d =
      measureDeviation(square(0, 1), square(5, 1), false, 0.5, 1.0, 0.0, progress);
  EXPECT_TRUE(d.capped);
  EXPECT_DOUBLE_EQ(d.largest(), 1.0);
  EXPECT_DOUBLE_EQ(d.bound(), 1.0);
}

// A closed box [-0.5, 1.5]^2 x [-1, 0] whose top (z = 0) is an n x n grid of squares, its centre
// vertex pushed down by `dent`; the other faces one quad each (closed as a surface: the check
// of what the flat-region bound may assume).
TriangleMesh boxWithGridTop(int n, double dent) {
  TriangleMesh m;
  auto at = [&](int i, int j) { return uint32_t(i * (n + 1) + j); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const bool centre = 2 * i == n && 2 * j == n;
      m.positions.push_back({-0.5 + 2.0 * i / n, -0.5 + 2.0 * j / n, centre ? -dent : 0.0});
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  const uint32_t b = uint32_t(m.positions.size());
  for (const glm::dvec3& p : {glm::dvec3(-0.5, -0.5, -1), glm::dvec3(1.5, -0.5, -1),
                              glm::dvec3(1.5, 1.5, -1), glm::dvec3(-0.5, 1.5, -1)})
    m.positions.push_back(p);
  const uint32_t c00 = at(0, 0), c10 = at(n, 0), c11 = at(n, n), c01 = at(0, n);
  m.triangles.push_back({b, b + 2, b + 1});  // bottom
  m.triangles.push_back({b, b + 3, b + 2});
  const uint32_t top[4] = {c00, c10, c11, c01};
  for (uint32_t k = 0; k < 4; ++k) {  // the sides, from the top's corners down
    const uint32_t next = (k + 1) % 4;
    m.triangles.push_back({top[k], b + k, b + next});
    m.triangles.push_back({top[k], b + next, top[next]});
  }
  return m;
}

// The largest distance of a fine grid of points on the unit square at z = 0 from `to`.
double bruteForceSquareTo(const TriangleMesh& to, int steps) {
  double largest = 0.0;
  for (int i = 0; i <= steps; ++i)
    for (int j = 0; j <= steps; ++j) {
      const glm::dvec3 p(double(i) / steps, double(j) / steps, 0.0);
      double best = INFINITY;
      for (const auto& t : to.triangles)
        best = std::min(best, pointTriangleDistanceSquared(p, to.positions[t[0]],
                                                           to.positions[t[1]], to.positions[t[2]]));
      largest = std::max(largest, std::sqrt(best));
    }
  return largest;
}

TEST(MeshDistance, AFlatRegionOfAClosedSurfaceIsBoundedWithFewPoints) {
  Progress progress;
  const TriangleMesh flat = boxWithGridTop(40, 0.0);
  // The search reach (0.1) keeps the box's sides out of the cells the square passes through.
  const SurfaceDeviation open =
      measureDeviation(square(0, 1), flat, false, 2e-3, 0.1, 0.0, progress);
  const SurfaceDeviation closed =
      measureDeviation(square(0, 1), flat, true, 2e-3, 0.1, 0.0, progress);
  EXPECT_NEAR(closed.aToBBound, 0.0, 1e-12);
  EXPECT_NEAR(open.aToBBound, 0.0, 2e-3 + 1e-12);
  // Without the flat-region bound, proving 2e-3 over the square takes many more points.
  EXPECT_LT(closed.samples * 20, open.samples);
}

TEST(MeshDistance, ADentInAFlatClosedSurfaceIsStillFound) {
  Progress progress;
  // The dent (0.05 deep, 0.2 wide at the top) lies under the square's centre, far from its
  // corners; the flat-region bound must not hide it.
  const TriangleMesh dented = boxWithGridTop(20, 0.05);
  const double accuracy = 1e-3;
  const SurfaceDeviation d =
      measureDeviation(square(0, 1), dented, true, accuracy, 0.1, 0.0, progress);
  const double truth = bruteForceSquareTo(dented, 200);  // the dent's centre is a grid point
  ASSERT_GT(truth, 0.01);
  EXPECT_GE(d.aToBBound, truth - 1e-12);
  EXPECT_LE(d.aToBBound, truth + accuracy + 1e-12);
  EXPECT_NEAR(d.aToB, truth, accuracy);
}

TEST(MeshDistance, TheSameOnOneAndManyThreads) {
  TriangleMesh a = square(0, 1), b = square(0.01, 1, {0.003, 0.002, 0});
  Progress progress;
  setWorkerCount(1);
  const SurfaceDeviation one = measureDeviation(a, b, false, 0.0001, 1.0, 0.0, progress);
  setWorkerCount(4);
  const SurfaceDeviation many = measureDeviation(a, b, false, 0.0001, 1.0, 0.0, progress);
  setWorkerCount(0);
  EXPECT_EQ(one.aToB, many.aToB);
  EXPECT_EQ(one.bToA, many.bToA);
  EXPECT_EQ(one.aToBBound, many.aToBBound);
  EXPECT_EQ(one.bToABound, many.bToABound);
  EXPECT_EQ(one.samples, many.samples);
}

}  // namespace
}  // namespace strata::test
