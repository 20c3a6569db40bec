// checkMesh measures topology (after welding identical positions) and geometry; prepareMesh
// makes the repairs that never move a vertex: weld, drop degenerate triangles, orient shells
// consistently and outward (cavities inward). Edges come from sorting half-edges, so both are
// O(n log n); the shell nesting test visits, through a box tree, only the closed shells whose
// bounds hold a shell's probe point (O(n log n) unless shells pile up on one another).
#include "engine/geometry/mesh_check.h"

#include "engine/geometry/box_tree.h"
#include "engine/util/error.h"
#include "engine/util/hash.h"
#include "engine/util/parallel_for.h"
#include "engine/util/union_find.h"

#include <atomic>
#include <tuple>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>

namespace strata {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

bool isFinite(const glm::dvec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

struct PositionKey {
  uint64_t x, y, z;
  bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = k.x * 0x9e3779b97f4a7c15ull;
    h ^= (h >> 29) ^ (k.y * 0xbf58476d1ce4e5b9ull);
    h ^= (h >> 31) ^ (k.z * 0x94d049bb133111ebull);
    return static_cast<size_t>(h ^ (h >> 32));
  }
};

// canonical[i]: the first vertex with exactly the position of vertex i (i itself if none).
// A hash join partitioned by the hash's top bits, so that no step waits on memory at random:
// every finite vertex's (index, hash) goes to its partition (chunks of vertices scattered in
// order, so a partition lists its vertices by increasing index), then each partition, a few
// thousand vertices, is welded in an open-addressing table small enough for the cache, compared
// through the positions only where the hashes agree. Where one hash table over all vertices
// missed the cache twice a vertex, this weld took half the time of a check. In parallel over
// chunks and partitions; the result does not depend on the thread count.
std::vector<uint32_t> canonicalVertices(const std::vector<glm::dvec3>& positions) {
  const size_t n = positions.size();
  std::vector<uint32_t> canonical(n);
  const auto hashOf = [&](size_t v) {
    const glm::dvec3& p = positions[v];
    return avalanche64(uint64_t(PositionKeyHash()(
        PositionKey{coordinateBits(p.x), coordinateBits(p.y), coordinateBits(p.z)})));
  };
  int partitionBits = 0;
  while (partitionBits < 16 && (n >> partitionBits) > 4096) ++partitionBits;
  const size_t partitions = size_t(1) << partitionBits;
  const auto partitionOf = [&](uint64_t h) {
    return partitionBits == 0 ? size_t(0) : size_t(h >> (64 - partitionBits));
  };
  const size_t chunks =
      std::max<size_t>(1, std::min<size_t>(size_t(workerCount()) * 4, (n + 65535) / 65536));
  const size_t chunkSize = (n + chunks - 1) / chunks;
  // counts[chunk * partitions + p]: the chunk's vertices in partition p, then where they go.
  std::vector<uint32_t> counts(chunks * partitions, 0);
  parallelFor(0, int64_t(chunks), 1, [&](int64_t b, int64_t e) {
    for (int64_t chunk = b; chunk < e; ++chunk) {
      uint32_t* count = counts.data() + size_t(chunk) * partitions;
      const size_t end = std::min(n, size_t(chunk + 1) * chunkSize);
      for (size_t v = size_t(chunk) * chunkSize; v < end; ++v) {
        canonical[v] = uint32_t(v);
        if (isFinite(positions[v])) ++count[partitionOf(hashOf(v))];
      }
    }
  });
  std::vector<uint32_t> partitionStart(partitions + 1, 0);
  {
    uint32_t total = 0;
    for (size_t p = 0; p < partitions; ++p) {
      partitionStart[p] = total;
      for (size_t chunk = 0; chunk < chunks; ++chunk) {
        const uint32_t c = counts[chunk * partitions + p];
        counts[chunk * partitions + p] = total;
        total += c;
      }
    }
    partitionStart[partitions] = total;
  }
  struct Entry {
    uint32_t vertex;
    uint32_t hash;  // the hash's low bits
  };
  std::vector<Entry> entries(partitionStart[partitions]);
  parallelFor(0, int64_t(chunks), 1, [&](int64_t b, int64_t e) {
    for (int64_t chunk = b; chunk < e; ++chunk) {
      uint32_t* cursor = counts.data() + size_t(chunk) * partitions;
      const size_t end = std::min(n, size_t(chunk + 1) * chunkSize);
      for (size_t v = size_t(chunk) * chunkSize; v < end; ++v) {
        if (!isFinite(positions[v])) continue;
        const uint64_t h = hashOf(v);
        entries[cursor[partitionOf(h)]++] = {uint32_t(v), uint32_t(h)};
      }
    }
  });
  parallelFor(0, int64_t(partitions), 1, [&](int64_t b, int64_t e) {
    std::vector<uint32_t> table;  // entry numbers within the partition, + 1 (0: empty)
    for (int64_t p = b; p < e; ++p) {
      const Entry* first = entries.data() + partitionStart[size_t(p)];
      const size_t count = partitionStart[size_t(p) + 1] - partitionStart[size_t(p)];
      size_t capacity = 16;
      while (capacity < 2 * count) capacity *= 2;
      table.assign(capacity, 0);
      const size_t mask = capacity - 1;
      for (size_t i = 0; i < count; ++i) {
        const Entry& entry = first[i];
        for (size_t at = entry.hash & mask;; at = (at + 1) & mask) {
          if (table[at] == 0) {
            table[at] = uint32_t(i + 1);
            break;
          }
          const Entry& there = first[table[at] - 1];
          if (there.hash == entry.hash) {
            const glm::dvec3& a = positions[there.vertex];
            const glm::dvec3& c = positions[entry.vertex];
            if (coordinateBits(a.x) == coordinateBits(c.x) &&
                coordinateBits(a.y) == coordinateBits(c.y) &&
                coordinateBits(a.z) == coordinateBits(c.z)) {
              canonical[entry.vertex] = there.vertex;  // the first: entries are by index
              break;
            }
          }
        }
      }
    }
  });
  return canonical;
}

// One directed edge of a triangle, in the bucket of its smaller endpoint `lo` (which is left
// implicit): 8 bytes, where the half-edges of a large mesh are its largest array.
struct HalfEdge {
  uint32_t hiForward;       // hi << 1 | forward (the triangle traverses it lo -> hi)
  uint32_t triangleCorner;  // triangle * 3 + corner: the edge runs from corner to corner + 1
  uint32_t hi() const { return hiForward >> 1; }
  bool forward() const { return (hiForward & 1u) != 0; }
  uint32_t triangle() const { return triangleCorner / 3; }
  uint32_t corner() const { return triangleCorner % 3; }
  // The order within a bucket: (hi, triangle, corner).
  bool before(const HalfEdge& o) const {
    return hi() != o.hi() ? hi() < o.hi() : triangleCorner < o.triangleCorner;
  }
};

// Half-edges of all triangles (through `canonical` when given), sorted by (lo, hi) so that the
// half-edges of one undirected edge are adjacent, in increasing triangle order within an edge;
// bucketEnd[v] is the end of the half-edges whose lo is v (bucket v starts at bucketEnd[v - 1],
// or 0). Edges whose ends coincide are left out. A counting sort on lo (in parallel: counts
// and the scatter by atomic increments) and a sort of each bucket on (hi, triangle, corner): an
// insertion sort of a vertex's few edges, O(n) in all, where a comparison sort of the 3n
// half-edges took most of a check's time; a comparison sort of a bucket of more than 32 (a
// cone's apex, a triangle repeated), n log n where the insertion sort took n^2. The result does not
// depend on the thread count. Throws strata::Error for a mesh whose indices do not fit (2^31
// vertices, 1.4 billion triangles).
struct SortedHalfEdges {
  std::vector<HalfEdge> edges;
  std::vector<uint32_t> bucketEnd;  // one per vertex
  size_t bucketBegin(size_t v) const { return v == 0 ? 0 : bucketEnd[v - 1]; }
};

SortedHalfEdges sortedHalfEdges(const TriangleMesh& mesh, const std::vector<uint32_t>* canonical) {
  const auto& triangles = mesh.triangles;
  const size_t vertices = mesh.positions.size();
  if (vertices >= (size_t(1) << 31) || triangles.size() > size_t(UINT32_MAX) / 3)
    throw Error("the mesh is too large to check (" + std::to_string(vertices) + " vertices, " +
                std::to_string(triangles.size()) +
                " triangles; at most 2^31 vertices and 1.4 billion triangles)");
  auto ends = [&](size_t t, int k, uint32_t& a, uint32_t& b) {
    a = triangles[t][size_t(k)];
    b = triangles[t][size_t((k + 1) % 3)];
    if (canonical) {
      a = (*canonical)[a];
      b = (*canonical)[b];
    }
  };
  std::vector<std::atomic<uint32_t>> cursor(vertices);
  parallelFor(0, int64_t(vertices), 1 << 18, [&](int64_t b, int64_t e) {
    for (int64_t v = b; v < e; ++v) cursor[size_t(v)].store(0, std::memory_order_relaxed);
  });
  parallelFor(0, int64_t(triangles.size()), 65536, [&](int64_t b, int64_t e) {
    for (int64_t t = b; t < e; ++t)
      for (int k = 0; k < 3; ++k) {
        uint32_t x, y;
        ends(size_t(t), k, x, y);
        if (x != y) cursor[std::min(x, y)].fetch_add(1, std::memory_order_relaxed);
      }
  });
  SortedHalfEdges sorted;
  sorted.bucketEnd.resize(vertices);
  uint32_t total = 0;
  for (size_t v = 0; v < vertices; ++v) {
    const uint32_t count = cursor[v].load(std::memory_order_relaxed);
    cursor[v].store(total, std::memory_order_relaxed);
    total += count;
    sorted.bucketEnd[v] = total;
  }
  sorted.edges.resize(total);
  parallelFor(0, int64_t(triangles.size()), 65536, [&](int64_t b, int64_t e) {
    for (int64_t t = b; t < e; ++t)
      for (int k = 0; k < 3; ++k) {
        uint32_t x, y;
        ends(size_t(t), k, x, y);
        if (x == y) continue;
        sorted.edges[cursor[std::min(x, y)].fetch_add(1, std::memory_order_relaxed)] = {
            std::max(x, y) << 1 | uint32_t(x < y), uint32_t(t) * 3 + uint32_t(k)};
      }
  });
  parallelFor(0, int64_t(vertices), 4096, [&](int64_t b, int64_t e) {
    for (int64_t v = b; v < e; ++v) {
      HalfEdge* first = sorted.edges.data() + sorted.bucketBegin(size_t(v));
      HalfEdge* last = sorted.edges.data() + sorted.bucketEnd[size_t(v)];
      // `before` is a total order, so both sorts give the same: a vertex of many triangles (a
      // cone's apex of 640,000, or one triangle repeated) sorted in n log n, not n^2.
      if (last - first > 32) {
        std::sort(first, last, [](const HalfEdge& a, const HalfEdge& b) { return a.before(b); });
        continue;
      }
      for (HalfEdge* i = first + 1; i < last; ++i) {  // insertion sort: a handful of edges
        const HalfEdge h = *i;
        HalfEdge* j = i;
        for (; j > first && h.before(j[-1]); --j) *j = j[-1];
        *j = h;
      }
    }
  });
  return sorted;
}

// Calls visit(begin, end) for each run of half-edges sharing one undirected edge, over the
// buckets of the vertices [firstVertex, endVertex).
template <typename Visit>
void forEachEdge(const SortedHalfEdges& sorted, size_t firstVertex, size_t endVertex, Visit visit) {
  const std::vector<HalfEdge>& edges = sorted.edges;
  for (size_t v = firstVertex; v < endVertex; ++v) {
    const size_t end = sorted.bucketEnd[v];
    size_t i = sorted.bucketBegin(v);
    while (i < end) {
      size_t j = i + 1;
      while (j < end && edges[j].hi() == edges[i].hi()) ++j;
      visit(i, j);
      i = j;
    }
  }
}

// An axis-aligned box grown point by point, empty (lo > hi) until the first. NaN coordinates
// are left out: glm::min and glm::max keep their first argument then.
struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

  void include(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  double largestSide() const {
    const glm::dvec3 side = hi - lo;  // -inf on an axis without coordinates
    return std::max({side.x, side.y, side.z, 0.0});
  }
};

// The box around the vertices the triangles use: a stray vertex far away, which prepareMesh
// drops, must not make the frame below too coarse for the mesh.
Box usedBox(const TriangleMesh& mesh) {
  Box box;
  const glm::dvec3* positions = mesh.positions.data();  // a local: box stays in registers
  for (const auto& t : mesh.triangles) {
    for (uint32_t v : t) box.include(positions[v]);
  }
  return box;
}

// Positions relative to the centre of the box around the mesh's triangles, scaled by a power
// of two that brings its largest side into [1, 2): products of three such coordinates
// (volumes, the cross products of ray tests) neither overflow nor underflow for any finite
// mesh, and a mesh far from the origin keeps its precision. Scaling by a power of two is exact, so
// `edge` is the scaled difference of the original positions to the bit whenever that difference is
// neither infinite nor subnormal: exact zero tests and areas agree with an unscaled computation.
class LocalFrame {
 public:
  explicit LocalFrame(const TriangleMesh& mesh) {
    const auto [lo, hi] = usedBox(mesh);
    set(lo, hi);
  }
  LocalFrame(const glm::dvec3& lo, const glm::dvec3& hi) { set(lo, hi); }

  glm::dvec3 local(const glm::dvec3& p) const { return p * scale_ - centre_; }
  glm::dvec3 edge(const glm::dvec3& from, const glm::dvec3& to) const {
    return to * scale_ - from * scale_;
  }
  double areaToWorld(double area) const { return std::ldexp(area, 2 * exponent_); }
  double volumeToWorld(double volume) const { return std::ldexp(volume, 3 * exponent_); }

 private:
  void set(const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 halfSide = hi * 0.5 - lo * 0.5;
    const double half = std::max({halfSide.x, halfSide.y, halfSide.z});
    if (!(half > 0.0 && half < std::numeric_limits<double>::infinity())) return;  // no size
    exponent_ = std::max(std::ilogb(half) + 1, -1022);  // 2^-exponent_ stays finite
    scale_ = std::ldexp(1.0, -exponent_);
    centre_ = (lo * 0.5 + hi * 0.5) * scale_;
  }

  int exponent_ = 0;
  double scale_ = 1.0;      // 2^-exponent_
  glm::dvec3 centre_{0.0};  // scaled
};

// The cross product of a triangle's edges from its first corner, in the frame's scale.
glm::dvec3 cornerCross(const TriangleMesh& mesh, const LocalFrame& frame,
                       const std::array<uint32_t, 3>& t) {
  const glm::dvec3& a = mesh.positions[t[0]];
  return glm::cross(frame.edge(a, mesh.positions[t[1]]), frame.edge(a, mesh.positions[t[2]]));
}

bool isZero(const glm::dvec3& v) {
  return v.x == 0.0 && v.y == 0.0 && v.z == 0.0;
}

// Parity of crossings of the ray p + s*dir (s > 0) with the given triangles; p in the frame.
bool oddCrossings(const TriangleMesh& mesh, const LocalFrame& frame,
                  const std::vector<uint32_t>& triangles, const glm::dvec3& p,
                  const glm::dvec3& dir) {
  bool odd = false;
  for (uint32_t t : triangles) {
    const auto& tri = mesh.triangles[t];
    const glm::dvec3& corner = mesh.positions[tri[0]];
    const glm::dvec3 a = frame.local(corner);
    const glm::dvec3 e1 = frame.edge(corner, mesh.positions[tri[1]]);
    const glm::dvec3 e2 = frame.edge(corner, mesh.positions[tri[2]]);
    const glm::dvec3 h = glm::cross(dir, e2);
    const double det = glm::dot(e1, h);
    if (det == 0.0) continue;
    const double inv = 1.0 / det;
    const glm::dvec3 s = p - a;
    const double u = glm::dot(s, h) * inv;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(dir, q) * inv;
    if (v < 0.0 || u + v > 1.0) continue;
    if (glm::dot(e2, q) * inv > 0.0) odd = !odd;
  }
  return odd;
}

// Point-in-closed-shell by ray parity, majority of three directions with irrational-looking
// components so that rays rarely graze an edge or vertex; p in the frame.
bool insideShell(const TriangleMesh& mesh, const LocalFrame& frame,
                 const std::vector<uint32_t>& triangles, const glm::dvec3& p) {
  static const glm::dvec3 kDirections[3] = {
      glm::normalize(glm::dvec3(0.5773502691896258, 0.6180339887498949, 0.5345224838248488)),
      glm::normalize(glm::dvec3(-0.7071067811865476, 0.3183098861837907, 0.6324555320336759)),
      glm::normalize(glm::dvec3(0.2718281828459045, -0.8660254037844386, -0.4142135623730950)),
  };
  int votes = 0;
  for (const glm::dvec3& dir : kDirections) votes += oddCrossings(mesh, frame, triangles, p, dir);
  return votes >= 2;
}

// Keeps only vertices some triangle uses, in their original order; returns how many went.
size_t dropUnreferenced(TriangleMesh& mesh) {
  std::vector<uint32_t> remap(mesh.positions.size(), kNone);
  for (const auto& t : mesh.triangles)
    for (uint32_t v : t) remap[v] = 0;
  uint32_t next = 0;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (remap[i] == kNone) continue;
    remap[i] = next;
    mesh.positions[next++] = mesh.positions[i];
  }
  const size_t dropped = mesh.positions.size() - next;
  mesh.positions.resize(next);
  for (auto& t : mesh.triangles)
    for (uint32_t& v : t) v = remap[v];
  return dropped;
}

size_t weldInPlace(TriangleMesh& mesh) {
  const std::vector<uint32_t> canonical = canonicalVertices(mesh.positions);
  size_t merged = 0;
  for (size_t i = 0; i < canonical.size(); ++i) merged += canonical[i] != i;
  for (auto& t : mesh.triangles)
    for (uint32_t& v : t) v = canonical[v];
  return merged;
}

// Degenerate triangles (a repeated vertex through `canonical`, or zero area), the volume, the
// area and the smallest triangle's area, into c. In parallel over fixed blocks of triangles
// whose sums are added in block order: the result does not depend on the thread count.
struct MeasureSums {
  double smallest = std::numeric_limits<double>::infinity();
  double twiceArea = 0.0;
  double sixVolume = 0.0;
  size_t degenerate = 0;
};

// One triangle's measures added to s: its corners, and whether two of them weld.
void measureTriangle(const LocalFrame& frame, const glm::dvec3& a, const glm::dvec3& b,
                     const glm::dvec3& c, bool repeated, MeasureSums& s) {
  const glm::dvec3 n = glm::cross(frame.edge(a, b), frame.edge(a, c));
  if (repeated || isZero(n)) ++s.degenerate;
  const double length = glm::length(n);
  s.smallest = std::min(s.smallest, 0.5 * length);
  s.twiceArea += length;
  // Six times the signed volume of the tetrahedron of the triangle and the frame's centre:
  // a . (b x c) = a . ((b - a) x (c - a)) about that centre.
  s.sixVolume += glm::dot(frame.local(a), n);
}

void addBlock(const MeasureSums& block, MeasureSums& total) {
  total.smallest = std::min(total.smallest, block.smallest);
  total.twiceArea += block.twiceArea;
  total.sixVolume += block.sixVolume;
  total.degenerate += block.degenerate;
}

void finishMeasures(const LocalFrame& frame, const MeasureSums& total, size_t count, MeshCheck& c) {
  c.degenerateTriangles += total.degenerate;
  c.smallestTriangleArea = count == 0 ? 0.0 : frame.areaToWorld(total.smallest);
  c.area = frame.areaToWorld(total.twiceArea * 0.5);
  c.volume = frame.volumeToWorld(total.sixVolume / 6.0);
}

void measureTriangles(const TriangleMesh& mesh, const std::vector<uint32_t>& canonical,
                      MeshCheck& c) {
  const LocalFrame frame(mesh);
  const size_t count = mesh.triangles.size();
  std::vector<MeasureSums> blocks((count + kMeasureBlock - 1) / kMeasureBlock);
  parallelFor(0, int64_t(blocks.size()), 1, [&](int64_t first, int64_t last) {
    for (int64_t block = first; block < last; ++block) {
      MeasureSums s;
      const size_t end = std::min(count, size_t(block + 1) * kMeasureBlock);
      for (size_t i = size_t(block) * kMeasureBlock; i < end; ++i) {
        const auto& t = mesh.triangles[i];
        const uint32_t a = canonical[t[0]], b = canonical[t[1]], d = canonical[t[2]];
        measureTriangle(frame, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                        a == b || b == d || a == d, s);
      }
      blocks[size_t(block)] = s;
    }
  });
  MeasureSums total;
  for (const MeasureSums& s : blocks) addBlock(s, total);
  finishMeasures(frame, total, count, c);
}

}  // namespace

struct TriangleMeasures::State {
  State(const glm::dvec3& lo, const glm::dvec3& hi) : frame(lo, hi) {}
  LocalFrame frame;
  MeasureSums block;
  std::vector<MeasureSums> blocks;  // the whole blocks so far, in order
  size_t count = 0;
};

TriangleMeasures::TriangleMeasures(const glm::dvec3& usedLo, const glm::dvec3& usedHi)
    : state_(std::make_unique<State>(usedLo, usedHi)) {}

TriangleMeasures::~TriangleMeasures() = default;
TriangleMeasures::TriangleMeasures(TriangleMeasures&&) noexcept = default;
TriangleMeasures& TriangleMeasures::operator=(TriangleMeasures&&) noexcept = default;

void TriangleMeasures::add(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                           bool repeatedVertex) {
  State& s = *state_;
  measureTriangle(s.frame, a, b, c, repeatedVertex, s.block);
  if (++s.count % kMeasureBlock == 0) {
    s.blocks.push_back(s.block);
    s.block = MeasureSums();
  }
}

void TriangleMeasures::append(TriangleMeasures&& later) {
  State& s = *state_;
  State& l = *later.state_;
  if (s.count % kMeasureBlock != 0)
    throw Error("internal: triangle measures appended within a block");
  s.blocks.insert(s.blocks.end(), l.blocks.begin(), l.blocks.end());
  s.block = l.block;
  s.count += l.count;
}

void TriangleMeasures::finish(MeshCheck* check) {
  State& s = *state_;
  MeasureSums total;
  for (const MeasureSums& b : s.blocks) addBlock(b, total);
  if (s.count % kMeasureBlock != 0) addBlock(s.block, total);
  finishMeasures(s.frame, total, s.count, *check);
}

double largestExtent(const std::vector<glm::dvec3>& positions) {
  Box box;
  for (const glm::dvec3& p : positions) box.include(p);
  return box.largestSide();
}

double largestUsedExtent(const TriangleMesh& mesh) {
  return usedBox(mesh).largestSide();
}

namespace {
// checkMesh with the welding map given: canonical[i] is the first vertex at vertex i's position.
// `progress`: checked between passes and in each chunk of the parallel ones (may be null).
MeshCheck checkWelded(const TriangleMesh& mesh, const std::vector<uint32_t>& canonical,
                      const Progress* progress) {
  auto checkCancel = [progress] {
    if (progress) progress->check();
  };
  checkCancel();
  MeshCheck c;
  c.vertices = mesh.positions.size();
  c.triangles = mesh.triangles.size();
  std::atomic<size_t> nonFinite{0};
  parallelFor(0, int64_t(mesh.positions.size()), 1 << 16, [&](int64_t b, int64_t e) {
    size_t local = 0;
    for (int64_t i = b; i < e; ++i) {
      const glm::dvec3& p = mesh.positions[size_t(i)];
      local += size_t(!std::isfinite(p.x) + !std::isfinite(p.y) + !std::isfinite(p.z));
    }
    nonFinite += local;
  });
  c.nonFiniteCoordinates = nonFinite.load();

  measureTriangles(mesh, canonical, c);
  checkCancel();

  const SortedHalfEdges sorted = sortedHalfEdges(mesh, &canonical);
  checkCancel();
  const std::vector<HalfEdge>& edges = sorted.edges;
  // Edge counts and components, in parallel over the buckets of half-edges.
  ConcurrentUnionFind components(mesh.triangles.size());
  std::atomic<size_t> boundary{0}, nonManifold{0}, misoriented{0};
  parallelFor(0, int64_t(sorted.bucketEnd.size()), 4096, [&](int64_t b, int64_t e) {
    checkCancel();
    size_t localBoundary = 0, localNonManifold = 0, localMisoriented = 0;
    forEachEdge(sorted, size_t(b), size_t(e), [&](size_t begin, size_t end) {
      const size_t n = end - begin;
      if (n == 1) ++localBoundary;
      if (n > 2) ++localNonManifold;
      if (n == 2 && edges[begin].forward() == edges[begin + 1].forward()) ++localMisoriented;
      for (size_t i = begin + 1; i < end; ++i)
        components.unite(edges[begin].triangle(), edges[i].triangle());
    });
    boundary += localBoundary;
    nonManifold += localNonManifold;
    misoriented += localMisoriented;
  });
  c.boundaryEdges = boundary.load();
  c.nonManifoldEdges = nonManifold.load();
  c.misorientedEdges = misoriented.load();

  // Number the components densely, in order of their first triangle (a component's root is its
  // smallest triangle: union_find.h).
  const size_t triangleCount = mesh.triangles.size();
  constexpr int64_t kChunk = 65536;
  const size_t chunks = (triangleCount + size_t(kChunk) - 1) / size_t(kChunk);
  std::vector<uint32_t> componentOf(triangleCount);
  parallelFor(0, int64_t(triangleCount), kChunk, [&](int64_t b, int64_t e) {
    checkCancel();
    for (int64_t t = b; t < e; ++t) componentOf[size_t(t)] = components.find(uint32_t(t));
  });
  uint32_t componentCount = 0;
  componentOf = numberSetsByRoot(componentOf, &componentCount);
  c.components = int(componentCount);

  if (!c.watertight() || mesh.triangles.empty()) return c;
  checkCancel();

  // Euler characteristic per component, V - E + F, each vertex counted once per component it
  // belongs to. Sums of integers added by runs (neighbouring triangles and edges mostly share a
  // component): the same in any order.
  std::vector<std::atomic<long long>> chi(size_t(c.components));
  for (auto& x : chi) x.store(0, std::memory_order_relaxed);
  struct RunSum {
    std::vector<std::atomic<long long>>& chi;
    uint32_t component = kNone;
    long long sum = 0;
    void add(uint32_t comp, long long x) {
      if (comp != component) flush();
      component = comp;
      sum += x;
    }
    void flush() {
      if (component != kNone && sum != 0) chi[component].fetch_add(sum, std::memory_order_relaxed);
      sum = 0;
    }
  };
  // F, and the first triangle around each vertex (its smallest index).
  std::vector<std::atomic<uint32_t>> firstTriangle(mesh.positions.size());
  parallelFor(0, int64_t(firstTriangle.size()), 1 << 18, [&](int64_t b, int64_t e) {
    for (int64_t v = b; v < e; ++v)
      firstTriangle[size_t(v)].store(kNone, std::memory_order_relaxed);
  });
  parallelFor(0, int64_t(triangleCount), kChunk, [&](int64_t b, int64_t e) {
    checkCancel();
    RunSum faces{chi};
    for (int64_t t = b; t < e; ++t) {
      faces.add(componentOf[size_t(t)], 1);
      for (uint32_t v : mesh.triangles[size_t(t)]) {
        std::atomic<uint32_t>& first = firstTriangle[canonical[v]];
        uint32_t seen = first.load(std::memory_order_relaxed);
        while (uint32_t(t) < seen &&
               !first.compare_exchange_weak(seen, uint32_t(t), std::memory_order_relaxed)) {
        }
      }
    }
    faces.flush();
  });
  // V: each vertex once for the component of its first triangle; the corners in another
  // component (a vertex where components touch) collected as (vertex, component) pairs.
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> touching(chunks);
  parallelFor(0, int64_t(chunks), 1, [&](int64_t b, int64_t e) {
    checkCancel();
    for (int64_t chunk = b; chunk < e; ++chunk) {
      const size_t end = std::min(triangleCount, size_t(chunk + 1) * size_t(kChunk));
      for (size_t t = size_t(chunk) * size_t(kChunk); t < end; ++t)
        for (uint32_t v : mesh.triangles[t]) {
          const uint32_t cv = canonical[v];
          const uint32_t first = firstTriangle[cv].load(std::memory_order_relaxed);
          if (componentOf[first] != componentOf[t])
            touching[size_t(chunk)].push_back({cv, componentOf[t]});
        }
    }
  });
  parallelFor(0, int64_t(firstTriangle.size()), kChunk, [&](int64_t b, int64_t e) {
    RunSum vertices{chi};
    for (int64_t v = b; v < e; ++v) {
      const uint32_t first = firstTriangle[size_t(v)].load(std::memory_order_relaxed);
      if (first != kNone) vertices.add(componentOf[first], 1);
    }
    vertices.flush();
  });
  std::vector<std::pair<uint32_t, uint32_t>> extra;
  for (const auto& list : touching) extra.insert(extra.end(), list.begin(), list.end());
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
  for (const auto& [vertex, comp] : extra) chi[comp].fetch_add(1, std::memory_order_relaxed);
  checkCancel();
  // E: each undirected edge once, for the component of its first triangle.
  parallelFor(0, int64_t(sorted.bucketEnd.size()), 4096, [&](int64_t b, int64_t e) {
    RunSum edgeSum{chi};
    forEachEdge(sorted, size_t(b), size_t(e), [&](size_t begin, size_t) {
      edgeSum.add(componentOf[edges[begin].triangle()], -1);
    });
    edgeSum.flush();
  });
  int genus = 0;
  for (const auto& sum : chi) {
    const long long twiceGenus = 2 - sum.load(std::memory_order_relaxed);
    if (twiceGenus < 0 || twiceGenus % 2 != 0) return c;  // not a closed surface after all
    genus += static_cast<int>(twiceGenus / 2);
  }
  c.genus = genus;
  return c;
}
}  // namespace

MeshCheck checkMesh(const TriangleMesh& mesh, const Progress* progress) {
  if (progress) progress->check();
  std::vector<uint32_t> canonical = canonicalVertices(mesh.positions);
  return checkWelded(mesh, canonical, progress);
}

size_t weldIdenticalPositions(TriangleMesh& mesh) {
  const size_t merged = weldInPlace(mesh);
  dropUnreferenced(mesh);
  return merged;
}

namespace {

// Drops triangles with a repeated index or an exactly zero cross product; returns how many.
size_t removeDegenerateTriangles(TriangleMesh& mesh, const LocalFrame& frame) {
  size_t kept = 0;
  for (const auto& t : mesh.triangles) {
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated || isZero(cornerCross(mesh, frame, t))) continue;
    mesh.triangles[kept++] = t;
  }
  const size_t removed = mesh.triangles.size() - kept;
  mesh.triangles.resize(kept);
  return removed;
}

// Neighbours across manifold edges: neighbour[3t + k] is the triangle across the edge leaving
// corner k of triangle t (kNone unless exactly two triangles share that edge), sameWay[3t + k]
// whether that triangle traverses the edge in the same direction.
struct Adjacency {
  std::vector<uint32_t> neighbour;
  std::vector<uint8_t> sameWay;
};

Adjacency manifoldAdjacency(const TriangleMesh& mesh) {
  Adjacency adjacency;
  adjacency.neighbour.assign(mesh.triangles.size() * 3, kNone);
  adjacency.sameWay.assign(mesh.triangles.size() * 3, 0);
  const SortedHalfEdges sorted = sortedHalfEdges(mesh, nullptr);
  const std::vector<HalfEdge>& edges = sorted.edges;
  forEachEdge(sorted, 0, sorted.bucketEnd.size(), [&](size_t begin, size_t end) {
    if (end - begin != 2) return;
    const HalfEdge& x = edges[begin];
    const HalfEdge& y = edges[begin + 1];
    const bool same = x.forward() == y.forward();
    adjacency.neighbour[x.triangleCorner] = y.triangle();
    adjacency.neighbour[y.triangleCorner] = x.triangle();
    adjacency.sameWay[x.triangleCorner] = same;
    adjacency.sameWay[y.triangleCorner] = same;
  });
  return adjacency;
}

// Triangles connected through manifold edges.
struct Shell {
  std::vector<uint32_t> triangles;
  bool orientable = true;
  bool closed = true;
};

// Shells by breadth-first search over manifold edges. flip (one entry per triangle) marks the
// triangles to flip so that neighbours agree within each orientable shell.
std::vector<Shell> findShells(const Adjacency& adjacency, std::vector<uint8_t>& flip) {
  const size_t triangleCount = adjacency.neighbour.size() / 3;
  std::vector<Shell> shells;
  flip.assign(triangleCount, 0);
  std::vector<uint8_t> visited(triangleCount, 0);
  std::vector<uint32_t> queue;
  for (uint32_t start = 0; start < triangleCount; ++start) {
    if (visited[start]) continue;
    Shell shell;
    visited[start] = 1;
    queue.assign(1, start);
    for (size_t head = 0; head < queue.size(); ++head) {
      const uint32_t t = queue[head];
      shell.triangles.push_back(t);
      for (int k = 0; k < 3; ++k) {
        const uint32_t n = adjacency.neighbour[3 * t + k];
        if (n == kNone) {
          shell.closed = false;
          continue;
        }
        const uint8_t wanted = flip[t] ^ adjacency.sameWay[3 * t + k];
        if (!visited[n]) {
          visited[n] = 1;
          flip[n] = wanted;
          queue.push_back(n);
        } else if (flip[n] != wanted) {
          shell.orientable = false;
        }
      }
    }
    shells.push_back(std::move(shell));
  }
  return shells;
}

// Flips the minority of each orientable shell so that it agrees with the majority; returns how
// many triangles were flipped.
size_t orientShellsConsistently(TriangleMesh& mesh, const std::vector<Shell>& shells,
                                const std::vector<uint8_t>& flip) {
  size_t reoriented = 0;
  for (const Shell& shell : shells) {
    if (!shell.orientable) continue;
    size_t flipped = 0;
    for (uint32_t t : shell.triangles) flipped += flip[t];
    const bool invert = 2 * flipped > shell.triangles.size();
    reoriented += invert ? shell.triangles.size() - flipped : flipped;
    for (uint32_t t : shell.triangles) {
      if (flip[t] != invert) std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
    }
  }
  return reoriented;
}

// Where a shell lies, in the frame: six times its signed volume, its bounds, and a point on it
// away from its edges (the centroid of its largest triangle).
struct ShellPlacement {
  double sixVolume = 0.0;
  Bounds bounds;
  glm::dvec3 probe{0.0};
};

ShellPlacement placeShell(const TriangleMesh& mesh, const LocalFrame& frame, const Shell& shell) {
  ShellPlacement placement;
  Box world;
  double largest = -1.0;
  for (uint32_t t : shell.triangles) {
    const auto& tri = mesh.triangles[t];
    const glm::dvec3& corner = mesh.positions[tri[0]];
    const glm::dvec3 e1 = frame.edge(corner, mesh.positions[tri[1]]);
    const glm::dvec3 e2 = frame.edge(corner, mesh.positions[tri[2]]);
    const glm::dvec3 n = glm::cross(e1, e2);
    const glm::dvec3 a = frame.local(corner);
    placement.sixVolume += glm::dot(a, n);  // a . (b x c) = a . ((b - a) x (c - a))
    world.include(corner);
    world.include(mesh.positions[tri[1]]);
    world.include(mesh.positions[tri[2]]);
    const double area = glm::length(n);
    if (area > largest) {
      largest = area;
      placement.probe = a + (e1 + e2) / 3.0;
    }
  }
  // The frame's map is monotonic: the box of the local corners.
  placement.bounds.min = frame.local(world.lo);
  placement.bounds.max = frame.local(world.hi);
  return placement;
}

// Whether box outer holds box inner.
bool holds(const Bounds& outer, const Bounds& inner) {
  return glm::all(glm::lessThanEqual(outer.min, inner.min)) &&
         glm::all(glm::lessThanEqual(inner.max, outer.max));
}

// How many closed shells other than shell s contain it: hold its probe point and its bounds (a
// shell nested in another lies within the other's box; one that merely crosses another, as the
// struts of a lattice unioned by winding do, does not, even where its probe falls inside the
// other). containers indexes the closed shells' bounds, so a shell meets only the shells whose
// boxes hold its probe.
int nestingDepth(const TriangleMesh& mesh, const LocalFrame& frame,
                 const std::vector<Shell>& shells, const std::vector<ShellPlacement>& placements,
                 const BoxTree& containers, size_t s) {
  int depth = 0;
  containers.forEachContaining(placements[s].probe, [&](uint32_t o) {
    if (o != s && holds(placements[o].bounds, placements[s].bounds))
      depth += insideShell(mesh, frame, shells[o].triangles, placements[s].probe);
  });
  return depth;
}

// Outward: a shell nested in an even number of closed shells gets a positive volume, in an odd
// number (a cavity) a negative one. Counts the shells flipped into *report.
void orientShellsOutward(TriangleMesh& mesh, const LocalFrame& frame,
                         const std::vector<Shell>& shells, PrepareReport* report) {
  std::vector<ShellPlacement> placements;
  placements.reserve(shells.size());
  for (const Shell& shell : shells) placements.push_back(placeShell(mesh, frame, shell));
  // Only closed shells contain anything: the others get an empty box.
  std::vector<Bounds> closedBounds(shells.size());
  for (size_t s = 0; s < shells.size(); ++s)
    if (shells[s].closed) closedBounds[s] = placements[s].bounds;
  const BoxTree containers(closedBounds);
  for (size_t s = 0; s < shells.size(); ++s) {
    if (!shells[s].orientable || placements[s].sixVolume == 0.0) continue;
    const bool wantPositive = nestingDepth(mesh, frame, shells, placements, containers, s) % 2 == 0;
    if ((placements[s].sixVolume > 0.0) == wantPositive) continue;
    ++(wantPositive ? report->shellsTurnedOutward : report->cavitiesTurnedInward);
    for (uint32_t t : shells[s].triangles) std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
  }
}

}  // namespace

PrepareReport prepareMesh(TriangleMesh& mesh) {
  PrepareReport report;
  report.weldedVertices = weldInPlace(mesh);
  const LocalFrame frame(mesh);
  report.removedDegenerate = removeDegenerateTriangles(mesh, frame);
  std::vector<uint8_t> flip;
  const std::vector<Shell> shells = findShells(manifoldAdjacency(mesh), flip);
  report.reorientedTriangles = orientShellsConsistently(mesh, shells, flip);
  orientShellsOutward(mesh, frame, shells, &report);
  report.shells = shells.size();
  report.removedUnreferenced = dropUnreferenced(mesh);
  // Welded and without unreferenced vertices: no two vertices share a position, so the welding
  // map is the identity (no second hash of every position).
  std::vector<uint32_t> identity(mesh.positions.size());
  std::iota(identity.begin(), identity.end(), 0u);
  report.check = checkWelded(mesh, identity, nullptr);
  return report;
}

}  // namespace strata
