// The QEF's decompositions several at a time (contour_math.h: symmetricEigen3Batch) give the bits
// of one at a time (symmetricEigen3), whatever each one's convergence: the CPU's vertex step uses
// the batch, the device the single one, and their files must be byte for byte the same.
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
  float normals[12][3];  // count <= 12
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

TEST(ContourMath, DecompositionsInBatchesHaveTheBitsOfOneAtATime) {
  std::mt19937 rng(7);
  const double spreads[] = {0.0, 1e-6, 0.05, 0.3, 2.0};
  int compared = 0;
  for (int i = 0; i < 4000; ++i) {
    const int count = 1 + i % kEigenBatch;
    double m[kEigenBatch][3][3], alone[kEigenBatch][3][3], vAlone[kEigenBatch][3][3];
    double v[kEigenBatch][3][3];
    double(*ms[kEigenBatch])[3];
    double(*vs[kEigenBatch])[3];
    for (int l = 0; l < count; ++l) {
      planesMatrix(rng, 1 + (i + l) % 6, spreads[(i / 4 + l) % 5], m[l]);
      if ((i + l) % 97 == 0)  // already diagonal: converged before the first sweep
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) m[l][r][c] = r == c ? m[l][r][c] : 0.0;
      std::memcpy(alone[l], m[l], sizeof(m[l]));
      symmetricEigen3(alone[l], vAlone[l]);
      ms[l] = m[l];
      vs[l] = v[l];
    }
    symmetricEigen3Batch(ms, vs, count);
    for (int l = 0; l < count; ++l) {
      ASSERT_TRUE(sameBits(alone[l], m[l]) && sameBits(vAlone[l], v[l]))
          << "matrix " << l << " of batch " << i;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 10000);
}

// The decomposition stops once rounding is all that is left off the diagonal (relative to the
// diagonal: kJacobiRelativeOffDiagonal), and is then as exact as double arithmetic gives: the
// eigenvectors orthonormal and V diag(m) V^T the matrix, to 1e-13 of its trace. An absolute rule
// ran all kJacobiSweeps sweeps on matrices whose rounding never cancelled exactly.
TEST(ContourMath, DecompositionsStopAtRoundingAndStayExact) {
  std::mt19937 rng(11);
  const double spreads[] = {0.0, 1e-6, 0.05, 0.3, 2.0};
  const double scales[] = {1e-9, 1.0, 1e6};
  int sweepsSeen[kJacobiSweeps + 1] = {};
  for (int i = 0; i < 30000; ++i) {
    double m[3][3], a[3][3], v[3][3];
    planesMatrix(rng, 1 + i % 12, spreads[(i / 12) % 5], m);
    const double scale = scales[(i / 60) % 3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a[r][c] = m[r][c] *= scale;
    const int sweeps = symmetricEigen3(m, v);
    ++sweepsSeen[sweeps];
    ASSERT_LE(sweeps, 5) << "matrix " << i;
    const double trace = a[0][0] + a[1][1] + a[2][2];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        double back = 0.0, dot = 0.0;
        for (int k = 0; k < 3; ++k) {
          back += v[r][k] * m[k][k] * v[c][k];
          dot += v[k][r] * v[k][c];
        }
        ASSERT_NEAR(back, a[r][c], 1e-13 * trace) << "matrix " << i;
        ASSERT_NEAR(dot, r == c ? 1.0 : 0.0, 1e-14) << "matrix " << i;
      }
  }
  // Most need several sweeps (the matrices are not diagonal to start with; one plane's needs
  // one): the rule is exercised, not skipped.
  EXPECT_GT(sweepsSeen[2] + sweepsSeen[3] + sweepsSeen[4], 20000);
}

}  // namespace
}  // namespace strata
