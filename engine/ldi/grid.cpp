#include "engine/ldi/grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/util/error.h"

namespace strata {
namespace {
void checkResolution(int resolution) {
  if (resolution < kMinResolution || resolution > kMaxResolution)
    throw Error("resolution " + std::to_string(resolution) + " is out of range [" +
                std::to_string(kMinResolution) + ", " + std::to_string(kMaxResolution) + "]");
}
bool finite(const glm::dvec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}
}  // namespace

Bounds Grid::bounds() const {
  Bounds b;
  b.min = origin + h * glm::dvec3(first);
  b.max = origin + h * glm::dvec3(first + cells);
  return b;
}

Grid makeGrid(const Bounds& bounds, int resolution, double margin) {
  checkResolution(resolution);
  if (bounds.empty()) throw Error("the scene is empty: nothing visible to evaluate");
  if (!finite(bounds.min) || !finite(bounds.max))
    throw Error("the scene bounds are not finite (check transforms and meshes)");
  glm::dvec3 size = bounds.size();
  double longest = std::max({size.x, size.y, size.z});
  if (longest <= 0.0) longest = 1.0;
  glm::dvec3 extent = size + glm::dvec3(2.0 * margin * longest);
  double extentLongest = std::max({extent.x, extent.y, extent.z});
  Grid grid;
  grid.h = extentLongest / double(resolution - 2 * kGuardCells);
  for (int a = 0; a < 3; ++a) {
    int inner = std::max(1, int(std::ceil(extent[a] / grid.h - 1e-9)));
    grid.cells[a] = std::min(resolution, inner + 2 * kGuardCells);
  }
  grid.origin = bounds.center() - 0.5 * grid.h * glm::dvec3(grid.cells);
  return grid;
}

Grid makeGridExact(const Bounds& box, int resolution) {
  checkResolution(resolution);
  glm::dvec3 size = box.size();
  double longest = std::max({size.x, size.y, size.z});
  if (box.empty() || !(longest > 0.0) || !finite(box.min) || !finite(box.max))
    throw Error("the grid bounds are empty or not finite");
  Grid grid;
  grid.h = longest / resolution;
  grid.origin = box.min;
  for (int a = 0; a < 3; ++a) grid.cells[a] = std::max(1, int(std::ceil(size[a] / grid.h - 1e-9)));
  return grid;
}

}  // namespace strata
