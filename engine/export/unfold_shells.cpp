// See unfold_shells.h.
#include "engine/export/unfold_shells.h"

#include <glm/geometric.hpp>

#include <cmath>

#include "engine/util/union_find.h"

namespace strata {
namespace {

constexpr uint64_t kFaceVertexBit = uint64_t(1) << 63;  // faceSegmentKey (contour_cells.h)

// Six times the signed volume of the shell's triangles with vertex positions `at(i)`, relative
// to `ref` (a point of the shell, so that the sum does not cancel far from the origin).
template <typename At>
double sixVolume(const TriangleMesh& mesh, const std::vector<uint32_t>& shellTriangles,
                 const glm::dvec3& ref, At at) {
  double sum = 0.0;
  for (uint32_t t : shellTriangles) {
    const auto& tri = mesh.triangles[t];
    const glm::dvec3 a = at(tri[0]) - ref, b = at(tri[1]) - ref, c = at(tri[2]) - ref;
    sum += glm::dot(a, glm::cross(b, c));
  }
  return sum;
}

int sign(double x) {
  return (x > 0.0) - (x < 0.0);
}

}  // namespace

int unfoldInvertedShells(const Grid& grid, const std::vector<ContourVertex>& vertices,
                         TriangleMesh* mesh) {
  const size_t n = mesh->positions.size();
  if (n == 0 || vertices.size() != n) return 0;

  // Where each vertex goes at the grid's own placement: its cell's centre, or halfway there
  // when its cell has several components (their keys are adjacent: vertices are in key order).
  std::vector<glm::dvec3> anchor(n);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t key = vertices[i].key;
    if (key & kFaceVertexBit) {  // on a cell face, between two crossings: stays
      anchor[i] = mesh->positions[i];
      continue;
    }
    const uint64_t cell = key / 4;
    const uint64_t gx = uint64_t(grid.cells.x), gy = uint64_t(grid.cells.y);
    const glm::dvec3 index(double(cell % gx), double(cell / gx % gy), double(cell / gx / gy));
    const glm::dvec3 centre = grid.origin + grid.h * (index + 0.5);
    const bool shared = (i > 0 && vertices[i - 1].key / 4 == cell) ||
                        (i + 1 < n && vertices[i + 1].key / 4 == cell);
    anchor[i] = shared ? 0.5 * (centre + mesh->positions[i]) : centre;
  }

  // Shells: triangles joined through shared vertices.
  UnionFind sets(n);
  for (const auto& t : mesh->triangles) {
    sets.unite(t[0], t[1]);
    sets.unite(t[0], t[2]);
  }
  std::vector<uint32_t> shellOf(n, 0);
  std::vector<uint32_t> rootShell(n, UINT32_MAX);
  uint32_t shells = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t root = sets.find(uint32_t(i));
    if (rootShell[root] == UINT32_MAX) rootShell[root] = shells++;
    shellOf[i] = rootShell[root];
  }
  std::vector<std::vector<uint32_t>> shellTriangles(shells);
  for (size_t t = 0; t < mesh->triangles.size(); ++t)
    shellTriangles[shellOf[mesh->triangles[t][0]]].push_back(uint32_t(t));

  int moved = 0;
  std::vector<bool> done(n, false);  // a vertex belongs to one shell: moved once
  for (uint32_t s = 0; s < shells; ++s) {
    const std::vector<uint32_t>& tris = shellTriangles[s];
    if (tris.empty()) continue;
    const glm::dvec3 ref = anchor[mesh->triangles[tris[0]][0]];
    const auto placed = [&](uint32_t v) { return mesh->positions[v]; };
    const auto anchored = [&](uint32_t v) { return anchor[v]; };
    const int want = sign(sixVolume(*mesh, tris, ref, anchored));
    if (want == 0 || sign(sixVolume(*mesh, tris, ref, placed)) == want) continue;
    // Pulled back from the anchors: keep `keep` of each vertex's offset from its anchor.
    double keep = 0.5;
    for (;; keep *= 0.5) {
      const auto pulled = [&](uint32_t v) {
        return anchor[v] + keep * (mesh->positions[v] - anchor[v]);
      };
      if (keep < 1.0 / 64 || sign(sixVolume(*mesh, tris, ref, pulled)) == want) break;
    }
    if (keep < 1.0 / 64) keep = 0.0;
    for (uint32_t t : tris)
      for (uint32_t v : mesh->triangles[t]) {
        if (done[v]) continue;
        done[v] = true;
        mesh->positions[v] = anchor[v] + keep * (mesh->positions[v] - anchor[v]);
      }
    ++moved;
  }
  return moved;
}

}  // namespace strata
