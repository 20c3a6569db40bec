#include "engine/export/contour_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "engine/contour/contour_tile.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/parallel_for.h"
#include "engine/util/timer.h"

namespace strata {
namespace {

void collectLeafStyles(const NodePtr& node, std::map<uint32_t, LeafStyle>* styles) {
  if (!node) return;
  if (!isOperation(node->kind)) (*styles)[node->id] = LeafStyle{node->name, node->color};
  for (const auto& c : node->children) collectLeafStyles(c, styles);
}

}  // namespace

ExportMesh contourScene(const Scene& scene, Evaluator& evaluator, const ContourOptions& options,
                        Progress& progress, ContourReport* report) {
  if (options.tileCells < 8) throw Error("tile size must be at least 8 cells");
  ContourReport local;
  ContourReport& r = report ? *report : local;
  r = ContourReport();
  const Grid grid = Evaluator::gridFor(scene, options.resolution);
  r.grid = grid;
  const glm::ivec3 tiles = (grid.cells + options.tileCells - 1) / options.tileCells;
  // Cells of a tile are indexed in 32 bits (contour_cells.h, both backends); the tile count is
  // an int. Refuse what would overflow rather than wrap around into a wrong mesh.
  uint64_t tileWindowCells = 1;
  for (int a = 0; a < 3; ++a)
    tileWindowCells *= uint64_t(std::min(options.tileCells, grid.cells[a]) + 4);  // with halo
  if (tileWindowCells > uint64_t(UINT32_MAX))
    throw Error("a tile of " + std::to_string(options.tileCells) +
                " cells a side is too large to contour; use --tile 1024 or less");
  const int64_t tileCount = int64_t(tiles.x) * tiles.y * tiles.z;
  if (tileCount > INT32_MAX)
    throw Error(std::to_string(tileCount) + " tiles are too many; use a larger --tile");
  r.tiles = int(tileCount);

  std::vector<ContourVertex> vertices;
  std::vector<ContourTriangle> triangles;
  int done = 0;
  for (int tz = 0; tz < tiles.z; ++tz)
    for (int ty = 0; ty < tiles.y; ++ty)
      for (int tx = 0; tx < tiles.x; ++tx) {
        const glm::ivec3 begin = glm::ivec3(tx, ty, tz) * options.tileCells;
        const glm::ivec3 end = glm::min(begin + options.tileCells, grid.cells);
        const TileWindow window = tileWindow(begin, end, grid.cells);
        const bool whole = window.first == glm::ivec3(0) && window.cells == grid.cells;
        const Grid tileGrid = whole ? grid : grid.window(window.first, window.cells);

        Stopwatch evaluate;
        if (r.tiles > 1) {
          // Each tile has its own grid, so no cache entry serves another tile: keep none, so
          // that memory stays that of one tile's evaluation (what --tile promises).
          evaluator.clearCache();
        }
        EvalResult result = evaluator.evaluateOn(scene, tileGrid, progress);
        r.evaluateSeconds += evaluate.seconds();
        r.surfels += result.measure.surfels;
        if (result.measure.surfels == 0) {
          progress.report("export", double(++done) / r.tiles);
          continue;
        }
        Stopwatch contour;
        TileContour tile =
            evaluator.backend().contourTile(result.root, grid.cells, begin, end, progress);
        r.contourSeconds += contour.seconds();
        r.synthesizedCrossings += tile.synthesizedCrossings;
        r.signDisagreements += tile.signDisagreements;
        vertices.insert(vertices.end(), tile.vertices.begin(), tile.vertices.end());
        triangles.insert(triangles.end(), tile.triangles.begin(), tile.triangles.end());
        progress.report("export", double(++done) / r.tiles);
      }

  Stopwatch merge;
  // Vertices: one per key (neighbouring tiles computed their shared halo cells identically),
  // in key order; triangles in edge order. Both orders are independent of the tiling. Each
  // tile emits its cells and edges in increasing order already, so one tile needs no sort.
  auto byKey = [](const ContourVertex& a, const ContourVertex& b) { return a.key < b.key; };
  if (!std::is_sorted(vertices.begin(), vertices.end(), byKey))
    std::sort(vertices.begin(), vertices.end(), byKey);
  vertices.erase(
      std::unique(vertices.begin(), vertices.end(),
                  [](const ContourVertex& a, const ContourVertex& b) { return a.key == b.key; }),
      vertices.end());
  progress.check();
  auto byOrder = [](const ContourTriangle& a, const ContourTriangle& b) {
    return a.order < b.order;
  };
  if (!std::is_sorted(triangles.begin(), triangles.end(), byOrder))
    std::sort(triangles.begin(), triangles.end(), byOrder);
  progress.check();

  ExportMesh out;
  out.unit = scene.settings.unit;
  collectLeafStyles(scene.root, &out.leaves);
  out.mesh.positions.resize(vertices.size());
  parallelFor(0, int64_t(vertices.size()), 65536, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i)
      out.mesh.positions[size_t(i)] =
          grid.origin + grid.h * glm::dvec3(vertices[size_t(i)].position[0],
                                            vertices[size_t(i)].position[1],
                                            vertices[size_t(i)].position[2]);
  });
  for (const ContourVertex& v : vertices)
    r.maxPlaneDistance = std::max(r.maxPlaneDistance, v.planeDistance * grid.h);
  out.mesh.triangles.resize(triangles.size());
  out.triangleLeaf.resize(triangles.size());
  auto indexOf = [&](uint64_t key) {
    auto it = std::lower_bound(vertices.begin(), vertices.end(), key,
                               [](const ContourVertex& v, uint64_t k) { return v.key < k; });
    if (it == vertices.end() || it->key != key)
      throw Error("internal: a triangle refers to a vertex no tile produced");
    return uint32_t(it - vertices.begin());
  };
  parallelFor(0, int64_t(triangles.size()), 65536, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) {
      const ContourTriangle& t = triangles[size_t(i)];
      out.mesh.triangles[size_t(i)] = {indexOf(t.vertex[0]), indexOf(t.vertex[1]),
                                       indexOf(t.vertex[2])};
      out.triangleLeaf[size_t(i)] = t.leaf;
    }
  });
  uint32_t previous = 0xffffffffu;  // neighbouring triangles mostly share a leaf
  for (uint32_t leaf : out.triangleLeaf) {
    if (leaf == previous) continue;
    previous = leaf;
    if (!out.leaves.count(leaf)) out.leaves[leaf] = LeafStyle{"unknown", glm::vec3(0.8f)};
  }
  r.mergeSeconds = merge.seconds();
  r.deviationBound = std::sqrt(3.0) * grid.h;
  r.peakBytes = peakResidentBytes();
  return out;
}

}  // namespace strata
