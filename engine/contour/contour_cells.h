// The per-cell steps of dual contouring on one tile, shared by the CPU exporter
// (contour_tile.cpp) and its CUDA twin (gpu/contour/contour_tile.cu): crossings on grid edges,
// one QEF vertex per surface component of a boundary cell, and the polygons around the
// sign-changing edges a cell owns. Plain inline functions over a plain view of the tile.
#pragma once

#include <cstdint>

#include "engine/contour/contour_math.h"

namespace strata {

// A vertex: a component of a boundary cell (key = global cell * 4 + component), or a vertex
// splitting a face segment (key with the top bit set). Position in global grid units.
struct CellVertex {
  uint64_t key;
  double position[3];
  double planeDistance;  // grid units: distance to the farthest of its Hermite planes
};

struct CellTriangle {
  uint64_t vertex[3];  // vertex keys, counter-clockwise seen from outside
  uint64_t order;      // global edge key * 8 + triangle: a tiling-independent order
  uint32_t leaf;       // leaf id of the surfel the edge's crossing came from
  uint8_t resolved;    // kInsideResolved | kOutsideResolved of the edge's two nodes
};

// CellTriangle::resolved: whether the grid resolves the sides of the sign-changing edge the
// triangle is dual to. The edge's inside node is inside by all three of its rays; its outside
// node is outside by all three, or lies on the grid's outer faces. A closed component none of
// whose triangles has one of the bits encloses (or excludes) only nodes the rays disagree on:
// a speck thinner than a cell that the grid cannot resolve (export/drop_specks.h).
constexpr uint8_t kInsideResolved = 1;
constexpr uint8_t kOutsideResolved = 2;

// At most 3 owned edges per cell, each a polygon of at most 8 vertices (4 cells and up to 4
// face-segment vertices): 6 triangles and 4 face vertices per edge.
constexpr int kMaxCellTriangles = 18;
constexpr int kMaxCellFaceVertices = 12;

// Everything a tile's per-cell steps read. Window coordinates: nodes [0, cells] per axis,
// node (i, j, k) at index i + (cells.x + 1) * (j + (cells.y + 1) * k); cells likewise with
// `cells` per axis. All pointers address memory of the side that runs the step.
struct TileView {
  int first[3];                // global index of the window's first node
  int cells[3];                // window cells per axis
  int globalCells[3];          // the whole grid's cells
  int ownedLo[3], ownedHi[3];  // owned edges' lower nodes, window coordinates, [lo, hi)
  const uint32_t* offsets[3];  // the root LDI of the window, per axis (CSR)
  const Surfel* surfels[3];
  // Node sides as two bit planes (nodeBit below): a row of nodes along x takes rowWords words.
  const uint64_t* insideBits;     // 1: the node is inside (decideNodeSide)
  const uint64_t* unanimousBits;  // 1: its three rays agree (all inside or all outside)
  int64_t rowWords;               // nodeRowWords(cells[0])
  const uint32_t* boundary;       // boundary cells (mixed corners), increasing index
  const uint8_t* boundaryMasks;   // per boundary cell: bit c set when corner c is inside
  int64_t boundaryCount;
  // Optional (null: search all of `boundary`): per row of window cells along x, (j, k) at
  // j + cells[1] * k, its first boundary cell's number, and boundaryCount last.
  const uint32_t* boundaryRowStart;
  const uint32_t* vertexStart;  // per boundary cell: its first vertex in `vertices`
  const CellVertex* vertices;   // the tile's cell vertices (read by the polygon step)
  // Optional (null: the polygon step looks the crossings up again): per boundary cell, for
  // each axis, its corner-0 edge's crossing as the vertex step found it, cornerCrossingWord.
  // Written by the vertex step (placeCellVertices and the CPU's batches of it); a view that
  // points here must not reach the polygon step before every cell's vertices are placed.
  uint32_t* cornerCrossings;
};

// An edge crossing's leaf and whether it was synthesised, in one word (leaves are below 2^31:
// surfelLeaf), for TileView::cornerCrossings.
STRATA_HD uint32_t cornerCrossingWord(uint32_t leaf, bool synthesized) {
  return leaf | (synthesized ? 0x80000000u : 0u);
}

STRATA_HD int64_t tileNode(const TileView& t, int i, int j, int k) {
  return int64_t(i) + int64_t(t.cells[0] + 1) * (int64_t(j) + int64_t(t.cells[1] + 1) * k);
}
// The 64-bit words of one row of window nodes along x (cells + 1 nodes), in a node bit plane.
STRATA_HD int64_t nodeRowWords(int cellsX) {
  return (int64_t(cellsX) + 1 + 63) / 64;
}
// The first word of the row of nodes (., j, k) in a node bit plane.
STRATA_HD int64_t nodeRow(const TileView& t, int j, int k) {
  return (int64_t(j) + int64_t(t.cells[1] + 1) * k) * t.rowWords;
}
// Bit i of a row of a node bit plane.
STRATA_HD uint32_t rowBit(const uint64_t* row, int i) {
  return uint32_t(row[i >> 6] >> (i & 63)) & 1u;
}
STRATA_HD uint32_t nodeInside(const TileView& t, int i, int j, int k) {
  return rowBit(t.insideBits + nodeRow(t, j, k), i);
}
STRATA_HD uint32_t nodeUnanimous(const TileView& t, int i, int j, int k) {
  return rowBit(t.unanimousBits + nodeRow(t, j, k), i);
}
STRATA_HD int64_t tileCell(const TileView& t, int i, int j, int k) {
  return int64_t(i) + int64_t(t.cells[0]) * (int64_t(j) + int64_t(t.cells[1]) * k);
}
STRATA_HD void tileCellCoords(const TileView& t, uint32_t index, int c[3]) {
  const int64_t i = index;
  c[0] = int(i % t.cells[0]);
  c[1] = int((i / t.cells[0]) % t.cells[1]);
  c[2] = int(i / (int64_t(t.cells[0]) * t.cells[1]));
}
STRATA_HD uint64_t tileGlobalCell(const TileView& t, const int c[3]) {
  return uint64_t(c[0] + t.first[0]) +
         uint64_t(t.globalCells[0]) * (uint64_t(c[1] + t.first[1]) +
                                       uint64_t(t.globalCells[1]) * uint64_t(c[2] + t.first[2]));
}

// The window ray along `axis` through window node n (n[axis] is ignored): rays of an axis are
// indexed u + (cells[u] + 1) * v, with u = (axis + 1) % 3 and v = (axis + 2) % 3.
STRATA_HD int64_t tileRay(const TileView& t, int axis, const int n[3]) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  return int64_t(n[u]) + int64_t(n[v]) * (t.cells[u] + 1);
}

// One ray's walk over its surfels for the node votes, visiting its nodes in increasing order.
struct RayVoteCursor {
  uint32_t next, end;  // the next surfel and the ray's end, in t.surfels[axis]
  bool in;             // parity of the surfels passed
};

// The cursor at the start of the window ray along `axis` through window node n.
STRATA_HD RayVoteCursor startRayVote(const TileView& t, int axis, const int n[3]) {
  const int64_t ray = tileRay(t, axis, n);
  return RayVoteCursor{t.offsets[axis][ray], t.offsets[axis][ray + 1], false};
}

// This ray's vote for its window node number `node` along the axis (1: inside), after the nodes
// before it. A node counts the surfels at or before it: it sits just after its own depth, as the
// tie rule's perturbation puts the other axes' rays just after theirs.
STRATA_HD uint8_t rayVote(const TileView& t, int axis, RayVoteCursor& c, int node) {
  const float depth = float(t.first[axis] + node);
  while (c.next < c.end && t.surfels[axis][c.next].depth <= depth) {
    c.in = !c.in;
    ++c.next;
  }
  return c.in ? 1 : 0;
}

// Global key of the edge along `axis` whose lower node is `node` (global).
STRATA_HD uint64_t globalEdgeKey(const int globalCells[3], int axis, const int node[3]) {
  const uint64_t nx = uint64_t(globalCells[0]) + 1, ny = uint64_t(globalCells[1]) + 1;
  return ((uint64_t(node[2]) * ny + uint64_t(node[1])) * nx + uint64_t(node[0])) * 3 +
         uint64_t(axis);
}

// Key of the vertex splitting the face segment around inside corner `corner` (0..3: offset
// along the face's lower in-plane axis + 2 * along the higher) of the face whose lowest node
// is `faceMin` (global) and whose normal is `normalAxis`.
STRATA_HD uint64_t faceSegmentKey(const int globalCells[3], const int faceMin[3], int normalAxis,
                                  int corner) {
  const uint64_t nx = uint64_t(globalCells[0]) + 1, ny = uint64_t(globalCells[1]) + 1;
  const uint64_t node =
      (uint64_t(faceMin[2]) * ny + uint64_t(faceMin[1])) * nx + uint64_t(faceMin[0]);
  return (uint64_t(1) << 63) | ((node * 3 + uint64_t(normalAxis)) * 4 + uint64_t(corner));
}

// The node's decided side from its three votes (rays saying inside): majority, and outside on
// the grid's outer faces.
STRATA_HD uint8_t decideNodeSide(uint8_t votes, bool onOuterFace) {
  return (!onOuterFace && votes >= 2) ? 1 : 0;
}

// The corner mask of window cell (i, j, k) from the node sides (corner c at offset c & 1 along
// x, (c >> 1) & 1 along y, c >> 2 along z).
STRATA_HD uint8_t cellMaskFromNodes(const TileView& t, int i, int j, int k) {
  const uint64_t* r00 = t.insideBits + nodeRow(t, j, k);
  const uint64_t* r10 = r00 + t.rowWords;
  const uint64_t* r01 = t.insideBits + nodeRow(t, j, k + 1);
  const uint64_t* r11 = r01 + t.rowWords;
  return uint8_t(rowBit(r00, i) | (rowBit(r00, i + 1) << 1) | (rowBit(r10, i) << 2) |
                 (rowBit(r10, i + 1) << 3) | (rowBit(r01, i) << 4) | (rowBit(r01, i + 1) << 5) |
                 (rowBit(r11, i) << 6) | (rowBit(r11, i + 1) << 7));
}

struct EdgeCrossing {
  double t;  // global grid units along the edge's axis
  float normal[3];
  uint32_t leaf;
  bool synthesized;
};

// The crossing on the edge along `axis` from window node n, whose side is `lowerInside`: the
// first surfel in (depth(n), depth(n) + 1] that crosses in the decided direction; when the
// ray's own parity disagreed with the decided signs (a tangent ray), one synthesised at the
// middle facing out of the solid along the axis, with the leaf of the ray's nearest surfel.
STRATA_HD EdgeCrossing tileCrossing(const TileView& t, int axis, const int n[3], bool lowerInside) {
  const int64_t ray = tileRay(t, axis, n);
  const float lo = float(t.first[axis] + n[axis]), hi = lo + 1.0f;
  const Surfel* begin = t.surfels[axis] + t.offsets[axis][ray];
  const Surfel* end = t.surfels[axis] + t.offsets[axis][ray + 1];
  // First surfel with depth > lo.
  const Surfel* s = begin;
  int64_t count = end - begin;
  while (count > 0) {
    const int64_t half = count / 2;
    if (s[half].depth <= lo) {
      s += half + 1;
      count -= half + 1;
    } else {
      count = half;
    }
  }
  const bool wantEnter = !lowerInside;  // moving along +axis from outside into the solid
  EdgeCrossing c;
  for (; s != end && s->depth <= hi; ++s) {
    if (surfelEnters(s->tag) == wantEnter) {
      c.t = s->depth;
      decodeNormal(s->normal, c.normal);
      c.leaf = surfelLeaf(s->tag);
      c.synthesized = false;
      return c;
    }
  }
  c.t = double(lo) + 0.5;
  c.normal[0] = c.normal[1] = c.normal[2] = 0.0f;
  c.normal[axis] = wantEnter ? -1.0f : 1.0f;
  c.synthesized = true;
  c.leaf = 0;
  float nearest = 3.4e38f;
  for (const Surfel* x = begin; x != end; ++x) {
    const float d = fabsf(x->depth - lo);
    if (d < nearest) {
      nearest = d;
      c.leaf = surfelLeaf(x->tag);
    }
  }
  return c;
}

// The Hermite data of a boundary cell per surface component, and their QEFs: the first step of
// placing its vertices.
struct CellPlanes {
  int c[3];  // the window cell
  int components;
  uint32_t cornerCrossing[3];  // per axis, its corner-0 edge's crossing (cornerCrossingWord)
  double points[kMaxCellComponents][12][3];
  float normals[kMaxCellComponents][12][3];
  int n[kMaxCellComponents];
  Qef qef[kMaxCellComponents];
};

STRATA_HD void gatherCellPlanes(const TileView& t, const CellCaseTable& table, int64_t b,
                                CellPlanes* cp) {
  tileCellCoords(t, t.boundary[b], cp->c);
  const int* c = cp->c;
  const uint8_t mask = t.boundaryMasks[b];
  const CellCase& cc = table.cases[mask];
  cp->components = cc.components;
  for (int comp = 0; comp < kMaxCellComponents; ++comp) cp->n[comp] = 0;
  for (int axis = 0; axis < 3; ++axis) cp->cornerCrossing[axis] = 0;
  for (int edge = 0; edge < 12; ++edge) {
    const int comp = cc.edgeComponent[edge];
    if (comp < 0) continue;
    int c0, c1;
    edgeCorners(edge, &c0, &c1);
    const int axis = edge >> 2;
    const int node[3] = {c[0] + (c0 & 1), c[1] + ((c0 >> 1) & 1), c[2] + ((c0 >> 2) & 1)};
    const EdgeCrossing x = tileCrossing(t, axis, node, (mask >> c0) & 1);
    if (c0 == 0) cp->cornerCrossing[axis] = cornerCrossingWord(x.leaf, x.synthesized);
    double* p = cp->points[comp][cp->n[comp]];
    for (int d = 0; d < 3; ++d) p[d] = double(t.first[d] + node[d]);
    p[axis] = x.t;
    for (int d = 0; d < 3; ++d) cp->normals[comp][cp->n[comp]][d] = x.normal[d];
    ++cp->n[comp];
  }
  for (int comp = 0; comp < cp->components; ++comp)
    cp->qef[comp] = buildQef(cp->points[comp], cp->normals[comp], cp->n[comp]);
}

// The last step: the cell's vertices (one per component, in component order) to out, from the
// decompositions m[comp], v[comp] of its QEFs' matrices (symmetricEigen3 of qefMatrix).
STRATA_HD void finishCellVertices(const TileView& t, const CellPlanes& cp, const double (*m)[3][3],
                                  const double (*v)[3][3], CellVertex* out) {
  const int64_t cellGlobal[3] = {cp.c[0] + t.first[0], cp.c[1] + t.first[1], cp.c[2] + t.first[2]};
  double x[kMaxCellComponents][3];
  double mass[kMaxCellComponents][3];
  for (int comp = 0; comp < cp.components; ++comp) {
    const Qef& q = cp.qef[comp];
    for (int k = 0; k < 3; ++k) x[comp][k] = mass[comp][k] = q.mass[k];
    solveQefWithEigen(q, m[comp], v[comp], cellGlobal, x[comp]);
  }
  separateCoincidentVertices(x, mass, cp.components);
  const uint64_t cellKey = tileGlobalCell(t, cp.c) * 4;
  for (int comp = 0; comp < cp.components; ++comp) {
    out[comp].key = cellKey + uint64_t(comp);
    for (int k = 0; k < 3; ++k) out[comp].position[k] = x[comp][k];
    out[comp].planeDistance =
        qefPlaneDistance(cp.points[comp], cp.normals[comp], cp.n[comp], x[comp]);
  }
}

// Keeps boundary cell number b's corner-0 crossings for the polygon step, where the view has
// room for them (TileView::cornerCrossings).
STRATA_HD void keepCornerCrossings(const TileView& t, int64_t b, const CellPlanes& cp) {
  if (t.cornerCrossings)
    for (int axis = 0; axis < 3; ++axis) t.cornerCrossings[b * 3 + axis] = cp.cornerCrossing[axis];
}

// Writes the vertices of boundary cell number b (one per surface component, in component
// order) to out. The CPU places two cells at a time with the same steps (contour_tile.cpp).
STRATA_HD void placeCellVertices(const TileView& t, const CellCaseTable& table, int64_t b,
                                 CellVertex* out) {
  CellPlanes cp;
  gatherCellPlanes(t, table, b, &cp);
  double m[kMaxCellComponents][3][3], v[kMaxCellComponents][3][3];
  for (int comp = 0; comp < cp.components; ++comp) {
    qefMatrix(cp.qef[comp], m[comp]);
    symmetricEigen3(m[comp], v[comp]);
  }
  finishCellVertices(t, cp, m, v, out);
  keepCornerCrossings(t, b, cp);
}

// The vertex of the component of window cell c that contains cell edge `edge`.
STRATA_HD const CellVertex& vertexOfEdge(const TileView& t, const CellCaseTable& table,
                                         const int c[3], int edge) {
  const uint32_t index = uint32_t(tileCell(t, c[0], c[1], c[2]));
  int64_t lo = 0, hi = t.boundaryCount;  // lower bound of index in t.boundary
  if (t.boundaryRowStart) {              // within the cell's row: the same lower bound
    const int64_t row = int64_t(c[1]) + int64_t(t.cells[1]) * c[2];
    lo = t.boundaryRowStart[row];
    hi = t.boundaryRowStart[row + 1];
  }
  while (lo < hi) {
    const int64_t mid = (lo + hi) / 2;
    if (t.boundary[mid] < index)
      lo = mid + 1;
    else
      hi = mid;
  }
  return t
      .vertices[t.vertexStart[lo] + uint32_t(table.cases[t.boundaryMasks[lo]].edgeComponent[edge])];
}

STRATA_HD double splitAgreement(const double* a, const double* b, const double* c,
                                const double* d) {
  // Triangles (a, b, c) and (a, c, d): the cosine between their normals; -2 if one is degenerate.
  double e1[3], e2[3], e3[3], n1[3], n2[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = b[k] - a[k];
    e2[k] = c[k] - a[k];
    e3[k] = d[k] - a[k];
  }
  n1[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n1[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n1[2] = e1[0] * e2[1] - e1[1] * e2[0];
  n2[0] = e2[1] * e3[2] - e2[2] * e3[1];
  n2[1] = e2[2] * e3[0] - e2[0] * e3[2];
  n2[2] = e2[0] * e3[1] - e2[1] * e3[0];
  const double l1 = sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
  const double l2 = sqrt(n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2]);
  if (!(l1 > 0.0) || !(l2 > 0.0)) return -2.0;
  return (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]) / (l1 * l2);
}

STRATA_HD int localEdgeIndex(int axis, const int bits[3]) {
  return 4 * axis + bits[(axis + 1) % 3] + 2 * bits[(axis + 2) % 3];
}

// The polygon around one sign-changing edge: the vertices of the four cells around it,
// counter-clockwise in (u, v) seen from +axis, each followed by a face-segment vertex where the
// face it shares with the next cell is split (at most 8 vertices).
struct EdgePolygon {
  uint64_t keys[8];
  double pos[8][3];
  int count;
  int firstInserted;  // the first face-segment vertex, or -1 when there is none
};

// Offsets (along u, then v) below the edge's lower node of the q-th cell around an edge, q in
// 0..3 counter-clockwise in (u, v) seen from +axis.
STRATA_HD void cellAroundEdge(int q, int offset[2]) {
  const int around[4][2] = {{1, 1}, {0, 1}, {0, 0}, {1, 0}};
  offset[0] = around[q][0];
  offset[1] = around[q][1];
}

// The window cells around the edge along `axis` from window node n, q = 0..3 as cellAroundEdge.
STRATA_HD void cellsAroundEdge(const int n[3], int axis, int cells[4][3]) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  for (int q = 0; q < 4; ++q) {
    int offset[2];
    cellAroundEdge(q, offset);
    for (int k = 0; k < 3; ++k) cells[q][k] = n[k];
    cells[q][u] -= offset[0];  // >= 0: the grid's outer nodes are outside
    cells[q][v] -= offset[1];
  }
}

// The sign-changing edges boundary cell number b owns (those from its corner 0 whose lower node
// the tile owns), as a bit per axis; n its window cell (= the edges' lower node), in0 the side
// of its corner 0.
STRATA_HD int ownedCrossingEdges(const TileView& t, int64_t b, int n[3], bool* in0) {
  tileCellCoords(t, t.boundary[b], n);
  for (int k = 0; k < 3; ++k)
    if (n[k] < t.ownedLo[k] || n[k] >= t.ownedHi[k]) return 0;
  const uint8_t mask = t.boundaryMasks[b];
  *in0 = mask & 1;
  int axes = 0;
  for (int axis = 0; axis < 3; ++axis)  // corner 1, 2 or 4 against corner 0
    if (bool((mask >> (1 << axis)) & 1) != *in0) axes |= 1 << axis;
  return axes;
}

// The face shared by cells q and q + 1 around an edge along `axis`.
struct FaceAroundEdge {
  bool normalU;    // its normal is along u (else along v)
  int normalAxis;  // u or v
  int w;           // its other in-plane axis (v or u)
  int wBit;        // where the edge lies across the face along w (same in both cells)
};

STRATA_HD FaceAroundEdge faceAroundEdge(int axis, int q) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  int aq[2], aq1[2];
  cellAroundEdge(q, aq);
  cellAroundEdge((q + 1) % 4, aq1);
  FaceAroundEdge f;
  f.normalU = aq[0] != aq1[0];
  f.normalAxis = f.normalU ? u : v;
  f.w = f.normalU ? v : u;
  f.wBit = f.w == u ? aq[0] : aq[1];
  return f;
}

// Whether the face shared by cells q and q + 1 around the edge along `axis` (cells: the four
// cells around it) is split: on each side both of its edges along `axis` belong to one
// component, and the face is ambiguous (its two w-edges cross too; otherwise the two
// axis-edges form the face's single segment).
STRATA_HD bool faceSplitsEdge(const TileView& t, const CellCaseTable& table, const int cells[4][3],
                              int axis, int q, const FaceAroundEdge& f) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const int q1 = (q + 1) % 4;
  int aq[2], aq1[2];
  cellAroundEdge(q, aq);
  cellAroundEdge(q1, aq1);
  int bitsQ[3], bitsQ1[3];
  bitsQ[axis] = bitsQ1[axis] = 0;
  bitsQ[u] = aq[0];
  bitsQ[v] = aq[1];
  bitsQ1[u] = aq1[0];
  bitsQ1[v] = aq1[1];
  const int eQ = localEdgeIndex(axis, bitsQ), eQ1 = localEdgeIndex(axis, bitsQ1);
  bitsQ[f.w] = bitsQ1[f.w] = 1 - f.wBit;
  const int oppQ = localEdgeIndex(axis, bitsQ), oppQ1 = localEdgeIndex(axis, bitsQ1);
  const CellCase& caseQ = table.cases[cellMaskFromNodes(t, cells[q][0], cells[q][1], cells[q][2])];
  const CellCase& caseQ1 =
      table.cases[cellMaskFromNodes(t, cells[q1][0], cells[q1][1], cells[q1][2])];
  if (caseQ.edgeComponent[oppQ] != caseQ.edgeComponent[eQ] ||
      caseQ1.edgeComponent[oppQ1] != caseQ1.edgeComponent[eQ1])
    return false;
  int wBits[3];
  wBits[f.normalAxis] = f.normalU ? aq[0] : aq[1];
  wBits[f.w] = 0;
  wBits[axis] = 0;
  const int w0 = localEdgeIndex(f.w, wBits);
  wBits[axis] = 1;
  const int w1 = localEdgeIndex(f.w, wBits);
  return !(caseQ.edgeComponent[w0] < 0 || caseQ.edgeComponent[w1] < 0);
}

// The vertex splitting a split face (f) around the edge along `axis` from window node n, the
// corner 0 of a boundary cell (in0: its side): on the face segment around the edge's inside
// corner, made of this edge and the w-edge at that corner, halfway between their crossings.
STRATA_HD void faceSegmentVertex(const TileView& t, const int n[3], int axis, bool in0,
                                 const FaceAroundEdge& f, uint64_t* key, double pos[3]) {
  const int w = f.w;
  int insideCorner[3] = {n[0], n[1], n[2]};
  if (!in0) insideCorner[axis] += 1;
  int faceMin[3] = {n[0], n[1], n[2]};
  if (f.wBit == 1) faceMin[w] -= 1;
  int wLower[3] = {insideCorner[0], insideCorner[1], insideCorner[2]};
  if (f.wBit == 1) wLower[w] -= 1;
  // Corner offsets ordered by axis index, so that the polygons around the segment's a-edge
  // and around its w-edge compute the same key.
  const int lowAxis = axis < w ? axis : w, highAxis = axis < w ? w : axis;
  const int corner =
      (insideCorner[lowAxis] - faceMin[lowAxis]) + 2 * (insideCorner[highAxis] - faceMin[highAxis]);
  const int faceMinGlobal[3] = {faceMin[0] + t.first[0], faceMin[1] + t.first[1],
                                faceMin[2] + t.first[2]};
  *key = faceSegmentKey(t.globalCells, faceMinGlobal, f.normalAxis, corner);
  const EdgeCrossing ea = tileCrossing(t, axis, n, nodeInside(t, n[0], n[1], n[2]) != 0);
  const EdgeCrossing ew =
      tileCrossing(t, w, wLower, nodeInside(t, wLower[0], wLower[1], wLower[2]) != 0);
  for (int k = 0; k < 3; ++k) {
    double pa = double(t.first[k] + n[k]), pw = double(t.first[k] + wLower[k]);
    if (k == axis) pa = ea.t;
    if (k == w) pw = ew.t;
    pos[k] = 0.5 * (pa + pw);
  }
}

// The polygon around the sign-changing edge along `axis` from window node n (corner 0 of a
// boundary cell, on side in0), counter-clockwise seen from +axis, into *p. Its face-segment
// vertices are also written to faceVertices (when not null) from *faceCount on, which counts
// them.
STRATA_HD void edgePolygon(const TileView& t, const CellCaseTable& table, const int n[3], int axis,
                           bool in0, EdgePolygon* p, CellVertex* faceVertices, int* faceCount) {
  int cells[4][3];
  cellsAroundEdge(n, axis, cells);
  p->count = 0;
  p->firstInserted = -1;
  for (int q = 0; q < 4; ++q) {
    int offset[2];
    cellAroundEdge(q, offset);
    const CellVertex& vtx = vertexOfEdge(t, table, cells[q], 4 * axis + offset[0] + 2 * offset[1]);
    p->keys[p->count] = vtx.key;
    for (int k = 0; k < 3; ++k) p->pos[p->count][k] = vtx.position[k];
    ++p->count;
    const FaceAroundEdge f = faceAroundEdge(axis, q);
    if (!faceSplitsEdge(t, table, cells, axis, q, f)) continue;
    faceSegmentVertex(t, n, axis, in0, f, &p->keys[p->count], p->pos[p->count]);
    if (faceVertices) {
      CellVertex& fv = faceVertices[*faceCount];
      fv.key = p->keys[p->count];
      for (int k = 0; k < 3; ++k) fv.position[k] = p->pos[p->count][k];
      fv.planeDistance = 0.0;
    }
    ++*faceCount;
    if (p->firstInserted < 0) p->firstInserted = p->count;
    ++p->count;
  }
}

// Reverses the polygon's order (when the solid lies after the edge, the surface faces -axis).
STRATA_HD void reverseEdgePolygon(EdgePolygon* p) {
  for (int i = 0, j = p->count - 1; i < j; ++i, --j) {
    const uint64_t tk = p->keys[i];
    p->keys[i] = p->keys[j];
    p->keys[j] = tk;
    for (int k = 0; k < 3; ++k) {
      const double tp = p->pos[i][k];
      p->pos[i][k] = p->pos[j][k];
      p->pos[j][k] = tp;
    }
  }
  if (p->firstInserted >= 0) p->firstInserted = p->count - 1 - p->firstInserted;
}

// The triangles of an edge's polygon, ordered from `order` (the edge's global key * 8), written
// to tris when not null; returns their number. Four vertices: the better-agreeing diagonal
// split. More: a fan from the first inserted face vertex (its spokes are unique to this polygon).
STRATA_HD int edgePolygonTriangles(const EdgePolygon& p, uint64_t order, uint32_t leaf,
                                   uint8_t resolved, CellTriangle* tris) {
  if (p.firstInserted < 0) {
    const double splitA = splitAgreement(p.pos[0], p.pos[1], p.pos[2], p.pos[3]);
    const double splitB = splitAgreement(p.pos[1], p.pos[2], p.pos[3], p.pos[0]);
    const int s = splitA >= splitB ? 0 : 1;
    if (tris) {
      tris[0] = CellTriangle{{p.keys[s], p.keys[s + 1], p.keys[s + 2]}, order, leaf, resolved};
      tris[1] =
          CellTriangle{{p.keys[s], p.keys[s + 2], p.keys[(s + 3) % 4]}, order + 1, leaf, resolved};
    }
    return 2;
  }
  const int f = p.firstInserted, m = p.count;
  int count = 0;
  for (int k = 1; k + 1 < m; ++k) {
    if (tris)
      tris[count] = CellTriangle{{p.keys[f], p.keys[(f + k) % m], p.keys[(f + k + 1) % m]},
                                 order + uint64_t(k - 1),
                                 leaf,
                                 resolved};
    ++count;
  }
  return count;
}

// CellTriangle::resolved of the sign-changing edge along `axis` from window node n (in0: the
// side of n).
STRATA_HD uint8_t edgeResolved(const TileView& t, const int n[3], int axis, bool in0) {
  int m[3] = {n[0], n[1], n[2]};
  m[axis] += 1;
  const int* insideNode = in0 ? n : m;
  const int* outsideNode = in0 ? m : n;
  bool onOuterFace = false;
  for (int k = 0; k < 3; ++k) {
    const int g = outsideNode[k] + t.first[k];
    onOuterFace = onOuterFace || g == 0 || g == t.globalCells[k];
  }
  // The inside node is inside by its majority: unanimous means all three rays. The outside node
  // off the outer faces is outside by its majority: unanimous means none.
  const uint32_t insideAll = nodeUnanimous(t, insideNode[0], insideNode[1], insideNode[2]);
  const uint32_t outsideNone = nodeUnanimous(t, outsideNode[0], outsideNode[1], outsideNode[2]);
  return uint8_t((insideAll ? kInsideResolved : 0) |
                 (onOuterFace || outsideNone ? kOutsideResolved : 0));
}

// What cellPolygons will write for boundary cell number b, from the corner signs alone (no
// vertex or crossing is read, so it may run before the vertices are placed): returns the number
// of triangles, and *faceCount the face-segment vertices. A polygon without a split face is two
// triangles; one with s split faces has 4 + s vertices and is a fan of 2 + s triangles.
STRATA_HD int cellPolygonCounts(const TileView& t, const CellCaseTable& table, int64_t b,
                                int* faceCount) {
  *faceCount = 0;
  int n[3];
  bool in0 = false;
  const int axes = ownedCrossingEdges(t, b, n, &in0);
  int triangleCount = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!((axes >> axis) & 1)) continue;
    int cells[4][3];
    cellsAroundEdge(n, axis, cells);
    int splits = 0;
    for (int q = 0; q < 4; ++q)
      splits += faceSplitsEdge(t, table, cells, axis, q, faceAroundEdge(axis, q)) ? 1 : 0;
    triangleCount += 2 + splits;
    *faceCount += splits;
  }
  return triangleCount;
}

// The polygons of the sign-changing edges owned by boundary cell number b (those running from
// its corner 0), joining the vertices of the four cells around each edge. Two neighbouring
// cells whose components both pass twice through their shared, ambiguous face would be joined
// by the same dual edge four times; there the dual edge is split at a vertex per face segment
// (between the segment's two crossings), so every output edge has exactly two triangles.
// Writes up to kMaxCellTriangles triangles and kMaxCellFaceVertices face vertices (when tris and
// faceVertices are not null); returns the number of triangles (and *faceCount the face
// vertices); adds the synthesised crossings of the edges to *synthesized.
STRATA_HD int cellPolygons(const TileView& t, const CellCaseTable& table, int64_t b,
                           CellTriangle* tris, CellVertex* faceVertices, int* faceCount,
                           int* synthesized) {
  *faceCount = 0;
  int n[3];
  bool in0 = false;
  const int axes = ownedCrossingEdges(t, b, n, &in0);
  int triangleCount = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!((axes >> axis) & 1)) continue;
    EdgePolygon polygon;
    edgePolygon(t, table, n, axis, in0, &polygon, faceVertices, faceCount);
    if (!in0) reverseEdgePolygon(&polygon);
    uint32_t leaf;
    if (t.cornerCrossings) {  // the vertex step's crossing of this edge (the same lookup)
      const uint32_t word = t.cornerCrossings[b * 3 + axis];
      leaf = word & 0x7fffffffu;
      *synthesized += int(word >> 31);
    } else {
      const EdgeCrossing x = tileCrossing(t, axis, n, in0);
      leaf = x.leaf;
      *synthesized += x.synthesized ? 1 : 0;
    }
    const int g[3] = {n[0] + t.first[0], n[1] + t.first[1], n[2] + t.first[2]};
    const uint64_t order = globalEdgeKey(t.globalCells, axis, g) * 8;
    triangleCount += edgePolygonTriangles(polygon, order, leaf, edgeResolved(t, n, axis, in0),
                                          tris ? tris + triangleCount : nullptr);
  }
  return triangleCount;
}

}  // namespace strata
