// measureDeviation: two parallel squares a known distance apart measure that distance both
// ways; a triangle off the edge of the other measures its farthest sampled corner; one beyond
// the search radius is flagged as capped; the result does not depend on the thread count.
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
  const SurfaceDeviation d = measureDeviation(square(0, 1), square(0.125, 1), 0.1, 1.0, progress);
  EXPECT_NEAR(d.aToB, 0.125, 1e-12);
  EXPECT_NEAR(d.bToA, 0.125, 1e-12);
  EXPECT_FALSE(d.capped);
  EXPECT_GT(d.samples, 100u);
}

TEST(MeshDistance, ASquareBeyondTheOthersEdgeMeasuresItsFarthestPoint) {
  Progress progress;
  // b continues past a's edge by 0.5 along x, in the same plane.
  const SurfaceDeviation d =
      measureDeviation(square(0, 1), square(0, 1, {0.5, 0, 0}), 0.05, 2.0, progress);
  EXPECT_NEAR(d.aToB, 0.5, 1e-12);
  EXPECT_NEAR(d.bToA, 0.5, 1e-12);
}

TEST(MeshDistance, FartherThanTheCapIsFlagged) {
  Progress progress;
  const SurfaceDeviation d = measureDeviation(square(0, 1), square(5, 1), 0.5, 1.0, progress);
  EXPECT_TRUE(d.capped);
  EXPECT_DOUBLE_EQ(d.largest(), 1.0);
}

TEST(MeshDistance, TheSameOnOneAndManyThreads) {
  TriangleMesh a = square(0, 1), b = square(0.01, 1, {0.003, 0.002, 0});
  Progress progress;
  setWorkerCount(1);
  const SurfaceDeviation one = measureDeviation(a, b, 0.01, 1.0, progress);
  setWorkerCount(4);
  const SurfaceDeviation many = measureDeviation(a, b, 0.01, 1.0, progress);
  setWorkerCount(0);
  EXPECT_EQ(one.aToB, many.aToB);
  EXPECT_EQ(one.bToA, many.bToA);
  EXPECT_EQ(one.samples, many.samples);
}

}  // namespace
}  // namespace strata::test
