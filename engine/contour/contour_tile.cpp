#include "engine/contour/contour_tile.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>

#include "engine/contour/contour_math.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr CellCaseTable kCellCases = buildCellCaseTable();

struct Crossing {
  double t;  // global grid units along the edge's axis
  float normal[3];
  uint32_t leaf;
  bool synthesized;
};

// Read-only view of a tile during contouring.
struct Tile {
  const Ldi& ldi;
  glm::ivec3 first;                // window's first node (global)
  glm::ivec3 cells;                // window cells
  glm::ivec3 globalCells;          // whole grid
  std::vector<uint8_t> inside;     // per window node: 1 inside, 0 outside
  std::vector<uint8_t> masks;      // per window cell: bit c set when corner c is inside
  std::vector<uint32_t> boundary;  // window cells with mixed corners, increasing index

  int64_t node(int i, int j, int k) const {
    return int64_t(i) + int64_t(cells.x + 1) * (int64_t(j) + int64_t(cells.y + 1) * k);
  }
  int64_t node(const glm::ivec3& n) const { return node(n.x, n.y, n.z); }
  int64_t cell(const glm::ivec3& c) const {
    return int64_t(c.x) + int64_t(cells.x) * (int64_t(c.y) + int64_t(cells.y) * c.z);
  }
  glm::ivec3 cellCoords(uint32_t index) const {
    const int64_t i = index;
    return glm::ivec3(int(i % cells.x), int((i / cells.x) % cells.y),
                      int(i / (int64_t(cells.x) * cells.y)));
  }
  uint64_t globalCell(const glm::ivec3& local) const {
    glm::ivec3 c = local + first;
    return uint64_t(c.x) +
           uint64_t(globalCells.x) * (uint64_t(c.y) + uint64_t(globalCells.y) * uint64_t(c.z));
  }

  // The crossing on the edge along `axis` from window node n (whose side is `lowerInside`).
  Crossing crossing(int axis, const glm::ivec3& n, bool lowerInside) const {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const AxisLdi& a = ldi.axes[axis];
    const int64_t ray = int64_t(n[u]) + int64_t(n[v]) * (cells[u] + 1);
    const float lo = float(first[axis] + n[axis]), hi = lo + 1.0f;
    const Surfel* begin = a.surfels.data() + a.offsets[size_t(ray)];
    const Surfel* end = a.surfels.data() + a.offsets[size_t(ray) + 1];
    const Surfel* s =
        std::upper_bound(begin, end, lo, [](float d, const Surfel& x) { return d < x.depth; });
    const bool wantEnter = !lowerInside;  // moving along +axis from outside into the solid
    Crossing c{};
    for (; s != end && s->depth <= hi; ++s) {
      if (surfelEnters(s->tag) == wantEnter) {
        c.t = s->depth;
        decodeNormal(s->normal, c.normal);
        c.leaf = surfelLeaf(s->tag);
        return c;
      }
    }
    // The ray's own parity disagreed with the decided signs (a tangent ray dropped or added a
    // hit): synthesise a crossing at the middle, facing out of the solid along the axis, with
    // the leaf of the ray's nearest surfel.
    c.t = double(lo) + 0.5;
    c.normal[0] = c.normal[1] = c.normal[2] = 0.0f;
    c.normal[axis] = wantEnter ? -1.0f : 1.0f;
    c.synthesized = true;
    c.leaf = 0;
    if (begin != end) {
      const Surfel* nearest = std::min_element(begin, end, [&](const Surfel& x, const Surfel& y) {
        return std::fabs(x.depth - lo) < std::fabs(y.depth - lo);
      });
      c.leaf = surfelLeaf(nearest->tag);
    }
    return c;
  }

  uint8_t cellMask(const glm::ivec3& c) const { return masks[size_t(cell(c))]; }
};

// Majority of the three rays through each window node; nodes on the grid's outer faces are
// outside. Returns the number of nodes whose rays disagreed.
//
// Every ray walks its surfels once while the loops run over nodes in memory order (x fastest),
// keeping one cursor per ray of the current row or slab, so all writes are sequential.
uint64_t decideNodeSigns(Tile& tile, Progress* progress) {
  const glm::ivec3 nodes = tile.cells + 1;
  const int64_t plane = int64_t(nodes.x) * nodes.y;
  std::vector<uint8_t> votes(size_t(plane * nodes.z), 0);
  struct Cursor {
    uint32_t next, end;
    bool in;
  };
  auto startCursor = [&](const AxisLdi& a, int64_t ray) {
    return Cursor{a.offsets[size_t(ray)], a.offsets[size_t(ray) + 1], false};
  };
  // A node counts the surfels at or before it: it sits just after its own depth, as the tie
  // rule's perturbation puts the other axes' rays just after theirs.
  auto advance = [](const AxisLdi& a, Cursor& c, float depth) {
    while (c.next < c.end && a.surfels[c.next].depth <= depth) {
      c.in = !c.in;
      ++c.next;
    }
    return c.in;
  };
  const AxisLdi& ax = tile.ldi.axes[0];  // rays indexed by (y, z)
  const AxisLdi& ay = tile.ldi.axes[1];  // rays indexed by (z, x)
  const AxisLdi& az = tile.ldi.axes[2];  // rays indexed by (x, y)
  // x rays and y rays: one z slab at a time.
  parallelFor(0, nodes.z, 1, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    std::vector<Cursor> yCursors(size_t(nodes.x));
    for (int k = int(b); k < int(e); ++k) {
      for (int i = 0; i < nodes.x; ++i)
        yCursors[size_t(i)] = startCursor(ay, int64_t(k) + int64_t(i) * nodes.z);
      for (int j = 0; j < nodes.y; ++j) {
        uint8_t* row = votes.data() + plane * k + int64_t(nodes.x) * j;
        Cursor xc = startCursor(ax, int64_t(j) + int64_t(k) * nodes.y);
        const float yDepth = float(tile.first.y + j);
        for (int i = 0; i < nodes.x; ++i) {
          row[i] = uint8_t(advance(ax, xc, float(tile.first.x + i)) ? 1 : 0) +
                   uint8_t(advance(ay, yCursors[size_t(i)], yDepth) ? 1 : 0);
        }
      }
    }
  });
  // z rays: one y row at a time, all its x cursors marching up through the slabs.
  parallelFor(0, nodes.y, 1, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    std::vector<Cursor> zCursors(size_t(nodes.x));
    for (int j = int(b); j < int(e); ++j) {
      for (int i = 0; i < nodes.x; ++i)
        zCursors[size_t(i)] = startCursor(az, int64_t(i) + int64_t(j) * nodes.x);
      for (int k = 0; k < nodes.z; ++k) {
        uint8_t* row = votes.data() + plane * k + int64_t(nodes.x) * j;
        const float zDepth = float(tile.first.z + k);
        for (int i = 0; i < nodes.x; ++i)
          row[i] = uint8_t(row[i] + (advance(az, zCursors[size_t(i)], zDepth) ? 1 : 0));
      }
    }
  });
  std::atomic<uint64_t> disagreements{0};
  tile.inside.assign(votes.size(), 0);
  parallelFor(0, nodes.z, 1, [&](int64_t b, int64_t e) {
    uint64_t local = 0;
    for (int k = int(b); k < int(e); ++k) {
      const int gz = tile.first.z + k;
      const bool zFace = gz == 0 || gz == tile.globalCells.z;
      for (int j = 0; j < nodes.y; ++j) {
        const int gy = tile.first.y + j;
        const bool yFace = zFace || gy == 0 || gy == tile.globalCells.y;
        const size_t at = size_t(plane * k + int64_t(nodes.x) * j);
        for (int i = 0; i < nodes.x; ++i) {
          const int gx = tile.first.x + i;
          const uint8_t vote = votes[at + size_t(i)];
          local += (vote == 1 || vote == 2) ? 1 : 0;
          const bool face = yFace || gx == 0 || gx == tile.globalCells.x;
          tile.inside[at + size_t(i)] = (!face && vote >= 2) ? 1 : 0;
        }
      }
    }
    disagreements += local;
  });
  return disagreements.load();
}

// The corner-inside mask of every window cell, and the list of boundary cells (mixed corners)
// in increasing cell index.
void computeCellMasks(Tile& tile, Progress* progress) {
  const glm::ivec3 cells = tile.cells;
  tile.masks.assign(size_t(int64_t(cells.x) * cells.y * cells.z), 0);
  const int64_t dx = 1, dy = cells.x + 1, dz = int64_t(cells.x + 1) * (cells.y + 1);
  std::vector<std::vector<uint32_t>> slabs(size_t(cells.z));
  parallelFor(0, cells.z, 1, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    for (int k = int(b); k < int(e); ++k)
      for (int j = 0; j < cells.y; ++j) {
        const uint8_t* n = tile.inside.data() + tile.node(0, j, k);
        const int64_t rowStart = tile.cell(glm::ivec3(0, j, k));
        uint8_t* m = tile.masks.data() + rowStart;
        for (int i = 0; i < cells.x; ++i, ++n) {
          const uint8_t mask =
              uint8_t(n[0] | (n[dx] << 1) | (n[dy] << 2) | (n[dx + dy] << 3) | (n[dz] << 4) |
                      (n[dx + dz] << 5) | (n[dy + dz] << 6) | (n[dx + dy + dz] << 7));
          m[i] = mask;
          if (mask != 0 && mask != 255) slabs[size_t(k)].push_back(uint32_t(rowStart + i));
        }
      }
  });
  tile.boundary.clear();
  for (const auto& slab : slabs)
    tile.boundary.insert(tile.boundary.end(), slab.begin(), slab.end());
}

// Places one QEF vertex per surface component of every boundary cell. vertexStart[b] is the
// index of the first vertex of boundary cell b (tile.boundary[b]); vertexStart has one more
// entry than there are boundary cells.
void placeVertices(const Tile& tile, TileContour* out, std::vector<uint32_t>* vertexStart,
                   Progress* progress) {
  const size_t count = tile.boundary.size();
  vertexStart->assign(count + 1, 0);
  uint32_t total = 0;
  for (size_t b = 0; b < count; ++b) {
    (*vertexStart)[b] = total;
    total += uint32_t(kCellCases.cases[tile.masks[tile.boundary[b]]].components);
  }
  (*vertexStart)[count] = total;
  out->vertices.resize(total);
  parallelFor(0, int64_t(count), 2048, [&](int64_t first, int64_t last) {
    if (progress) progress->check();
    for (int64_t b = first; b < last; ++b) {
      const glm::ivec3 c = tile.cellCoords(tile.boundary[size_t(b)]);
      const uint8_t mask = tile.masks[tile.boundary[size_t(b)]];
      const CellCase& cc = kCellCases.cases[mask];
      double points[kMaxCellComponents][12][3];
      float normals[kMaxCellComponents][12][3];
      int n[kMaxCellComponents] = {0, 0, 0, 0};
      for (int edge = 0; edge < 12; ++edge) {
        const int comp = cc.edgeComponent[edge];
        if (comp < 0) continue;
        int c0, c1;
        edgeCorners(edge, &c0, &c1);
        const int axis = edge >> 2;
        const glm::ivec3 node = c + glm::ivec3(c0 & 1, (c0 >> 1) & 1, (c0 >> 2) & 1);
        const Crossing x = tile.crossing(axis, node, (mask >> c0) & 1);
        double* p = points[comp][n[comp]];
        for (int d = 0; d < 3; ++d) p[d] = double(tile.first[d] + node[d]);
        p[axis] = x.t;
        for (int d = 0; d < 3; ++d) normals[comp][n[comp]][d] = x.normal[d];
        ++n[comp];
      }
      const glm::ivec3 g = tile.first + c;
      const int64_t cellGlobal[3] = {g.x, g.y, g.z};
      double x[kMaxCellComponents][3];
      double mass[kMaxCellComponents][3];
      for (int comp = 0; comp < cc.components; ++comp) {
        Qef q = buildQef(points[comp], normals[comp], n[comp]);
        for (int k = 0; k < 3; ++k) x[comp][k] = mass[comp][k] = q.mass[k];
        solveQef(q, cellGlobal, x[comp]);
      }
      separateCoincidentVertices(x, mass, cc.components);
      for (int comp = 0; comp < cc.components; ++comp) {
        ContourVertex& vtx = out->vertices[(*vertexStart)[size_t(b)] + uint32_t(comp)];
        vtx.key = tile.globalCell(c) * 4 + uint64_t(comp);
        vtx.position = glm::dvec3(x[comp][0], x[comp][1], x[comp][2]);
        vtx.planeDistance = qefPlaneDistance(points[comp], normals[comp], n[comp], x[comp]);
      }
    }
  });
}

double splitAgreement(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      const glm::dvec3& d) {
  // Triangles (a, b, c) and (a, c, d): the cosine between their normals; -2 if one is degenerate.
  glm::dvec3 n1 = glm::cross(b - a, c - a), n2 = glm::cross(c - a, d - a);
  double l1 = glm::length(n1), l2 = glm::length(n2);
  if (!(l1 > 0.0) || !(l2 > 0.0)) return -2.0;
  return glm::dot(n1, n2) / (l1 * l2);
}

// Key of the vertex inserted for the face segment around the inside corner `corner` (0..3: its
// offset along the face's lower in-plane axis + 2 * along the higher one) of the face whose lowest node is `faceMin` (global) and whose normal is
// `normalAxis`. The top bit keeps these keys apart from cell vertex keys.
uint64_t faceVertexKey(const glm::ivec3& globalCells, const glm::ivec3& faceMin, int normalAxis,
                       int corner) {
  const uint64_t nx = uint64_t(globalCells.x) + 1, ny = uint64_t(globalCells.y) + 1;
  const uint64_t node = (uint64_t(faceMin.z) * ny + uint64_t(faceMin.y)) * nx + uint64_t(faceMin.x);
  return (uint64_t(1) << 63) | ((node * 3 + uint64_t(normalAxis)) * 4 + uint64_t(corner));
}

// Cell-local index of the edge along `axis` whose corner-0 bits on the other axes are given.
int localEdge(int axis, const int bits[3]) {
  return 4 * axis + bits[(axis + 1) % 3] + 2 * bits[(axis + 2) % 3];
}

// One polygon per sign-changing edge owned by the tile: the vertices of the components of the
// four cells around the edge. Such an edge runs from corner 0 of a boundary cell (the cell whose
// lowest node is the edge's lower node), so owned edges are found from the boundary cells alone.
//
// Two neighbouring cells whose components both pass twice through their shared, ambiguous face
// (all four face edges crossing, both face segments in one component on each side) would be
// joined by the same dual edge four times. There the dual edge is split at a vertex per face
// segment (between the segment's two crossings), so every edge of the output has exactly two
// triangles.
void emitPolygons(const Tile& tile, const glm::ivec3& begin, const glm::ivec3& end,
                  const std::vector<uint32_t>& vertexStart, TileContour* out, Progress* progress) {
  const glm::ivec3 lo = begin - tile.first, hi = end - tile.first;
  const size_t count = tile.boundary.size();
  constexpr int64_t kGrain = 4096;
  const size_t chunkCount = size_t((int64_t(count) + kGrain - 1) / kGrain);
  std::vector<std::vector<ContourTriangle>> chunks(chunkCount);
  std::vector<std::vector<ContourVertex>> faceVertices(chunkCount);
  std::atomic<uint64_t> synthesized{0};
  auto componentOf = [&](const glm::ivec3& c, int edge) {
    return int(kCellCases.cases[tile.masks[size_t(tile.cell(c))]].edgeComponent[edge]);
  };
  auto vertexOf = [&](const glm::ivec3& c, int edge) -> const ContourVertex& {
    const uint32_t index = uint32_t(tile.cell(c));
    const size_t b = size_t(std::lower_bound(tile.boundary.begin(), tile.boundary.end(), index) -
                            tile.boundary.begin());
    return out->vertices[vertexStart[b] + uint32_t(componentOf(c, edge))];
  };
  auto crossingPoint = [&](int axis, const glm::ivec3& node) {
    const Crossing x = tile.crossing(axis, node, tile.inside[size_t(tile.node(node))]);
    glm::dvec3 p = glm::dvec3(tile.first + node);
    p[axis] = x.t;
    return p;
  };
  parallelFor(0, int64_t(count), kGrain, [&](int64_t first, int64_t last) {
    if (progress) progress->check();
    std::vector<ContourTriangle>& tris = chunks[size_t(first / kGrain)];
    std::vector<ContourVertex>& extra = faceVertices[size_t(first / kGrain)];
    uint64_t localSynthesized = 0;
    for (int64_t b = first; b < last; ++b) {
      const uint32_t index = tile.boundary[size_t(b)];
      const glm::ivec3 n = tile.cellCoords(index);  // the cell's corner 0: the edges' lower node
      if (n.x < lo.x || n.y < lo.y || n.z < lo.z || n.x >= hi.x || n.y >= hi.y || n.z >= hi.z)
        continue;
      const uint8_t mask = tile.masks[index];
      const bool in0 = mask & 1;
      for (int axis = 0; axis < 3; ++axis) {
        if (bool((mask >> (1 << axis)) & 1) == in0) continue;  // corner 1, 2 or 4 vs corner 0
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        // The four cells around the edge, counter-clockwise in (u, v) seen from +axis.
        const int around[4][2] = {{1, 1}, {0, 1}, {0, 0}, {1, 0}};
        glm::ivec3 cells[4];
        for (int q = 0; q < 4; ++q) {
          cells[q] = n;
          cells[q][u] -= around[q][0];
          cells[q][v] -= around[q][1];
          // >= 0: the grid's outer nodes are outside, so no sign change touches them.
        }
        uint64_t keys[8];
        glm::dvec3 pos[8];
        int m = 0, firstInserted = -1;
        for (int q = 0; q < 4; ++q) {
          const ContourVertex& vtx = vertexOf(cells[q], 4 * axis + around[q][0] + 2 * around[q][1]);
          keys[m] = vtx.key;
          pos[m++] = vtx.position;
          // The face shared by cells q and q + 1, its normal along u or v, its other in-plane
          // axis w; bits of this edge (e) and of the face's other a-edge (eOpp) in both cells.
          const int q1 = (q + 1) % 4;
          const bool normalU = around[q][0] != around[q1][0];
          const int normalAxis = normalU ? u : v, w = normalU ? v : u;
          int bitsQ[3], bitsQ1[3];
          bitsQ[axis] = bitsQ1[axis] = 0;
          bitsQ[u] = around[q][0];
          bitsQ[v] = around[q][1];
          bitsQ1[u] = around[q1][0];
          bitsQ1[v] = around[q1][1];
          const int eQ = localEdge(axis, bitsQ), eQ1 = localEdge(axis, bitsQ1);
          const int wBit = bitsQ[w];  // where e lies across the face (same in both cells)
          bitsQ[w] = bitsQ1[w] = 1 - wBit;
          const int oppQ = localEdge(axis, bitsQ), oppQ1 = localEdge(axis, bitsQ1);
          const int cq = componentOf(cells[q], eQ), cq1 = componentOf(cells[q1], eQ1);
          if (componentOf(cells[q], oppQ) != cq || componentOf(cells[q1], oppQ1) != cq1) continue;
          // Both a-edges in one component on each side: split only if the face is ambiguous
          // (its two w-edges cross too; otherwise e and eOpp form the face's single segment).
          int wBits[3];
          wBits[normalAxis] = normalU ? around[q][0] : around[q][1];
          wBits[w] = 0;
          wBits[axis] = 0;
          const int w0 = localEdge(w, wBits);
          wBits[axis] = 1;
          const int w1 = localEdge(w, wBits);
          if (componentOf(cells[q], w0) < 0 || componentOf(cells[q], w1) < 0) continue;
          // The segment around e's inside corner: e and the w-edge at that corner.
          glm::ivec3 insideCorner = n;
          if (!in0) insideCorner[axis] += 1;
          glm::ivec3 faceMin = n;
          if (wBit == 1) faceMin[w] -= 1;
          glm::ivec3 wLower = insideCorner;
          if (wBit == 1) wLower[w] -= 1;
          // The inside corner's offsets in the face, ordered by axis index, so that the quads
          // around the segment's a-edge and around its w-edge compute the same key.
          const glm::ivec3 offset = insideCorner - faceMin;
          const int corner = offset[std::min(axis, w)] + 2 * offset[std::max(axis, w)];
          keys[m] = faceVertexKey(tile.globalCells, tile.first + faceMin, normalAxis, corner);
          pos[m] = 0.5 * (crossingPoint(axis, n) + crossingPoint(w, wLower));
          extra.push_back(ContourVertex{keys[m], pos[m], 0.0});
          if (firstInserted < 0) firstInserted = m;
          ++m;
        }
        if (!in0) {  // the solid lies after the edge: the surface faces -axis
          std::reverse(keys, keys + m);
          std::reverse(pos, pos + m);
          if (firstInserted >= 0) firstInserted = m - 1 - firstInserted;
        }
        const Crossing x = tile.crossing(axis, n, in0);
        localSynthesized += x.synthesized ? 1 : 0;
        const uint64_t order = edgeKey(tile.globalCells, axis, tile.first + n) * 8;
        if (firstInserted < 0) {
          const double splitA = splitAgreement(pos[0], pos[1], pos[2], pos[3]);
          const double splitB = splitAgreement(pos[1], pos[2], pos[3], pos[0]);
          const int s = splitA >= splitB ? 0 : 1;
          tris.push_back({{keys[s], keys[s + 1], keys[s + 2]}, order, x.leaf});
          tris.push_back({{keys[s], keys[s + 2], keys[(s + 3) % 4]}, order + 1, x.leaf});
        } else {
          // A fan from an inserted face vertex: its spokes are unique to this polygon.
          for (int t = 1; t + 1 < m; ++t) {
            tris.push_back({{keys[firstInserted], keys[(firstInserted + t) % m],
                             keys[(firstInserted + t + 1) % m]},
                            order + uint64_t(t - 1),
                            x.leaf});
          }
        }
      }
    }
    synthesized += localSynthesized;
  });
  size_t total = 0;
  for (const auto& c : chunks) total += c.size();
  out->triangles.reserve(total);
  for (auto& c : chunks) out->triangles.insert(out->triangles.end(), c.begin(), c.end());
  for (auto& f : faceVertices) out->vertices.insert(out->vertices.end(), f.begin(), f.end());
  out->synthesizedCrossings = synthesized.load();
}

}  // namespace

TileWindow tileWindow(const glm::ivec3& begin, const glm::ivec3& end, const glm::ivec3& cells) {
  TileWindow w;
  w.first = glm::max(begin - 1, glm::ivec3(0));
  glm::ivec3 last = glm::min(end, cells);
  w.cells = last - w.first;
  return w;
}

uint64_t edgeKey(const glm::ivec3& globalCells, int axis, const glm::ivec3& node) {
  const uint64_t nx = uint64_t(globalCells.x) + 1, ny = uint64_t(globalCells.y) + 1;
  return ((uint64_t(node.z) * ny + uint64_t(node.y)) * nx + uint64_t(node.x)) * 3 + uint64_t(axis);
}

TileContour contourTile(const Ldi& ldi, const glm::ivec3& globalCells, const glm::ivec3& begin,
                        const glm::ivec3& end, Progress* progress) {
  Tile tile{ldi, ldi.grid.first, ldi.grid.cells, globalCells, {}, {}, {}};
  TileContour out;
  out.signDisagreements = decideNodeSigns(tile, progress);
  computeCellMasks(tile, progress);
  std::vector<uint32_t> vertexStart;
  placeVertices(tile, &out, &vertexStart, progress);
  emitPolygons(tile, begin, end, vertexStart, &out, progress);
  return out;
}

}  // namespace strata
