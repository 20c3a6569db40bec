#include "tests/support/export_cases.h"

#include <cmath>

#include "engine/geometry/mesh_check.h"
#include "tests/support/scene_builder.h"

namespace strata::test {

std::shared_ptr<const TriangleMesh> facetedTorus(double major, double minor, int around,
                                                 int across) {
  auto m = std::make_shared<TriangleMesh>();
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const double u = 2 * M_PI * i / around, v = 2 * M_PI * j / across;
      const double r = major + minor * std::cos(v);
      m->positions.push_back({r * std::cos(u), r * std::sin(u), minor * std::sin(v)});
    }
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const uint32_t a = uint32_t(i * across + j), b = uint32_t(((i + 1) % around) * across + j),
                     c = uint32_t(((i + 1) % around) * across + (j + 1) % across),
                     d = uint32_t(i * across + (j + 1) % across);
      m->triangles.push_back({a, b, c});
      m->triangles.push_back({a, c, d});
    }
  return m;
}

NodePtr foldedSliver() {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0.961176, 0.501176, 0.501176},
                     {-1.72941, -0.6, -0.581176},
                     {-0.6, -0.236863, -0.6},
                     {-0.6, -0.8, -0.6},
                     {-0.6, -0.6, -0.4},
                     {-0.6, -0.6, -0.8}};
  mesh->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                     {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  prepareMesh(*mesh);
  Transform t;
  t.translate = glm::dvec3(-1.0);
  t.scale = glm::dvec3(-0.3, 0.3, 0.3);
  return withTransform(meshLeaf(mesh), t);
}

}  // namespace strata::test
