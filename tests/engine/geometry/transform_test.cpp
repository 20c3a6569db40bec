// Transform <-> matrix: transformFromMatrix undoes matrix() for every rotation, scale (mirrors
// included) and translation, up to the equivalence of Euler angles.
#include <gtest/gtest.h>

#include <cmath>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/geometry/transform.h"

namespace strata {
namespace {

double maxDifference(const glm::dmat4& a, const glm::dmat4& b) {
  double worst = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) worst = std::max(worst, std::fabs(a[c][r] - b[c][r]));
  return worst;
}

TEST(Transform, FromMatrixUndoesMatrix) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-180.0, 180.0), size(0.1, 4.0), at(-50.0, 50.0);
  for (int i = 0; i < 2000; ++i) {
    Transform t;
    t.translate = {at(random), at(random), at(random)};
    t.rotateDegrees = {angle(random), angle(random) / 2.0, angle(random)};
    t.scale = {size(random), size(random), size(random)};
    if (i % 3 == 0) t.scale.y = -t.scale.y;     // a mirror
    if (i % 50 == 0) t.rotateDegrees.y = 90.0;  // gimbal lock
    const Transform back = transformFromMatrix(t.matrix());
    EXPECT_LT(maxDifference(back.matrix(), t.matrix()), 1e-9) << i;
  }
}

TEST(Transform, ARigidMotionOfAnUnshearedNodeStaysExact) {
  Transform node;
  node.translate = {1.0, 2.0, 3.0};
  node.rotateDegrees = {10.0, 20.0, 30.0};
  node.scale = {2.0, 0.5, 1.5};
  Transform turn;
  turn.rotateDegrees = {0.0, 0.0, 45.0};
  turn.translate = {-4.0, 0.0, 1.0};
  const glm::dmat4 moved = turn.matrix() * node.matrix();
  EXPECT_LT(maxDifference(transformFromMatrix(moved).matrix(), moved), 1e-9);
}

// A turn about z and back leaves rounding in the other angles; they come back as 0, not as
// -1e-15 (which the inspector shows as "-0.00").
TEST(Transform, AnglesOfRoundingNoiseAreZero) {
  Transform node;
  node.rotateDegrees = {0.0, 0.0, 30.0};
  Transform turn;
  turn.rotateDegrees = {0.0, 0.0, 29.3};
  Transform back;
  back.rotateDegrees = {0.0, 0.0, -29.3};
  const Transform t = transformFromMatrix(back.matrix() * turn.matrix() * node.matrix());
  EXPECT_EQ(t.rotateDegrees.x, 0.0);
  EXPECT_FALSE(std::signbit(t.rotateDegrees.x));
  EXPECT_EQ(t.rotateDegrees.y, 0.0);
  EXPECT_FALSE(std::signbit(t.rotateDegrees.y));
  EXPECT_NEAR(t.rotateDegrees.z, 30.0, 1e-9);
}

// A part turned onto a surface was saved with scale 0.9999999999999999 and 1.0000000000000002
// (an artist's test): the columns' lengths of a turned matrix. Whole scales come back whole,
// others as they were.
TEST(Transform, ScalesOfRoundingNoiseAreWhole) {
  Transform node;
  node.rotateDegrees = {0.0, 0.0, 30.0};
  node.scale = {1.0, 2.0, 0.7};
  for (double degrees : {65.79774, 12.3, 91.0, 137.0}) {
    const glm::dmat4 turn =
        glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::normalize(glm::dvec3(1, 2, 3)));
    const Transform t = transformFromMatrix(turn * node.matrix());
    EXPECT_EQ(t.scale.x, 1.0) << degrees;
    EXPECT_EQ(t.scale.y, 2.0) << degrees;
    EXPECT_NEAR(t.scale.z, 0.7, 1e-12) << degrees;
  }
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

glm::dmat4 scaleMatrix(const glm::dvec3& s) {
  glm::dmat4 m(1.0);
  for (int i = 0; i < 3; ++i) m[i][i] = s[i];
  return m;
}

// A part scaled along its own axes keeps its turn (a mirror stays a negative scale, not a half
// turn with another axis negated); a turned part stretched along another axis is sheared, which
// no Transform holds: the nearest one, and said.
TEST(Transform, NearKeepsTheTurnWhereItCanAndSaysWhereItCannot) {
  Transform like;
  like.translate = glm::dvec3(1.0, 2.0, 3.0);
  like.rotateDegrees = glm::dvec3(0.0, 0.0, 30.0);
  bool exact = false;
  // Mirrored along its own z about a point: rotation kept, z scale negative.
  const glm::dmat4 mirrored = like.matrix() * scaleMatrix(glm::dvec3(1.0, 1.0, -1.75));
  const Transform a = transformNear(mirrored, like, &exact);
  EXPECT_TRUE(exact);
  EXPECT_EQ(a.rotateDegrees, like.rotateDegrees);
  EXPECT_NEAR(a.scale.z, -1.75, 1e-12);
  EXPECT_NEAR(a.scale.x, 1.0, 1e-12);
  // Unturned, mirrored along world z: transformFromMatrix would give a half turn and -x.
  const Transform b = transformNear(scaleMatrix(glm::dvec3(1.0, 1.0, -1.788)), Transform(), &exact);
  EXPECT_TRUE(exact);
  EXPECT_EQ(b.rotateDegrees, glm::dvec3(0.0));
  EXPECT_EQ(b.scale, glm::dvec3(1.0, 1.0, -1.788));
  // Turned 30 degrees about z, stretched along world x: a shear.
  transformNear(scaleMatrix(glm::dvec3(2.0, 1.0, 1.0)) * like.matrix(), like, &exact);
  EXPECT_FALSE(exact);
  // Far from the origin a slight shear is still one (the tolerance is the linear part's).
  Transform far = like;
  far.translate = glm::dvec3(1e6, 0.0, 0.0);
  transformNear(scaleMatrix(glm::dvec3(1.001, 1.0, 1.0)) * far.matrix(), far, &exact);
  EXPECT_FALSE(exact);
  // Turned, then turned more (a rigid motion): exact, by the matrix's own angles.
  glm::dmat4 turn(1.0);
  turn = glm::rotate(turn, glm::radians(20.0), glm::dvec3(0.0, 0.0, 1.0));
  const Transform d = transformNear(turn * like.matrix(), like, &exact);
  EXPECT_TRUE(exact);
  EXPECT_NEAR(d.rotateDegrees.z, 50.0, 1e-9);
}

}  // namespace
}  // namespace strata
