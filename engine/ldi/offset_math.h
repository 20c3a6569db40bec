// The per-line math of offsets (engine/ldi/offset_ldi.h), shared by the CPU reference and its
// CUDA twin (gpu/ldi/offset_ldi.cu): plain inline functions on plain types, __host__ __device__
// under nvcc, so both backends compute every distance, sign and surfel with the same arithmetic
// (the GPU tests require bitwise-equal results).
//
// Units: distances in cells (grid units); squared distances in cells^2. Nodes of the grid
// window are indexed x + nx * (y + ny * z) (OffsetLattice); a "line" along an axis is the nodes
// sharing the two other coordinates, and is also the ray of that axis through them.
#pragma once

#include <cstdint>

#include "engine/ldi/shared_math.h"

namespace strata {

STRATA_HD float offsetFar() {
  return __builtin_huge_valf();  // a node with no surface sample on its line(s)
}

// The window's nodes: per axis cells + 1.
struct OffsetLattice {
  int64_t n[3];
  int64_t stride[3];
  int64_t count;
  int first[3];  // global index of the window's first node (Grid::first)

  // The first node of the line along `axis` through window coordinates (i, j) on the axes
  // u = (axis + 1) % 3 and v = (axis + 2) % 3 (also that axis's ray i + j * n[u]).
  STRATA_HD int64_t lineStart(int axis, int64_t i, int64_t j) const {
    return i * stride[(axis + 1) % 3] + j * stride[(axis + 2) % 3];
  }
  STRATA_HD int64_t lineCount(int axis) const { return n[(axis + 1) % 3] * n[(axis + 2) % 3]; }
  // The window coordinates (i, j) of line t along `axis`, numbered in memory order: t's
  // neighbours are the lines whose nodes lie next to its own (i on u fastest, except where v
  // has the smaller stride: along y in the x-fastest layout, where u = z). The CPU's chunks of
  // consecutive lines then share cache lines, the GPU's neighbouring threads read neighbouring
  // addresses; the order changes no value (every line is computed on its own).
  STRATA_HD void lineCoords(int axis, int64_t t, int64_t* i, int64_t* j) const {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (stride[v] < stride[u]) {
      *j = t % n[v];
      *i = t / n[v];
    } else {
      *i = t % n[u];
      *j = t / n[u];
    }
  }
};

inline OffsetLattice makeOffsetLattice(const int cells[3], const int first[3]) {
  OffsetLattice lat{};
  for (int a = 0; a < 3; ++a) {
    lat.n[a] = int64_t(cells[a]) + 1;
    lat.first[a] = first[a];
  }
  lat.stride[0] = 1;
  lat.stride[1] = lat.n[0];
  lat.stride[2] = lat.n[0] * lat.n[1];
  lat.count = lat.n[0] * lat.n[1] * lat.n[2];
  return lat;
}

// The band of the distance transform: squared distances (cells^2) above this bound are stored
// as offsetFar(). The result reads sd only at the nodes on both sides of its surface (within a
// cell of |offsetCells|, the distance being 1-Lipschitz) and at their neighbours (one more cell,
// for the gradient), so every value it reads is below the bound and exact; lines far from the
// surface on both sides are then empty to the envelopes, which skip them.
STRATA_HD float offsetBandSquared(double offsetCells) {
  const double band = (offsetCells < 0.0 ? -offsetCells : offsetCells) + 4.0;
  return float(band * band);
}

// The cells beyond an offset's distance that its result at a node depends on: the band's 4 and
// the neighbours the result reads (the sign change and the gradient), and one to spare. An
// offset evaluated on a window grown by ceil(|d| / h) + kOffsetHaloCells on every side is
// exactly that of a larger grid inside the original window (tiled exports, contour_scene.h).
constexpr int kOffsetHaloCells = 7;
// Bytes per node of the grid window an offset holds at once: 17 on the CPU (offset_ldi.h), 37 on
// the CUDA backend (gpu/ldi/offset_ldi.cu: distances and leaves in three copies, the inside
// flags, the envelopes' vertices and intersections); for sizing tiles, rounded up.
constexpr uint64_t kOffsetBytesPerNode = 40;
// The CPU's alone (offset_ldi.h), for the host memory an export will need.
constexpr uint64_t kHostOffsetBytesPerNode = 17;

// Step 1 for one line of `n` nodes (`stride` apart, the first at global depth `first`): each
// node's squared distance along the line to the nearest of the ray's `count` surfels `s` (sorted
// by depth) and that surfel's leaf; with `inside` non-null also whether the node is inside (the
// ray's last surfel at or before it enters). Nodes of a line without surfels, and nodes beyond
// the band (offsetBandSquared), get offsetFar().
STRATA_HD void offsetSeedLine(const Surfel* s, int64_t count, int first, int64_t n, int64_t stride,
                              float bandSquared, float* d, uint32_t* leaf, uint8_t* inside) {
  int64_t next = 0;  // the first surfel deeper than the node
  for (int64_t k = 0; k < n; ++k) {
    const double depth = double(first + k);
    while (next < count && double(s[next].depth) <= depth) ++next;
    double best = double(offsetFar());
    uint32_t bestLeaf = 0;
    if (next > 0) {
      best = depth - double(s[next - 1].depth);
      bestLeaf = surfelLeaf(s[next - 1].tag);
    }
    if (next < count && double(s[next].depth) - depth < best) {
      best = double(s[next].depth) - depth;
      bestLeaf = surfelLeaf(s[next].tag);
    }
    const float squared = best == double(offsetFar()) ? offsetFar() : float(best * best);
    d[k * stride] = squared > bandSquared ? offsetFar() : squared;
    leaf[k * stride] = bestLeaf;
    if (inside) inside[k * stride] = next > 0 && surfelEnters(s[next - 1].tag) ? 1 : 0;
  }
}

// Step 2 for one line: out[q] = min_i (q - i)^2 + in[i] over the line's n samples (spacing one
// cell), each node's leaf following its minimiser; samples at offsetFar() take no part (a line
// without any keeps them). The lower envelope of parabolas (Felzenszwalb and Huttenlocher,
// "Distance Transforms of Sampled Functions", 2012): O(n), whatever the distances.
// `in`/`inLeaf` are read at q * inStride, `out`/`outLeaf` written at q * outStride (they may
// not overlap the input); the scratch `v` and `z` (n entries each) at q * scratchStride.
// With `onlySmaller`, a node's out and outLeaf are replaced only where the new value is smaller
// than the one there (a line without samples writes nothing): the envelope and the minimum over
// the axes' samplings in one pass. Values above bandSquared are written as offsetFar().
// The parabola on top of the stack and, when reading the envelope, the current one are kept in
// locals: scratch and input are read again only when the stack pops or the envelope moves on
// (on the GPU those reads are scattered across a warp's lines; the values are the same).
// `origin` is the global index of the line's first node (OffsetLattice::first along the line):
// the parabolas' keys and breakpoints are computed at global positions, so that a window of the
// grid (an export's tile grown by the modifiers' reach) rounds exactly as the whole grid does.
STRATA_HD void offsetEnvelopeLine(const float* in, const uint32_t* inLeaf, int64_t inStride,
                                  float* out, uint32_t* outLeaf, int64_t outStride, int64_t n,
                                  int64_t origin, int32_t* v, double* z, int64_t scratchStride,
                                  float bandSquared, bool onlySmaller) {
  const double minusInfinity = -__builtin_huge_val();
  int64_t k = -1;
  int64_t topP = 0;                           // the top parabola's node (window index)
  double topKey = 0.0, topZ = minusInfinity;  // its in[p] + P^2 (P global), and where it starts
  for (int64_t q = 0; q < n; ++q) {
    const float f = in[q * inStride];
    if (f == offsetFar()) continue;
    const double globalQ = double(origin + q);
    const double fq = double(f) + globalQ * globalQ;
    double s = minusInfinity;
    while (k >= 0) {
      s = (fq - topKey) / (2.0 * double(q - topP));
      if (s > topZ) break;
      if (--k >= 0) {
        topP = v[k * scratchStride];
        const double globalP = double(origin + topP);
        topKey = double(in[topP * inStride]) + globalP * globalP;
        topZ = z[k * scratchStride];
      }
    }
    ++k;
    topP = q;
    topKey = fq;
    topZ = k == 0 ? minusInfinity : s;
    v[k * scratchStride] = int32_t(q);
    z[k * scratchStride] = topZ;
  }
  if (k < 0) {  // no sample on this line: every node stays far
    if (onlySmaller) return;
    for (int64_t q = 0; q < n; ++q) {
      out[q * outStride] = offsetFar();
      outLeaf[q * outStride] = inLeaf[q * inStride];
    }
    return;
  }
  const int64_t last = k;
  const double plusInfinity = __builtin_huge_val();
  k = 0;
  int64_t p = v[0];
  double fp = double(in[p * inStride]);
  uint32_t leafP = inLeaf[p * inStride];
  double zNext = last > 0 ? z[scratchStride] : plusInfinity;  // where parabola k + 1 starts
  for (int64_t q = 0; q < n; ++q) {
    while (k < last && zNext < double(origin + q)) {
      ++k;
      p = v[k * scratchStride];
      fp = double(in[p * inStride]);
      leafP = inLeaf[p * inStride];
      zNext = k < last ? z[(k + 1) * scratchStride] : plusInfinity;
    }
    const double dq = double(q - p);
    float value = float(dq * dq + fp);
    if (value > bandSquared) value = offsetFar();
    if (onlySmaller && !(value < out[q * outStride])) continue;
    out[q * outStride] = value;
    outLeaf[q * outStride] = leafP;
  }
}

// The signed distance in cells at a node from the smallest squared distance: negative inside.
STRATA_HD float offsetSignedDistance(float bestSquared, uint8_t inside) {
  const float m = sqrtf(bestSquared);
  return inside ? -m : m;
}

// Whether a node belongs to the offset solid {sd - offsetCells < 0}.
STRATA_HD bool offsetInside(const float* sd, int64_t node, double offsetCells) {
  return double(sd[node]) - offsetCells < 0.0;
}

// The number of surfels of the offset on the line along `axis` through (i, j): one per change
// of offsetInside between neighbouring nodes, plus the cuts at the window's faces.
STRATA_HD uint32_t offsetRayCount(const OffsetLattice& lat, const float* sd, int axis, int64_t i,
                                  int64_t j, double offsetCells) {
  const int64_t start = lat.lineStart(axis, i, j), step = lat.stride[axis], n = lat.n[axis];
  bool previous = false;
  uint32_t c = 0;
  for (int64_t k = 0; k < n; ++k) {
    const bool now = offsetInside(sd, start + k * step, offsetCells);
    c += now != previous ? 1u : 0u;
    previous = now;
  }
  return c + (previous ? 1u : 0u);
}

// sd's gradient at window node p, central differences (one-sided at the window's faces).
STRATA_HD void offsetGradient(const OffsetLattice& lat, const float* sd, const int64_t p[3],
                              double out[3]) {
  const int64_t node = p[0] * lat.stride[0] + p[1] * lat.stride[1] + p[2] * lat.stride[2];
  for (int a = 0; a < 3; ++a) {
    const int64_t lo = p[a] > 0 ? 1 : 0, hi = p[a] + 1 < lat.n[a] ? 1 : 0;
    if (lo + hi == 0) {
      out[a] = 0.0;
      continue;
    }
    out[a] = (double(sd[node + hi * lat.stride[a]]) - double(sd[node - lo * lat.stride[a]])) /
             double(lo + hi);
  }
}

// Writes the offsetRayCount surfels of the line along `axis` through (i, j) to `out`, in depth
// order: each at the linear interpolation of sd - offsetCells between the two nodes where it
// changes sign, with the normal of sd's interpolated gradient and the leaf of the nearer node's
// nearest surface sample (`leaf`); cuts at the window's faces face along the axis.
STRATA_HD void offsetWriteRay(const OffsetLattice& lat, const float* sd, const uint32_t* leaf,
                              int axis, int64_t i, int64_t j, double offsetCells, Surfel* out) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const int64_t start = lat.lineStart(axis, i, j), step = lat.stride[axis], n = lat.n[axis];
  bool previous = false;
  for (int64_t k = 0; k <= n; ++k) {
    const bool now = k < n && offsetInside(sd, start + k * step, offsetCells);
    if (now == previous) continue;
    previous = now;
    Surfel& x = *out++;
    if (k == 0 || k == n) {  // cut at the window's face
      const int64_t node = start + (k == 0 ? 0 : n - 1) * step;
      x.depth = float(lat.first[axis] + (k == 0 ? 0 : n - 1));
      float normal[3] = {0.0f, 0.0f, 0.0f};
      normal[axis] = now ? -1.0f : 1.0f;
      x.normal = encodeNormal(normal[0], normal[1], normal[2]);
      x.tag = makeSurfelTag(leaf[node], now);
      continue;
    }
    const int64_t a = start + (k - 1) * step, b = start + k * step;
    const double fa = double(sd[a]) - offsetCells, fb = double(sd[b]) - offsetCells;
    double t = fa / (fa - fb);
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    // In (node a, node b]: a surfel counts as before every node at or below its depth (the
    // LDI's rule, contour_cells.h), so one at a's own depth (t about 0: a surface through a node,
    // as a flat face on a grid plane puts it) would give a the new state on this ray alone while
    // offsetInside, and so the other axes' rays, keep the old one. That disagreement was
    // contoured as a crossing at the edge's middle: a whole flat face moved by half a cell.
    const float nodeA = float(lat.first[axis] + k - 1);
    x.depth = float(double(lat.first[axis] + k - 1) + t);
    if (!(x.depth > nodeA)) x.depth = nextafterf(nodeA, __builtin_huge_valf());
    int64_t pa[3], pb[3];
    pa[axis] = k - 1;
    pb[axis] = k;
    pa[u] = pb[u] = i;
    pa[v] = pb[v] = j;
    double ga[3], gb[3];
    offsetGradient(lat, sd, pa, ga);
    offsetGradient(lat, sd, pb, gb);
    float normal[3];
    for (int c = 0; c < 3; ++c) normal[c] = float(ga[c] + t * (gb[c] - ga[c]));
    const float length =
        sqrtf(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (length > 0.0f) {
      for (float& c : normal) c /= length;
    } else {
      normal[0] = normal[1] = normal[2] = 0.0f;
      normal[axis] = now ? -1.0f : 1.0f;
    }
    x.normal = encodeNormal(normal[0], normal[1], normal[2]);
    x.tag = makeSurfelTag(leaf[t < 0.5 ? a : b], now);
  }
}

}  // namespace strata
