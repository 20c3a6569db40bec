// Per-ray math shared by the CPU backend and its CUDA twin (gpu/). Everything here is a plain
// inline function on plain types, compiled as __host__ __device__ under nvcc, so both backends
// decide every hit, tie and Boolean transition with the same arithmetic.
#pragma once

#include <cmath>
#include <cstdint>

#if defined(__CUDACC__)
#define STRATA_HD __host__ __device__ __forceinline__
#else
#define STRATA_HD inline
#endif

namespace strata {

// ---------------------------------------------------------------------------------------------
// Surfels

// One sample of a surface on a ray: 12 bytes.
//   depth:  along the ray, in grid units from the grid origin (see grid.h)
//   normal: unit outward normal of the solid, octahedral-encoded in 2 x 16 bits
//   tag:    bit 0 = 1 when the ray enters the solid here (0: it leaves), bits 1..31 = id of the
//           leaf node the surface came from (for colour and picking)
struct Surfel {
  float depth;
  uint32_t normal;
  uint32_t tag;
};

STRATA_HD bool surfelEnters(uint32_t tag) {
  return (tag & 1u) != 0;
}
STRATA_HD uint32_t surfelLeaf(uint32_t tag) {
  return tag >> 1;
}
STRATA_HD uint32_t makeSurfelTag(uint32_t leaf, bool enters) {
  return (leaf << 1) | (enters ? 1u : 0u);
}

// The order of a ray's raw hits before they are normalised: by depth, then tag, then normal. A
// total order on distinct surfels (equal keys are identical surfels), so every sorting algorithm
// gives the same list: the CPU's std::sort and the CUDA twin's insertion sort agree bit for bit.
STRATA_HD bool surfelLess(const Surfel& a, const Surfel& b) {
  if (a.depth != b.depth) return a.depth < b.depth;
  if (a.tag != b.tag) return a.tag < b.tag;
  return a.normal < b.normal;
}

STRATA_HD float signNotZero(float x) {
  return x >= 0.0f ? 1.0f : -1.0f;
}

// Octahedral encoding of a unit vector into two snorm16 values (x in the low half).
STRATA_HD uint32_t encodeNormal(float x, float y, float z) {
  float l1 = fabsf(x) + fabsf(y) + fabsf(z);
  if (!(l1 > 0.0f)) return 0u;
  x /= l1;
  y /= l1;
  if (z < 0.0f) {
    float ox = (1.0f - fabsf(y)) * signNotZero(x);
    float oy = (1.0f - fabsf(x)) * signNotZero(y);
    x = ox;
    y = oy;
  }
  x = fminf(1.0f, fmaxf(-1.0f, x));
  y = fminf(1.0f, fmaxf(-1.0f, y));
  int qx = int(lrintf(x * 32767.0f));
  int qy = int(lrintf(y * 32767.0f));
  return (uint32_t(uint16_t(int16_t(qx)))) | (uint32_t(uint16_t(int16_t(qy))) << 16);
}

STRATA_HD void decodeNormal(uint32_t packed, float* out) {
  float x = float(int16_t(uint16_t(packed & 0xffffu))) / 32767.0f;
  float y = float(int16_t(uint16_t(packed >> 16))) / 32767.0f;
  float z = 1.0f - fabsf(x) - fabsf(y);
  if (z < 0.0f) {
    float ox = (1.0f - fabsf(y)) * signNotZero(x);
    float oy = (1.0f - fabsf(x)) * signNotZero(y);
    x = ox;
    y = oy;
  }
  float len = sqrtf(x * x + y * y + z * z);
  out[0] = x / len;
  out[1] = y / len;
  out[2] = z / len;
}

// True when `axis` is the axis the unit normal n is most aligned with (ties go to the lower
// axis): drawing or writing each surfel only there shows every patch of surface once, at an even
// density of one sample per h^2 of projected area.
STRATA_HD bool onDominantAxis(const float n[3], int axis) {
  const float a = fabsf(n[axis]);
  for (int k = 0; k < 3; ++k) {
    if (k == axis) continue;
    const float b = fabsf(n[k]);
    if (b > a || (b == a && k < axis)) return false;
  }
  return true;
}

// The thinnest wall one clean ray crosses (surfels [0, count), alternating enter / leave), in
// grid units, or +infinity when it crosses none it can judge. Each inside span is a wall of
// thickness length x |cos| of the angle between the ray and the wall's normal (exact for a flat
// wall, whose two faces share the normal); the two surfels' |cos| are averaged. Judged only
// where the span is a wall: its two faces turn away from each other (normals within 30 degrees
// of opposite; a ray through a part's corner meets two faces at right angles, which is no thin
// wall) and both face the ray steeply (|cos| >= 1/sqrt(3), 54.7 degrees: every surface faces
// one of the three axes that steeply, while a ray grazing a curved surface would see a short span
// that is no wall). Spans shorter than half a cell are not judged either:
// at that size they are as often slivers between faces that touch (a cutter flush with a face)
// as walls, and the grid cannot tell. *at: the span's middle depth.
STRATA_HD float rayThinnestWall(const Surfel* surfels, uint32_t count, int axis, float* at) {
  const float kSteep = 0.57735027f;
  const float kShortest = 0.5f;         // grid units
  const float kOpposite = -0.8660254f;  // cos 150 degrees
  float best = INFINITY;
  for (uint32_t k = 0; k + 1 < count; k += 2) {
    if (surfels[k + 1].depth - surfels[k].depth < kShortest) continue;
    float a[3], b[3];
    decodeNormal(surfels[k].normal, a);
    decodeNormal(surfels[k + 1].normal, b);
    const float ca = fabsf(a[axis]), cb = fabsf(b[axis]);
    if (ca < kSteep || cb < kSteep) continue;
    if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] > kOpposite) continue;
    const float t = (surfels[k + 1].depth - surfels[k].depth) * 0.5f * (ca + cb);
    if (t < best) {
      best = t;
      *at = 0.5f * (surfels[k].depth + surfels[k + 1].depth);
    }
  }
  return best;
}

// The normal with its sign flipped (a surfel taken from a subtracted solid).
STRATA_HD uint32_t flipNormal(uint32_t packed) {
  float n[3];
  decodeNormal(packed, n);
  return encodeNormal(-n[0], -n[1], -n[2]);
}

// ---------------------------------------------------------------------------------------------
// Watertight sampling of a triangle on the rays of one axis.
//
// Triangle corners are projected onto the (u, v) plane across the axis and snapped to a fixed
// lattice of kSubcell steps per cell; rays sit on multiples of kSubcell. Edge functions are then
// exact integer arithmetic, and exact zeros (a ray through an edge or a corner) are decided by
// symbolic perturbation: the ray is treated as passing through (u + e, v + e^2) for an
// infinitesimal e > 0. Each edge is evaluated with its endpoints in a canonical order, so the two
// triangles sharing an edge see exactly opposite signs. Together: a ray through a shared edge or
// vertex of a closed mesh hits exactly the triangles a generic nearby ray would, never 0 or 2.

constexpr int64_t kSubcell = 256;  // lattice steps per cell for projected corners
constexpr int64_t kMaxLatticeCoord = int64_t(1) << 60;  // |snapped coordinate| limit

#if defined(__SIZEOF_INT128__)
using wide_t = __int128;
#else
#error "Strata needs a compiler with 128-bit integers"
#endif

// Sign (+1 / -1) of the edge function of the directed edge a -> b at the perturbed ray point p:
// positive when p lies to the left of a -> b. Returns 0 only for a degenerate edge (a == b).
STRATA_HD int edgeSign(int64_t au, int64_t av, int64_t bu, int64_t bv, int64_t pu, int64_t pv) {
  bool swapped = (au > bu) || (au == bu && av > bv);
  if (swapped) {
    int64_t tu = au, tv = av;
    au = bu;
    av = bv;
    bu = tu;
    bv = tv;
  }
  wide_t e = wide_t(bu - au) * wide_t(pv - av) - wide_t(bv - av) * wide_t(pu - au);
  int s;
  if (e != 0)
    s = e > 0 ? 1 : -1;
  else if (bv != av)
    s = (av - bv) > 0 ? 1 : -1;  // d/du of the edge function is -(bv - av)
  else if (bu != au)
    s = (bu - au) > 0 ? 1 : -1;  // d/dv of the edge function is (bu - au)
  else
    return 0;
  return swapped ? -s : s;
}

// Exact edge function value (not perturbed) of the directed edge a -> b at p.
STRATA_HD wide_t edgeValue(int64_t au, int64_t av, int64_t bu, int64_t bv, int64_t pu, int64_t pv) {
  return wide_t(bu - au) * wide_t(pv - av) - wide_t(bv - av) * wide_t(pu - au);
}

// A triangle prepared for the rays of one axis.
struct ProjectedTriangle {
  int64_t u[3], v[3];      // snapped corners on the lattice (kSubcell steps per cell)
  double depth[3];         // corner depths in grid units
  int orientation;         // sign of the projected area: +1, -1, or 0 (parallel to the rays: skip)
  bool enters;             // the ray enters the solid through this triangle (orientation < 0)
  int64_t firstU, firstV;  // global lattice index of the window's ray (0, 0)
  int rayUMin, rayUMax, rayVMin, rayVMax;  // inclusive window ray range to test (may be empty)
  uint32_t normal;                         // encoded outward face normal
};

STRATA_HD int64_t floorDiv(int64_t a, int64_t b) {
  int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}
STRATA_HD int64_t ceilDiv(int64_t a, int64_t b) {
  return -floorDiv(-a, b);
}

// Prepares a triangle given its corners in global grid units (p[i][axis] is depth; p[i][u],
// p[i][v] are the coordinates across), the face normal (unit, outward), the global index of
// the window's first ray along u and v, and the window's ray counts. Corners must be finite
// with |coordinate| * kSubcell < kMaxLatticeCoord.
STRATA_HD ProjectedTriangle projectTriangle(const double p[3][3], const double normal[3], int axis,
                                            int64_t firstU, int64_t firstV, int raysU, int raysV) {
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  ProjectedTriangle t;
  t.firstU = firstU;
  t.firstV = firstV;
  for (int i = 0; i < 3; ++i) {
    t.u[i] = int64_t(llrint(p[i][ua] * double(kSubcell)));
    t.v[i] = int64_t(llrint(p[i][va] * double(kSubcell)));
    t.depth[i] = p[i][axis];
  }
  wide_t area = edgeValue(t.u[0], t.v[0], t.u[1], t.v[1], t.u[2], t.v[2]);
  t.orientation = area > 0 ? 1 : (area < 0 ? -1 : 0);
  t.enters = t.orientation < 0;
  t.normal = encodeNormal(float(normal[0]), float(normal[1]), float(normal[2]));
  int64_t umin = t.u[0], umax = t.u[0], vmin = t.v[0], vmax = t.v[0];
  for (int i = 1; i < 3; ++i) {
    umin = t.u[i] < umin ? t.u[i] : umin;
    umax = t.u[i] > umax ? t.u[i] : umax;
    vmin = t.v[i] < vmin ? t.v[i] : vmin;
    vmax = t.v[i] > vmax ? t.v[i] : vmax;
  }
  int64_t r0 = ceilDiv(umin, kSubcell) - firstU, r1 = floorDiv(umax, kSubcell) - firstU;
  int64_t s0 = ceilDiv(vmin, kSubcell) - firstV, s1 = floorDiv(vmax, kSubcell) - firstV;
  // Clamped to the window on both sides in 64 bits before narrowing: a triangle far outside it
  // (a tool parked away) must give an empty range, not one that wrapped around.
  r0 = r0 < 0 ? 0 : r0;
  r1 = r1 > raysU - 1 ? raysU - 1 : r1;
  s0 = s0 < 0 ? 0 : s0;
  s1 = s1 > raysV - 1 ? raysV - 1 : s1;
  const bool empty = r0 > r1 || s0 > s1;
  t.rayUMin = empty ? 0 : int(r0);
  t.rayUMax = empty ? -1 : int(r1);
  t.rayVMin = empty ? 0 : int(s0);
  t.rayVMax = empty ? -1 : int(s1);
  if (t.orientation == 0 || empty) {
    t.rayUMin = 0;  // nothing to test
    t.rayUMax = -1;
    t.rayVMin = 0;
    t.rayVMax = -1;
  }
  return t;
}

// The depth in global grid units at which the window's ray (i, j) meets the triangle's plane,
// for a ray that hits it (hitTriangle, triangleRowSpan). Barycentric weights from exact edge
// values; depth written as d0 + ... so that a triangle with equal corner depths (an axis-aligned
// face) gives exactly that depth.
STRATA_HD double hitDepth(const ProjectedTriangle& t, int i, int j) {
  const int64_t pu = (t.firstU + i) * kSubcell, pv = (t.firstV + j) * kSubcell;
  double w1 = double(edgeValue(t.u[2], t.v[2], t.u[0], t.v[0], pu, pv));
  double w2 = double(edgeValue(t.u[0], t.v[0], t.u[1], t.v[1], pu, pv));
  double w0 = double(edgeValue(t.u[1], t.v[1], t.u[2], t.v[2], pu, pv));
  double sum = w0 + w1 + w2;
  return t.depth[0] + (w1 * (t.depth[1] - t.depth[0]) + w2 * (t.depth[2] - t.depth[0])) / sum;
}

// Whether the window's ray (i, j) lies on the triangle's inner side of its edge k -> k + 1.
STRATA_HD bool insideEdge(const ProjectedTriangle& t, int k, int i, int j) {
  const int n = k == 2 ? 0 : k + 1;
  return edgeSign(t.u[k], t.v[k], t.u[n], t.v[n], (t.firstU + i) * kSubcell,
                  (t.firstV + j) * kSubcell) == t.orientation;
}

// Whether the window's ray (i, j) hits the triangle (with the perturbation tie rule).
STRATA_HD bool rayHitsTriangle(const ProjectedTriangle& t, int i, int j) {
  return insideEdge(t, 0, i, j) && insideEdge(t, 1, i, j) && insideEdge(t, 2, i, j);
}

// True when the window's ray (i, j) hits the triangle; then *depth is the depth of the hit in
// global grid units.
STRATA_HD bool hitTriangle(const ProjectedTriangle& t, int i, int j, double* depth) {
  if (!rayHitsTriangle(t, i, j)) return false;
  *depth = hitDepth(t, i, j);
  return true;
}

// The rays of window row j that hit the triangle: i in [*first, *last] (none when *first >
// *last), exactly those for which hitTriangle is true, found with a few edge tests a row
// instead of three a ray. Along a row an edge's perturbed sign is monotone in i (its edge
// function is linear in u; a zero is decided as for a point just beyond it, see edgeSign), so
// each edge keeps a prefix or a suffix of the row and the hits are one run. Each end is found
// by edgeSign itself, starting next to where the edge's line crosses the row.
// Rows of at most kNarrowRow rays are tested ray by ray (fewer edge tests than the ends').
constexpr int kNarrowRow = 4;
STRATA_HD void triangleRowSpan(const ProjectedTriangle& t, int j, int* first, int* last) {
  int lo = t.rayUMin, hi = t.rayUMax;
  if (hi - lo < kNarrowRow) {
    *first = hi + 1;
    *last = hi;
    for (int i = lo; i <= hi; ++i)
      if (rayHitsTriangle(t, i, j)) {
        if (*first > i) *first = i;
        *last = i;  // the hits are one run: [first hit, last hit]
      }
    return;
  }
  for (int k = 0; k < 3 && lo <= hi; ++k) {
    const bool atLo = insideEdge(t, k, lo, j), atHi = insideEdge(t, k, hi, j);
    if (atLo && atHi) continue;  // the whole run so far
    if (!atLo && !atHi) {        // none of it (monotone)
      lo = 1;
      hi = 0;
      break;
    }
    // One change within (lo, hi]: the first i on the inner side (a suffix) or the first past it
    // (a prefix). Bisection, with its first probes at the crossing of the edge's line.
    const int n = k == 2 ? 0 : k + 1;
    const double du = double(t.u[n] - t.u[k]), dv = double(t.v[n] - t.v[k]);
    const double pv = double((t.firstV + j) * kSubcell);
    double guess = double(lo) + 1.0;
    if (dv != 0.0) {
      const double cross =
          (double(t.u[k]) + du * (pv - double(t.v[k])) / dv) / double(kSubcell) - double(t.firstU);
      guess = cross < double(lo) + 1.0 ? double(lo) + 1.0
                                       : (cross > double(hi) ? double(hi) : ceil(cross));
    }
    // Invariant: insideEdge(lo) == atLo, insideEdge(hi) == atHi, the change in (a, b].
    int a = lo, b = hi, probe = int(guess);
    for (int step = 0; b - a > 1; ++step) {
      if (step >= 2 || probe <= a || probe >= b) probe = a + (b - a) / 2;
      if (insideEdge(t, k, probe, j) == atLo) {
        a = probe;
        probe = a + 1;
      } else {
        b = probe;
        probe = b - 1;
      }
    }
    if (atLo)
      hi = a;  // a prefix: [lo, a]
    else
      lo = b;  // a suffix: [b, hi]
  }
  *first = lo;
  *last = hi;
}

// ---------------------------------------------------------------------------------------------
// Per-ray sweeps.
//
// Events at depths closer than kCoincidentDepth (grid units) are treated as one: all are applied
// together and at most one transition is emitted, so coincident faces (two boxes sharing a face,
// A minus A) leave neither a seam nor a zero-thickness sliver. Features thinner than this are
// below what an LDI represents.
constexpr float kCoincidentDepth = 1.0f / 1024.0f;

// A surfel of a child, seen by the parent's sweep.
struct RayEvent {
  float depth;
  uint32_t normal;
  uint32_t tag;
  uint32_t child;  // index of the child (operation) or 0 (leaf)
};

enum class RayOp : uint8_t { Union = 0, Intersection = 1, Difference = 2 };

// One axis of a child LDI as the per-ray steps read it (CSR, see ldi.h). Whole: offsets[r] ..
// offsets[r + 1] index grid ray r's surfels. Windowed (whole == false): offsets index the local
// rays of the window of uCount x vCount rays from (u0, v0); other rays have none. Memory of the
// side that runs the step.
struct AxisLdiView {
  const uint32_t* offsets;
  const Surfel* surfels;
  bool whole = true;
  int u0 = 0, v0 = 0, uCount = 0, vCount = 0;
};

// Child c's surfels on grid ray `ray`, whose coordinates across the axis are (i, j):
// [*begin, *end) in surfels (empty outside a window).
STRATA_HD void viewRayRange(const AxisLdiView& v, int64_t ray, int i, int j, uint32_t* begin,
                            uint32_t* end) {
  int64_t local = ray;
  if (!v.whole) {
    if (i < v.u0 || j < v.v0 || i >= v.u0 + v.uCount || j >= v.v0 + v.vCount) {
      *begin = *end = 0;
      return;
    }
    local = int64_t(i - v.u0) + int64_t(j - v.v0) * v.uCount;
  }
  *begin = v.offsets[local];
  *end = v.offsets[local + 1];
}

// The number of events on grid ray `ray` = (i, j) of the children (children[c] is child c's
// axis).
STRATA_HD uint64_t rayEventCount(const AxisLdiView* children, int childCount, int64_t ray, int i,
                                 int j) {
  uint64_t n = 0;
  for (int c = 0; c < childCount; ++c) {
    uint32_t b, e;
    viewRayRange(children[c], ray, i, j, &b, &e);
    n += e - b;
  }
  return n;
}

// Gathers the surfels of grid ray `ray` = (i, j) of every child into `events` (room for
// rayEventCount), sorted by depth with ties in child order, and within a child in its list's order:
// a stable insertion of the children's lists one after the other, which orders exactly as a stable
// sort of their concatenation does. Returns the number of events.
STRATA_HD int gatherRayEvents(const AxisLdiView* children, int childCount, int64_t ray, int i,
                              int j, RayEvent* events) {
  int n = 0;
  for (int c = 0; c < childCount; ++c) {
    const AxisLdiView& v = children[c];
    uint32_t first, last;
    viewRayRange(v, ray, i, j, &first, &last);
    for (uint32_t k = first; k < last; ++k) {
      const Surfel s = v.surfels[k];
      const RayEvent e{s.depth, s.normal, s.tag, uint32_t(c)};
      int m = n - 1;
      while (m >= 0 && e.depth < events[m].depth) {
        events[m + 1] = events[m];
        --m;
      }
      events[m + 1] = e;
      ++n;
    }
  }
  return n;
}

// Sorts events by depth, stably (ties keep their order): the order gatherRayEvents produces
// when the events were appended child by child. Insertion: quadratic, for short rays.
STRATA_HD void sortRayEvents(RayEvent* events, int n) {
  for (int k = 1; k < n; ++k) {
    const RayEvent e = events[k];
    int m = k - 1;
    while (m >= 0 && e.depth < events[m].depth) {
      events[m + 1] = events[m];
      --m;
    }
    events[m + 1] = e;
  }
}

// Normalises a leaf's sorted raw hits into clean alternating enter/exit surfels: inside where the
// winding number (enter +1, exit -1) is non-zero, so overlapping shells of one mesh unite. Hits
// outside [lo, hi] only update the winding; a solid crossing lo or hi is closed there with a
// synthetic surfel facing along -axis / +axis (normalMinus / normalPlus). Returns the number of
// surfels written to out (at most n + 1).
// A ray whose hits leave the winding away from zero went through a hole of an open mesh (taken
// with --allow-open or marked open; a closed mesh's rays always balance, by the hit test's tie
// rule): what lies beyond its last hit is unknown, and taking it as inside ran a streak of solid
// to the grid's end. Such a ray is left empty for this leaf (0 surfels); the two other axes still
// sample the part there, and the contour's node signs follow their majority.
STRATA_HD int normalizeLeafRay(const Surfel* in, int n, float lo, float hi, uint32_t leaf,
                               uint32_t normalMinus, uint32_t normalPlus, Surfel* out) {
  int balance = 0;
  for (int m = 0; m < n; ++m) balance += surfelEnters(in[m].tag) ? 1 : -1;
  if (balance != 0) return 0;
  int written = 0;
  int winding = 0;
  bool inside = false;
  int k = 0;
  // Hits before lo: only the winding.
  while (k < n && in[k].depth < lo) {
    winding += surfelEnters(in[k].tag) ? 1 : -1;
    ++k;
  }
  if (winding != 0) {
    out[written++] = Surfel{lo, normalMinus, makeSurfelTag(leaf, true)};
    inside = true;
  }
  while (k < n && in[k].depth <= hi) {
    const float start = in[k].depth;
    int first = k;
    while (k < n && in[k].depth <= hi && in[k].depth - start <= kCoincidentDepth) {
      winding += surfelEnters(in[k].tag) ? 1 : -1;
      ++k;
    }
    bool now = winding != 0;
    if (now != inside) {
      int pick = first;
      for (int m = first; m < k; ++m) {
        if (surfelEnters(in[m].tag) == now) {
          pick = m;
          break;
        }
      }
      out[written++] = Surfel{in[pick].depth, in[pick].normal, makeSurfelTag(leaf, now)};
      inside = now;
    }
  }
  if (inside) out[written++] = Surfel{hi, normalPlus, makeSurfelTag(leaf, false)};
  return written;
}

// State of an n-ary Boolean while sweeping one ray: how many children are inside.
struct BooleanState {
  int insideCount;   // children currently inside (all children for union / intersection,
                     // the subtracted ones for difference)
  bool firstInside;  // difference only: the first child is inside
};

STRATA_HD bool booleanInside(RayOp op, const BooleanState& s, int childCount) {
  switch (op) {
    case RayOp::Union:
      return s.insideCount > 0;
    case RayOp::Intersection:
      return s.insideCount == childCount;
    default:
      return s.firstInside && s.insideCount == 0;
  }
}

// Would this child's event move the node towards `becomingInside`?
STRATA_HD bool eventDrives(RayOp op, const RayEvent& e, bool becomingInside) {
  bool enters = surfelEnters(e.tag);
  bool subtracted = op == RayOp::Difference && e.child != 0;
  return (enters != subtracted) == becomingInside;
}

// Combines the children's clean surfel lists of one ray. `events` holds all children's surfels
// sorted by (depth, child); children's lists alternate enter / exit. Writes the node's clean list
// to out (at most n entries) and returns its length. Surfels taken from a subtracted child get
// their normal flipped.
STRATA_HD int combineRayEvents(RayOp op, int childCount, const RayEvent* events, int n,
                               Surfel* out) {
  BooleanState s{0, false};
  bool inside = false;
  int written = 0;
  int k = 0;
  while (k < n) {
    const float start = events[k].depth;
    int first = k;
    while (k < n && events[k].depth - start <= kCoincidentDepth) {
      const RayEvent& e = events[k];
      int delta = surfelEnters(e.tag) ? 1 : -1;
      if (op == RayOp::Difference && e.child == 0)
        s.firstInside = delta > 0;
      else
        s.insideCount += delta;
      ++k;
    }
    bool now = booleanInside(op, s, childCount);
    if (now != inside) {
      int pick = first;
      for (int m = first; m < k; ++m) {
        if (eventDrives(op, events[m], now)) {
          pick = m;
          break;
        }
      }
      const RayEvent& e = events[pick];
      bool subtracted = op == RayOp::Difference && e.child != 0;
      uint32_t normal = subtracted ? flipNormal(e.normal) : e.normal;
      out[written++] = Surfel{e.depth, normal, makeSurfelTag(surfelLeaf(e.tag), now)};
      inside = now;
    }
  }
  return written;
}

}  // namespace strata
