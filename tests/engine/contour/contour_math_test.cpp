// The QEF's decomposition two at a time (contour_math.h: symmetricEigen3Pair) gives the bits of
// one at a time (symmetricEigen3), whatever each pair's convergence: the CPU's vertex step uses
// the pair, the device the single one, and their files must be byte for byte the same.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "engine/contour/contour_math.h"

namespace strata {
namespace {

// A*A^T-like matrix from `count` unit normals near `base`, spread by `spread` (0: all equal).
void planesMatrix(std::mt19937& rng, int count, double spread, double m[3][3]) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double base[3] = {n(rng), n(rng), n(rng)};
  double points[12][3] = {};
  float normals[12][3];
  for (int i = 0; i < count; ++i) {
    double v[3] = {base[0] + spread * n(rng), base[1] + spread * n(rng), base[2] + spread * n(rng)};
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k) normals[i][k] = float(v[k] / l);
  }
  qefMatrix(buildQef(points, normals, count), m);
}

bool sameBits(const double a[3][3], const double b[3][3]) {
  return std::memcmp(a, b, sizeof(double) * 9) == 0;
}

TEST(ContourMath, DecompositionsInPairsHaveTheBitsOfOneAtATime) {
  std::mt19937 rng(7);
  const double spreads[] = {0.0, 1e-6, 0.05, 0.3, 2.0};
  int compared = 0;
  for (int i = 0; i < 4000; ++i) {
    double a[3][3], b[3][3];
    planesMatrix(rng, 1 + i % 6, spreads[i % 5], a);
    planesMatrix(rng, 1 + (i / 6) % 6, spreads[(i / 5) % 5], b);
    if (i % 97 == 0)  // already diagonal: converged before the first sweep
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a[r][c] = r == c ? a[r][c] : 0.0;
    double a1[3][3], b1[3][3], va1[3][3], vb1[3][3], a2[3][3], b2[3][3], va2[3][3], vb2[3][3];
    std::memcpy(a1, a, sizeof(a));
    std::memcpy(b1, b, sizeof(b));
    std::memcpy(a2, a, sizeof(a));
    std::memcpy(b2, b, sizeof(b));
    symmetricEigen3(a1, va1);
    symmetricEigen3(b1, vb1);
    symmetricEigen3Pair(a2, va2, b2, vb2);
    ASSERT_TRUE(sameBits(a1, a2) && sameBits(va1, va2)) << "first matrix of pair " << i;
    ASSERT_TRUE(sameBits(b1, b2) && sameBits(vb1, vb2)) << "second matrix of pair " << i;
    ++compared;
  }
  EXPECT_EQ(compared, 4000);
}

}  // namespace
}  // namespace strata
