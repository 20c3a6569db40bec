// Volumes and areas measured from the LDI against analytic values, at two resolutions. The
// tolerance is proportional to the cell size h (times the surface area), so it shrinks as the
// resolution grows; each case is also checked to improve from the coarse to the fine grid.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {
constexpr double kPi = 3.14159265358979323846;

// Volume error allowed at cell size h for a solid whose boundary area is at most `area`:
// a quarter of a cell thickness over the whole surface.
double volumeTolerance(double h, double area) {
  return 0.25 * h * area;
}

struct Case {
  const char* name;
  NodePtr root;
  double volume;
  double boundArea;  // an upper bound of the boundary area (the leaves' areas summed)
};

Case twoSpheres(NodeKind kind, double volume) {
  return {kindName(kind), op(kind, {sphere(1.0, {-0.5, 0, 0}), sphere(1.0, {0.5, 0, 0})}), volume,
          8 * kPi};
}

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back(twoSpheres(NodeKind::Union, 9 * kPi / 4));
  c.push_back(twoSpheres(NodeKind::Intersection, 5 * kPi / 12));
  c.push_back(twoSpheres(NodeKind::Difference, 11 * kPi / 12));
  c.push_back({"steinmetz",
               op(NodeKind::Intersection, {cylinder(1.0, 3.0, {}, {0, 90, 0}),
                                           cylinder(1.0, 3.0, {}, {90, 0, 0}), cylinder(1.0, 3.0)}),
               8 * (2 - std::sqrt(2.0)), 3 * (2 * kPi * 3 + 2 * kPi)});
  double ball = 4.0 / 3.0 * kPi * 1.2 * 1.2 * 1.2;
  double cap = kPi * 0.2 * 0.2 * (3 * 1.2 - 0.2) / 3;
  c.push_back({"cube_minus_ball", op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2)}),
               8 - (ball - 6 * cap), 24 + 4 * kPi * 1.44});
  c.push_back({"torus_half",
               op(NodeKind::Intersection, {torus(1.0, 0.25), box({4, 4, 1}, {0, 0, 0.5})}),
               kPi * kPi * 1.0 * 0.25 * 0.25, 4 * kPi * kPi * 0.25 + 2 * kPi});
  return c;
}

class AnalyticVolume : public ::testing::TestWithParam<int> {};

TEST_P(AnalyticVolume, MatchesWithinCellTolerance) {
  const int resolution = GetParam();
  for (const Case& c : cases()) {
    EvalResult r = evaluateCpu(makeScene(c.root, resolution));
    double tol = volumeTolerance(r.grid.h, c.boundArea);
    EXPECT_NEAR(r.measure.volume, c.volume, tol)
        << c.name << " at " << resolution << " (h = " << r.grid.h << ")";
    // Each axis alone is a valid estimate too.
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(r.measure.axisVolume[a], c.volume, 2 * tol) << c.name << " axis " << a;
  }
}

INSTANTIATE_TEST_SUITE_P(Resolutions, AnalyticVolume, ::testing::Values(64, 128));

TEST(AnalyticVolume, ErrorShrinksWithResolution) {
  for (const Case& c : cases()) {
    double coarse = std::fabs(evaluateCpu(makeScene(c.root, 48)).measure.volume - c.volume);
    double fine = std::fabs(evaluateCpu(makeScene(c.root, 192)).measure.volume - c.volume);
    EXPECT_LT(fine, coarse + 1e-12) << c.name;
  }
}

TEST(AnalyticArea, SphereAndBoxAreas) {
  EvalResult s = evaluateCpu(makeScene(sphere(1.0), 128));
  EXPECT_NEAR(s.measure.area, 4 * kPi, 0.02 * 4 * kPi);
  // Flat faces are counted ray by ray, so their area is off by up to about one cell along each
  // edge: allow h times the total edge length (24 for this box).
  EvalResult b = evaluateCpu(makeScene(box({1, 2, 3}), 128));
  EXPECT_NEAR(b.measure.area, 22.0, b.grid.h * 24.0);
  EXPECT_NEAR(b.measure.volume, 6.0, volumeTolerance(b.grid.h, 22.0));
}

}  // namespace
}  // namespace strata::test
