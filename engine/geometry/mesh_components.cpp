#include "engine/geometry/mesh_components.h"

#include "engine/util/parallel_for.h"
#include "engine/util/union_find.h"

namespace strata {

std::vector<uint32_t> vertexComponentRoots(const TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  ConcurrentUnionFind sets(n);
  parallelFor(0, int64_t(mesh.triangles.size()), 65536, [&](int64_t b, int64_t e) {
    for (int64_t t = b; t < e; ++t) {
      const auto& tri = mesh.triangles[size_t(t)];
      sets.unite(tri[0], tri[1]);
      sets.unite(tri[0], tri[2]);
    }
  });
  std::vector<uint32_t> rootOf(n);
  parallelFor(0, int64_t(n), 65536, [&](int64_t b, int64_t e) {
    for (int64_t v = b; v < e; ++v) rootOf[size_t(v)] = sets.find(uint32_t(v));
  });
  return rootOf;
}

}  // namespace strata
