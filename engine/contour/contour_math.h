// Per-cell math of dual contouring, shared by the CPU exporter and its CUDA twin: the cell's
// corner and edge numbering, the surface components of each of the 256 corner-sign cases, and
// the QEF solve that places one vertex per component.
#pragma once

#include <cmath>
#include <cstdint>

#include "engine/ldi/shared_math.h"

namespace strata {

// Cell numbering. Corner c has offsets (c & 1, (c >> 1) & 1, (c >> 2) & 1) in x, y, z.
// Edge e = 4 * a + du + 2 * dv runs along axis a from the corner with bit a = 0 and bits
// (u, v) = (du, dv) (u = (a + 1) % 3, v = (a + 2) % 3) to the same corner with bit a = 1.
STRATA_HD int cellCorner(int x, int y, int z) {
  return x | (y << 1) | (z << 2);
}

STRATA_HD void edgeCorners(int edge, int* c0, int* c1) {
  int a = edge >> 2, du = edge & 1, dv = (edge >> 1) & 1;
  int bits[3] = {0, 0, 0};
  bits[(a + 1) % 3] = du;
  bits[(a + 2) % 3] = dv;
  *c0 = cellCorner(bits[0], bits[1], bits[2]);
  bits[a] = 1;
  *c1 = cellCorner(bits[0], bits[1], bits[2]);
}

// The surface components of a cell, for each corner-inside mask (bit c set: corner c inside).
// Components are the cycles of sign-changing edges linked across the cell's faces; on a face
// whose four edges all change sign (diagonal corners alike) the inside corners are kept apart,
// the same rule on both sides of the face, so neighbouring cells agree and the dual mesh is a
// closed 2-manifold. edgeComponent[e] is the component of edge e, or -1 without a crossing.
struct CellCase {
  int8_t components;
  int8_t edgeComponent[12];
};

namespace detail {
constexpr int findRoot(int* parent, int x) {
  while (parent[x] != x) x = parent[x];
  return x;
}
constexpr CellCase buildCellCase(int mask) {
  CellCase result{0, {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1}};
  int parent[12] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  bool crossing[12] = {};
  for (int e = 0; e < 12; ++e) {
    int a = e >> 2, du = e & 1, dv = (e >> 1) & 1;
    int bits0[3] = {0, 0, 0};
    bits0[(a + 1) % 3] = du;
    bits0[(a + 2) % 3] = dv;
    int c0 = bits0[0] | (bits0[1] << 1) | (bits0[2] << 2);
    int c1 = c0 | (1 << a);
    crossing[e] = ((mask >> c0) & 1) != ((mask >> c1) & 1);
  }
  // Each face: axis f, side s. Its corners in cyclic order around the face and the edges
  // between consecutive corners.
  for (int f = 0; f < 3; ++f) {
    for (int s = 0; s < 2; ++s) {
      const int p = (f + 1) % 3, q = (f + 2) % 3;
      int corners[4] = {0, 0, 0, 0};
      const int pq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (int k = 0; k < 4; ++k) {
        int bits[3] = {0, 0, 0};
        bits[f] = s;
        bits[p] = pq[k][0];
        bits[q] = pq[k][1];
        corners[k] = bits[0] | (bits[1] << 1) | (bits[2] << 2);
      }
      int edges[4] = {0, 0, 0, 0};  // edge k joins corners k and k + 1
      for (int k = 0; k < 4; ++k) {
        int a = corners[k], b = corners[(k + 1) % 4];
        int axis = 0;
        while (((a ^ b) >> axis) != 1) ++axis;
        int lo = a < b ? a : b;
        int du = (lo >> ((axis + 1) % 3)) & 1, dv = (lo >> ((axis + 2) % 3)) & 1;
        edges[k] = 4 * axis + du + 2 * dv;
      }
      int changing = 0;
      for (int k = 0; k < 4; ++k) changing += crossing[edges[k]] ? 1 : 0;
      int links[2][2] = {{-1, -1}, {-1, -1}};
      if (changing == 2) {
        int found = 0;
        for (int k = 0; k < 4; ++k)
          if (crossing[edges[k]]) links[0][found++] = edges[k];
      } else if (changing == 4) {
        // Keep inside corners apart: link the two edges around each inside corner. Corner k
        // lies between edges k - 1 and k.
        int found = 0;
        for (int k = 0; k < 4; ++k) {
          if ((mask >> corners[k]) & 1) {
            links[found][0] = edges[(k + 3) % 4];
            links[found][1] = edges[k];
            ++found;
          }
        }
      }
      for (int l = 0; l < 2; ++l) {
        if (links[l][0] < 0) continue;
        int ra = findRoot(parent, links[l][0]), rb = findRoot(parent, links[l][1]);
        if (ra != rb) parent[ra] = rb;
      }
    }
  }
  int label[12] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  for (int e = 0; e < 12; ++e) {
    if (!crossing[e]) continue;
    int r = findRoot(parent, e);
    if (label[r] < 0) label[r] = result.components++;
    result.edgeComponent[e] = int8_t(label[r]);
  }
  return result;
}
}  // namespace detail

struct CellCaseTable {
  CellCase cases[256];
};

constexpr CellCaseTable buildCellCaseTable() {
  CellCaseTable table{};
  for (int m = 0; m < 256; ++m) table.cases[m] = detail::buildCellCase(m);
  return table;
}

constexpr int kMaxCellComponents = 4;

// ---------------------------------------------------------------------------------------------
// QEF: minimise sum_i (n_i . (x - p_i))^2 over x, around the mass point of the p_i.

struct Qef {
  double ata[6];  // symmetric A^T A: xx, xy, xz, yy, yz, zz
  double atb[3];  // A^T b with b_i = n_i . (p_i - massPoint), accumulated after the mass point
  double mass[3];
  int count;
};

// Accumulates the planes (p_i, n_i), i < n, around their mass point. Points in grid units.
STRATA_HD Qef buildQef(const double (*points)[3], const float (*normals)[3], int n) {
  Qef q = {{0, 0, 0, 0, 0, 0}, {0, 0, 0}, {0, 0, 0}, n};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) q.mass[k] += points[i][k];
  for (int k = 0; k < 3; ++k) q.mass[k] /= n > 0 ? n : 1;
  for (int i = 0; i < n; ++i) {
    const double nx = normals[i][0], ny = normals[i][1], nz = normals[i][2];
    const double d = nx * (points[i][0] - q.mass[0]) + ny * (points[i][1] - q.mass[1]) +
                     nz * (points[i][2] - q.mass[2]);
    q.ata[0] += nx * nx;
    q.ata[1] += nx * ny;
    q.ata[2] += nx * nz;
    q.ata[3] += ny * ny;
    q.ata[4] += ny * nz;
    q.ata[5] += nz * nz;
    q.atb[0] += nx * d;
    q.atb[1] += ny * d;
    q.atb[2] += nz * d;
  }
  return q;
}

// One Jacobi rotation of symmetricEigen3 zeroing m[p][q] (m = J^T m J, v = v J).
STRATA_HD void jacobiRotate(double m[3][3], double v[3][3], int p, int q) {
  if (fabs(m[p][q]) < 1e-300) return;
  double theta = (m[q][q] - m[p][p]) / (2.0 * m[p][q]);
  double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
  double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
  for (int k = 0; k < 3; ++k) {  // m = J^T m J
    double mkp = m[k][p], mkq = m[k][q];
    m[k][p] = c * mkp - s * mkq;
    m[k][q] = s * mkp + c * mkq;
  }
  for (int k = 0; k < 3; ++k) {
    double mpk = m[p][k], mqk = m[q][k];
    m[p][k] = c * mpk - s * mqk;
    m[q][k] = s * mpk + c * mqk;
  }
  for (int k = 0; k < 3; ++k) {
    double vkp = v[k][p], vkq = v[k][q];
    v[k][p] = c * vkp - s * vkq;
    v[k][q] = s * vkp + c * vkq;
  }
}

// Off-diagonal size, relative to the diagonal's, at which symmetricEigen3 stops. Each rotation
// leaves rounding of about 1e-16 of the entries it mixes where it zeroes an entry, so an
// absolute rule (it was < 1e-30) ran every sweep on matrices whose rounding never cancelled
// exactly (6% of a scan's cells took all 12). Stopped at this size, an eigenvector is off by at
// most about 1e-14 of the trace over the gap to the next eigenvalue: directions with nearly equal
// eigenvalues are all kept or all truncated (kQefTruncation) together, where the mix within them
// changes no solution, and a kept direction lies at least 0.9 of the largest eigenvalue from a
// truncated one; vertices move by about 1e-14 cells, far below what the files store.
constexpr double kJacobiRelativeOffDiagonal = 1e-14;

// Whether symmetricEigen3 stops before its next sweep of m (symmetric, positive semidefinite).
STRATA_HD bool jacobiConverged(const double m[3][3]) {
  const double off = fabs(m[0][1]) + fabs(m[0][2]) + fabs(m[1][2]);
  const double diagonal = fabs(m[0][0]) + fabs(m[1][1]) + fabs(m[2][2]);
  return off <= kJacobiRelativeOffDiagonal * diagonal || off < 1e-300;
}

constexpr int kJacobiSweeps = 12;

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: on return
// m[i][i] are the eigenvalues and the columns of v the eigenvectors. Returns the sweeps run.
STRATA_HD int symmetricEigen3(double m[3][3], double v[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) v[i][j] = i == j ? 1.0 : 0.0;
  int sweep = 0;
  for (; sweep < kJacobiSweeps && !jacobiConverged(m); ++sweep)
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) jacobiRotate(m, v, p, q);
  return sweep;
}

// symmetricEigen3 of `count` (at most kEigenBatch) matrices at once, m[i] and v[i] each bit for
// bit as alone: their chains of dependent divisions and square roots (the decomposition's cost)
// run side by side, which a processor that executes out of order overlaps (on the CPU about
// twice the throughput of one at a time).
constexpr int kEigenBatch = 4;
STRATA_HD void symmetricEigen3Batch(double (*const* m)[3], double (*const* v)[3], int count) {
  bool done[kEigenBatch];
  for (int l = 0; l < count; ++l) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) v[l][i][j] = i == j ? 1.0 : 0.0;
    done[l] = false;
  }
  for (int sweep = 0; sweep < kJacobiSweeps; ++sweep) {
    bool all = true;
    for (int l = 0; l < count; ++l) {
      done[l] = done[l] || jacobiConverged(m[l]);
      all = all && done[l];
    }
    if (all) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q)
        for (int l = 0; l < count; ++l)
          if (!done[l]) jacobiRotate(m[l], v[l], p, q);
  }
}

// Relative size below which singular values are truncated: directions the planes do not pin
// down (along a flat face, along a sharp edge) stay at the mass point.
constexpr double kQefTruncation = 0.1;

// Keeps a vertex inside its cell [cell, cell + 1]^3 (grid units), a small margin away from the
// faces so that vertices of neighbouring cells never coincide.
constexpr double kCellMargin = 1e-3;

STRATA_HD bool insideCell(const double x[3], const int64_t cell[3]) {
  for (int k = 0; k < 3; ++k) {
    if (!(x[k] >= double(cell[k]) + kCellMargin && x[k] <= double(cell[k]) + 1.0 - kCellMargin))
      return false;
  }
  return true;
}

STRATA_HD void clampToCell(double x[3], const int64_t cell[3]) {
  for (int k = 0; k < 3; ++k) {
    double lo = double(cell[k]) + kCellMargin, hi = double(cell[k]) + 1.0 - kCellMargin;
    x[k] = x[k] < lo ? lo : (x[k] > hi ? hi : x[k]);
  }
}

// The QEF minimiser around the mass point, kept in its cell (grid units).
//
// Candidates are the pseudo-inverse solutions of rank 3, 2, 1 (singular values below
// kQefTruncation of the largest always dropped: a corner uses three directions, a sharp edge
// two, a flat patch one) and the mass point, each clamped into the cell; the one with the
// smallest QEF energy wins. The mass point of the cell's crossings lies in the cell, so a
// feature that leaves the cell pulls the vertex along the feature, not off it.
//
// In two steps: the decomposition of A^T A (qefMatrix, then symmetricEigen3 or, for two QEFs at
// once, symmetricEigen3Batch), then solveQefWithEigen from it; solveQef does both.
STRATA_HD void qefMatrix(const Qef& q, double m[3][3]) {
  m[0][0] = q.ata[0], m[0][1] = q.ata[1], m[0][2] = q.ata[2];
  m[1][0] = q.ata[1], m[1][1] = q.ata[3], m[1][2] = q.ata[4];
  m[2][0] = q.ata[2], m[2][1] = q.ata[4], m[2][2] = q.ata[5];
}

// `m` and `v`: symmetricEigen3 of qefMatrix(q).
STRATA_HD void solveQefWithEigen(const Qef& q, const double m[3][3], const double v[3][3],
                                 const int64_t cell[3], double out[3]) {
  int order[3] = {0, 1, 2};  // eigenvalues, largest first
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (m[order[j]][order[j]] > m[order[i]][order[i]]) {
        int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
  const double largest = m[order[0]][order[0]];
  int rank = 0;
  while (rank < 3 && largest > 0.0 && m[order[rank]][order[rank]] >= kQefTruncation * largest)
    ++rank;
  // Energy relative to the mass point: d^T (A^T A) d - 2 d . A^T b, d = x - mass.
  auto energy = [&](const double x[3]) {
    double d[3] = {x[0] - q.mass[0], x[1] - q.mass[1], x[2] - q.mass[2]};
    double ad[3] = {q.ata[0] * d[0] + q.ata[1] * d[1] + q.ata[2] * d[2],
                    q.ata[1] * d[0] + q.ata[3] * d[1] + q.ata[4] * d[2],
                    q.ata[2] * d[0] + q.ata[4] * d[1] + q.ata[5] * d[2]};
    return d[0] * ad[0] + d[1] * ad[1] + d[2] * ad[2] -
           2.0 * (d[0] * q.atb[0] + d[1] * q.atb[1] + d[2] * q.atb[2]);
  };
  double best = 0.0;
  for (int r = rank; r >= 0; --r) {
    double x[3] = {q.mass[0], q.mass[1], q.mass[2]};
    for (int k = 0; k < r; ++k) {
      const int e = order[k];
      const double proj = v[0][e] * q.atb[0] + v[1][e] * q.atb[1] + v[2][e] * q.atb[2];
      for (int i = 0; i < 3; ++i) x[i] += v[i][e] * proj / m[e][e];
    }
    clampToCell(x, cell);
    const double e = energy(x);
    if (r == rank || e < best) {
      best = e;
      for (int i = 0; i < 3; ++i) out[i] = x[i];
    }
  }
}

STRATA_HD void solveQef(const Qef& q, const int64_t cell[3], double out[3]) {
  double m[3][3], v[3][3];
  qefMatrix(q, m);
  symmetricEigen3(m, v);
  solveQefWithEigen(q, m, v, cell, out);
}

// Two components of one cell whose minimisers both left the cell the same way are clamped to
// the same point; distinct vertices must not share a position (the mesh would be pinched
// there). Each such vertex is moved halfway towards its own mass point, which differ because
// the components' crossings lie on different edges. `x` and `mass` hold `count` points.
STRATA_HD void separateCoincidentVertices(double (*x)[3], const double (*mass)[3], int count) {
  for (int i = 0; i < count; ++i) {
    for (int j = i + 1; j < count; ++j) {
      if (x[i][0] != x[j][0] || x[i][1] != x[j][1] || x[i][2] != x[j][2]) continue;
      for (int k = 0; k < 3; ++k) {
        x[i][k] = 0.5 * (x[i][k] + mass[i][k]);
        x[j][k] = 0.5 * (x[j][k] + mass[j][k]);
      }
    }
  }
}

// Distance (grid units) from x to the farthest of the QEF's planes: the vertex's measured
// deviation from the Hermite data it was fitted to.
STRATA_HD double qefPlaneDistance(const double (*points)[3], const float (*normals)[3], int n,
                                  const double x[3]) {
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    double d = normals[i][0] * (x[0] - points[i][0]) + normals[i][1] * (x[1] - points[i][1]) +
               normals[i][2] * (x[2] - points[i][2]);
    worst = fmax(worst, fabs(d));
  }
  return worst;
}

}  // namespace strata
