#include "engine/geometry/degenerate_repair.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <unordered_map>
#include <unordered_set>

#include "engine/util/parallel_for.h"

namespace strata {
namespace {

using Triangle = std::array<uint32_t, 3>;

enum class Flaw : uint8_t {
  None,
  Collinear,   // distinct corners on one line: no area
  Coincident,  // two corners stored at one point (or one index twice)
};

class StoredPositions {
 public:
  StoredPositions(const TriangleMesh& mesh, StoredRounding stored)
      : positions_(mesh.positions), stored_(stored) {}
  glm::dvec3 operator()(uint32_t v) const {
    const glm::dvec3& p = positions_[v];
    return stored_ ? glm::dvec3(stored_(p.x), stored_(p.y), stored_(p.z)) : p;
  }

 private:
  const std::vector<glm::dvec3>& positions_;
  StoredRounding stored_;
};

// As checkMesh judges a triangle with these (stored) corners: corners welded by identical
// coordinates, the area from the cross product of the edges from the first corner (exactly zero
// or not: a power-of-two frame, as checkMesh's, changes neither).
Flaw flawOfCorners(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  if (a == b || b == c || a == c) return Flaw::Coincident;
  const glm::dvec3 n = glm::cross(b - a, c - a);
  return n.x == 0.0 && n.y == 0.0 && n.z == 0.0 ? Flaw::Collinear : Flaw::None;
}

Flaw flawOf(const StoredPositions& at, const Triangle& t) {
  return flawOfCorners(at(t[0]), at(t[1]), at(t[2]));
}

// The triangle's corners rotated (same orientation) so that checkMesh finds an area; false when
// no rotation does.
bool rotatedToHaveArea(const StoredPositions& at, Triangle* t) {
  for (int r = 0; r < 3; ++r) {
    const Triangle rotated = {(*t)[size_t(r)], (*t)[size_t(r + 1) % 3], (*t)[size_t(r + 2) % 3]};
    if (flawOf(at, rotated) == Flaw::None) {
      *t = rotated;
      return true;
    }
  }
  return false;
}

// Indices of the flawed triangles, in order. Parallel over fixed blocks.
std::vector<uint32_t> flawedTriangles(const TriangleMesh& mesh, const StoredPositions& at) {
  constexpr int64_t kBlock = 65536;
  const int64_t count = int64_t(mesh.triangles.size());
  std::vector<std::vector<uint32_t>> blocks(size_t((count + kBlock - 1) / kBlock));
  parallelFor(0, int64_t(blocks.size()), 1, [&](int64_t first, int64_t last) {
    for (int64_t block = first; block < last; ++block) {
      const int64_t end = std::min(count, (block + 1) * kBlock);
      for (int64_t i = block * kBlock; i < end; ++i)
        if (flawOf(at, mesh.triangles[size_t(i)]) != Flaw::None)
          blocks[size_t(block)].push_back(uint32_t(i));
    }
  });
  std::vector<uint32_t> out;
  for (const auto& b : blocks) out.insert(out.end(), b.begin(), b.end());
  return out;
}

// The triangles around each of `vertices`, in index order. Parallel over fixed blocks.
std::unordered_map<uint32_t, std::vector<uint32_t>> trianglesAround(
    const TriangleMesh& mesh, const std::unordered_set<uint32_t>& vertices) {
  constexpr int64_t kBlock = 65536;
  const int64_t count = int64_t(mesh.triangles.size());
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> blocks(
      size_t((count + kBlock - 1) / kBlock));
  parallelFor(0, int64_t(blocks.size()), 1, [&](int64_t first, int64_t last) {
    for (int64_t block = first; block < last; ++block) {
      const int64_t end = std::min(count, (block + 1) * kBlock);
      for (int64_t i = block * kBlock; i < end; ++i)
        for (uint32_t v : mesh.triangles[size_t(i)])
          if (vertices.count(v)) blocks[size_t(block)].push_back({v, uint32_t(i)});
    }
  });
  std::unordered_map<uint32_t, std::vector<uint32_t>> around;
  for (const auto& b : blocks)
    for (const auto& [v, t] : b) {
      auto& list = around[v];
      if (list.empty() || list.back() != t) list.push_back(t);
    }
  return around;
}

// Position of v in t, or -1.
int cornerOf(const Triangle& t, uint32_t v) {
  for (int k = 0; k < 3; ++k)
    if (t[size_t(k)] == v) return k;
  return -1;
}

// The triangle among `candidates` holding the directed edge from -> to, or -1.
int64_t holdingEdge(const TriangleMesh& mesh, const std::vector<uint32_t>& candidates,
                    uint32_t from, uint32_t to) {
  for (uint32_t t : candidates) {
    const Triangle& tri = mesh.triangles[t];
    const int k = cornerOf(tri, from);
    if (k >= 0 && tri[size_t(k + 1) % 3] == to) return t;
  }
  return -1;
}

// One round: each flawed triangle whose neighbourhood no earlier repair of this round touched is
// repaired if it can be; returns the number repaired. Triangles a collapse removes are marked in
// `dead`.
size_t repairRound(TriangleMesh& mesh, const StoredPositions& at,
                   const std::vector<uint32_t>& flawed, std::vector<uint8_t>& dead,
                   DegenerateRepair& report) {
  std::unordered_set<uint32_t> corners;
  for (uint32_t t : flawed)
    for (uint32_t v : mesh.triangles[t]) corners.insert(v);
  const auto around = trianglesAround(mesh, corners);
  const auto aroundOf = [&](uint32_t v) -> const std::vector<uint32_t>& {
    static const std::vector<uint32_t> kNone;
    const auto it = around.find(v);
    return it == around.end() ? kNone : it->second;
  };
  // Vertices whose triangles changed this round: their lists above are stale.
  std::unordered_set<uint32_t> touched;
  const auto isTouched = [&](std::initializer_list<uint32_t> vs) {
    for (uint32_t v : vs)
      if (touched.count(v)) return true;
    return false;
  };
  size_t repaired = 0;
  for (uint32_t ti : flawed) {
    if (dead[ti]) continue;
    Triangle t = mesh.triangles[ti];
    if (isTouched({t[0], t[1], t[2]})) continue;
    const Flaw flaw = flawOf(at, t);
    if (flaw == Flaw::None) continue;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // an index twice: left
    if (flaw == Flaw::Collinear) {
      // Rotate so that the middle corner is second: the edge c -> a is the longest.
      const glm::dvec3 p[3] = {at(t[0]), at(t[1]), at(t[2])};
      double longest = -1.0;
      int middle = 0;
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 e = p[(k + 2) % 3] - p[(k + 1) % 3];  // the edge opposite corner k
        const double length = glm::dot(e, e);
        if (length > longest) {
          longest = length;
          middle = k;
        }
      }
      const uint32_t a = t[size_t(middle + 2) % 3], b = t[size_t(middle)],
                     c = t[size_t(middle + 1) % 3];
      // (a, b, c) in t's orientation; the neighbour holds a -> c.
      const int64_t ni = holdingEdge(mesh, aroundOf(a), a, c);
      if (ni < 0 || dead[size_t(ni)]) continue;
      const Triangle& n = mesh.triangles[size_t(ni)];
      const uint32_t d = n[size_t(cornerOf(n, c) + 1) % 3];
      if (d == b || isTouched({d})) continue;
      bool edgeExists = false;  // b - d already an edge: a flip would double it
      for (uint32_t s : aroundOf(b)) edgeExists = edgeExists || cornerOf(mesh.triangles[s], d) >= 0;
      if (edgeExists) continue;
      Triangle first = {a, b, d}, second = {b, c, d};
      if (!rotatedToHaveArea(at, &first) || !rotatedToHaveArea(at, &second)) {
        // No flip gives two good triangles: the same triangle turned so that its area shows.
        if (!rotatedToHaveArea(at, &t)) continue;
        mesh.triangles[ti] = t;
        ++report.rotated;
        ++repaired;
        continue;
      }
      mesh.triangles[ti] = first;
      mesh.triangles[size_t(ni)] = second;
      for (uint32_t v : {a, b, c, d}) touched.insert(v);
      ++report.flipped;
      ++repaired;
      continue;
    }
    // Coincident: collapse the edge u -> v whose ends are stored at one point.
    int k = 0;
    while (!(at(t[size_t(k)]) == at(t[size_t(k + 1) % 3]))) ++k;
    const uint32_t u = t[size_t(k)], v = t[size_t(k + 1) % 3], x = t[size_t(k + 2) % 3];
    const int64_t ni = holdingEdge(mesh, aroundOf(v), v, u);
    if (ni < 0 || dead[size_t(ni)]) continue;
    const Triangle& n = mesh.triangles[size_t(ni)];
    const uint32_t y = n[size_t(cornerOf(n, u) + 1) % 3];
    if (x == y || isTouched({x, y})) continue;
    // Link condition: u and v share no neighbour but x and y.
    std::unordered_set<uint32_t> neighboursOfU;
    for (uint32_t s : aroundOf(u))
      for (uint32_t w : mesh.triangles[s])
        if (w != u) neighboursOfU.insert(w);
    bool linked = true;
    std::unordered_set<uint32_t> neighboursOfV;
    for (uint32_t s : aroundOf(v))
      for (uint32_t w : mesh.triangles[s])
        if (w != v) neighboursOfV.insert(w);
    for (uint32_t w : neighboursOfV)
      if (w != u && w != x && w != y && neighboursOfU.count(w)) linked = false;
    if (!linked) continue;
    // After the collapse no two triangles may hold the same three vertices (x or y would be
    // left with two triangles back to back: a tetrahedron, or a corner of valence three).
    std::vector<Triangle> after;
    for (const auto* list : {&aroundOf(u), &aroundOf(v)})
      for (uint32_t s : *list) {
        if (s == ti || s == uint32_t(ni)) continue;
        Triangle r = mesh.triangles[s];
        for (uint32_t& w : r)
          if (w == u) w = v;
        std::sort(r.begin(), r.end());
        after.push_back(r);
      }
    std::sort(after.begin(), after.end());
    if (std::adjacent_find(after.begin(), after.end()) != after.end()) continue;
    dead[ti] = dead[size_t(ni)] = 1;
    for (uint32_t s : aroundOf(u)) {
      if (dead[s]) continue;
      for (uint32_t& w : mesh.triangles[s])
        if (w == u) w = v;
    }
    for (uint32_t w : {u, v, x, y}) touched.insert(w);
    ++report.collapsed;
    ++repaired;
  }
  return repaired;
}

}  // namespace

bool storedFlawed(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                  StoredRounding stored) {
  // As StoredPositions rounds (no mesh made: the streamed export asks this of every triangle).
  const auto at = [stored](const glm::dvec3& p) {
    return stored ? glm::dvec3(stored(p.x), stored(p.y), stored(p.z)) : p;
  };
  return flawOfCorners(at(a), at(b), at(c)) != Flaw::None;
}

DegenerateRepair repairDegenerateTriangles(TriangleMesh* mesh, StoredRounding stored,
                                           std::vector<uint32_t>* triangleData) {
  DegenerateRepair report;
  repairDegenerateTriangles(mesh, stored, triangleData, nullptr, &report);
  return report;
}

bool repairDegenerateTriangles(TriangleMesh* mesh, StoredRounding stored,
                               std::vector<uint32_t>* triangleData,
                               const std::vector<uint8_t>* ringComplete, DegenerateRepair* out) {
  DegenerateRepair& report = *out;
  report = DegenerateRepair();
  const StoredPositions at(*mesh, stored);
  std::vector<uint32_t> flawed = flawedTriangles(*mesh, at);
  // A round reads the triangles around every corner of the flawed triangles.
  const auto ringsKnown = [&] {
    if (!ringComplete) return true;
    for (uint32_t t : flawed)
      for (uint32_t v : mesh->triangles[t])
        if (!(*ringComplete)[v]) return false;
    return true;
  };
  // Each round repairs at least one triangle or stops; repairs next to each other wait for the
  // next round (their neighbourhoods changed), so a few rounds do.
  while (!flawed.empty()) {
    if (!ringsKnown()) return false;
    std::vector<uint8_t> dead(mesh->triangles.size(), 0);
    const size_t repaired = repairRound(*mesh, at, flawed, dead, report);
    if (std::find(dead.begin(), dead.end(), uint8_t(1)) != dead.end()) {
      size_t kept = 0;
      for (size_t i = 0; i < mesh->triangles.size(); ++i) {
        if (dead[i]) continue;
        mesh->triangles[kept] = mesh->triangles[i];
        if (triangleData) (*triangleData)[kept] = (*triangleData)[i];
        ++kept;
      }
      mesh->triangles.resize(kept);
      if (triangleData) triangleData->resize(kept);
    }
    flawed = flawedTriangles(*mesh, at);
    if (repaired == 0) break;
  }
  report.left = flawed.size();
  return true;
}

}  // namespace strata
