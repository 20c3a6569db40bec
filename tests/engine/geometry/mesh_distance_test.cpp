// measureDeviation: two parallel squares a known distance apart measure that distance both
// ways; a square off the edge of the other measures its farthest corner; a hole in the other
// surface, far from every corner, is found and bounded; one beyond the search radius is flagged
// as capped; the result does not depend on the thread count.
#include "engine/geometry/mesh_distance.h"

#include <gtest/gtest.h>

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
      measureDeviation(square(0, 1), square(0.125, 1), 0.1, 1.0, 0.0, progress);
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
      measureDeviation(square(0, 1), frame(0.1), accuracy, 1.0, 0.0, progress);
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
      measureDeviation(square(0, 1), square(0, 1, {0.5, 0, 0}), 0.05, 2.0, 0.0, progress);
  EXPECT_NEAR(d.aToB, 0.5, 1e-12);
  EXPECT_NEAR(d.bToA, 0.5, 1e-12);
  EXPECT_GE(d.bound(), 0.5 - 1e-12);
  EXPECT_LE(d.bound(), 0.5 + 0.05 + 1e-12);
}

TEST(MeshDistance, FartherThanTheCapIsFlagged) {
  Progress progress;
  const SurfaceDeviation d = measureDeviation(square(0, 1), square(5, 1), 0.5, 1.0, 0.0, progress);
  EXPECT_TRUE(d.capped);
  EXPECT_DOUBLE_EQ(d.largest(), 1.0);
  EXPECT_DOUBLE_EQ(d.bound(), 1.0);
}

TEST(MeshDistance, TheSameOnOneAndManyThreads) {
  TriangleMesh a = square(0, 1), b = square(0.01, 1, {0.003, 0.002, 0});
  Progress progress;
  setWorkerCount(1);
  const SurfaceDeviation one = measureDeviation(a, b, 0.0001, 1.0, 0.0, progress);
  setWorkerCount(4);
  const SurfaceDeviation many = measureDeviation(a, b, 0.0001, 1.0, 0.0, progress);
  setWorkerCount(0);
  EXPECT_EQ(one.aToB, many.aToB);
  EXPECT_EQ(one.bToA, many.bToA);
  EXPECT_EQ(one.aToBBound, many.aToBBound);
  EXPECT_EQ(one.bToABound, many.bToABound);
  EXPECT_EQ(one.samples, many.samples);
}

}  // namespace
}  // namespace strata::test
