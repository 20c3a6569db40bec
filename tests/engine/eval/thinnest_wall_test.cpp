// The thinnest-wall estimate of an evaluation (engine/ldi/ldi.h: LdiMeasure::thinnestWall):
// a turned flat slab is its thickness within a cell (its corners are no walls), a hollow box its
// thinnest side, a sphere no thinner than the chords whose ends face away from each other allow
// (2 R cos^2 15 degrees), and the point it names lies in the wall.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

TEST(ThinnestWall, AFlatSlabTurnedOffTheAxesIsItsThickness) {
  for (double degrees : {0.0, 20.0, 40.0}) {
    Transform t;
    t.rotateDegrees = glm::dvec3(degrees, 0.5 * degrees, 0.0);
    const EvalResult r = evaluateCpu(makeScene(withTransform(box({6.0, 6.0, 0.6}), t), 128));
    ASSERT_TRUE(std::isfinite(r.measure.thinnestWall)) << degrees;
    EXPECT_NEAR(r.measure.thinnestWall, 0.6, r.grid.h) << degrees;
    // The point named lies within the slab (its frame's z within half the thickness and a cell).
    const glm::dvec3 local =
        glm::dvec3(glm::inverse(t.matrix()) * glm::dvec4(r.measure.thinnestAt, 1.0));
    EXPECT_LE(std::abs(local.z), 0.3 + r.grid.h) << degrees;
  }
}

TEST(ThinnestWall, AHollowBoxIsItsThinnestSide) {
  // A 4 x 4 x 4 box with a cavity leaving walls of 0.8, except 0.4 on the +x side.
  const NodePtr hollow =
      op(NodeKind::Difference, {box(glm::dvec3(4.0)), box({2.8, 2.4, 2.4}, {0.2, 0.0, 0.0})});
  const EvalResult r = evaluateCpu(makeScene(hollow, 128));
  EXPECT_NEAR(r.measure.thinnestWall, 0.4, r.grid.h);
  EXPECT_NEAR(r.measure.thinnestAt.x, 1.8, r.grid.h);  // the middle of the thin side
}

TEST(ThinnestWall, ASphereIsNotAWall) {
  const EvalResult r = evaluateCpu(makeScene(sphere(1.0), 96));
  const double c15 = std::cos(15.0 * 3.14159265358979323846 / 180.0);
  EXPECT_GE(r.measure.thinnestWall, 2.0 * c15 * c15 - r.grid.h);
  EXPECT_LE(r.measure.thinnestWall, 2.0 + r.grid.h);
  // Nothing judged: an empty scene's LDI.
  EXPECT_FALSE(std::isfinite(LdiMeasure{}.thinnestWall));
}

}  // namespace
}  // namespace strata::test
