#include "engine/export/contour_scene.h"
#include "engine/export/drop_specks.h"
#include "engine/export/unfold_shells.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/contour/contour_tile.h"
#include "engine/geometry/mesh_components.h"
#include "engine/ldi/offset_math.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/parallel_for.h"
#include "engine/util/parallel_merge.h"
#include "engine/util/parallel_sort.h"
#include "engine/util/timer.h"

namespace strata {
namespace {

void collectLeafStyles(const NodePtr& node, std::map<uint32_t, LeafStyle>* styles) {
  if (!node) return;
  if (!isOperation(node->kind)) (*styles)[node->id] = LeafStyle{node->name, node->color};
  for (const auto& c : node->children) collectLeafStyles(c, styles);
}

// The ids of the mesh leaves taken as open (Node::meshOpen), sorted: the leaf ids triangles carry.
void collectOpenLeaves(const NodePtr& node, std::vector<uint32_t>* open) {
  if (!node) return;
  if (node->kind == NodeKind::Mesh && node->meshOpen) open->push_back(uint32_t(node->id));
  for (const auto& c : node->children) collectOpenLeaves(c, open);
}

// The tiles of `grid` of `size` cells per axis, refused where cell indices or the tile count
// would overflow.
glm::ivec3 tileCounts(const Grid& grid, const glm::ivec3& size) {
  if (size.x < 8 || size.y < 8 || size.z < 8) throw Error("tile size must be at least 8 cells");
  const glm::ivec3 tiles = (grid.cells + size - 1) / size;
  // Cells of a tile are indexed in 32 bits (contour_cells.h, both backends); the tile count is
  // an int. Refuse what would overflow rather than wrap around into a wrong mesh.
  uint64_t tileWindowCells = 1;
  for (int a = 0; a < 3; ++a)
    tileWindowCells *= uint64_t(std::min(size[a], grid.cells[a]) + 4);  // with halo
  if (tileWindowCells > uint64_t(UINT32_MAX))
    throw Error("a tile of " + std::to_string(std::max({size.x, size.y, size.z})) +
                " cells a side is too large to contour; use --tile 1024 or less");
  const int64_t tileCount = int64_t(tiles.x) * tiles.y * tiles.z;
  if (tileCount > INT32_MAX)
    throw Error(std::to_string(tileCount) + " tiles are too many; use a larger --tile");
  return tiles;
}

// Vertices and triangles of every tile, keyed on the global lattice: each tile's own arrays,
// sorted by sortTiles, then turned in merged order into the mesh's by indexedMesh, which keeps
// the merged vertices' keys (their order is the mesh's vertex order).
struct TiledContour {
  std::vector<TileContour> tiles;
  std::vector<uint64_t> keys;
};

// Evaluates and contours one tile, appending it to `out`. With a `halo` (modifiers), the tile
// is evaluated on its window grown by it on every side (within the grid) and cropped back.
// *lastEvaluated: the grid the previous tile was evaluated on (its cache entries), updated.
void contourOneTile(const Scene& scene, Evaluator& evaluator, const Grid& grid, int halo,
                    const glm::ivec3& begin, const glm::ivec3& end, Progress& progress,
                    ContourReport& r, std::vector<TileContour>* out, Grid* lastEvaluated) {
  const TileWindow window = tileWindow(begin, end, grid.cells);
  const bool whole = window.first == glm::ivec3(0) && window.cells == grid.cells;
  const Grid tileGrid = whole ? grid : grid.window(window.first, window.cells);
  const EvaluationWindow grown = evaluationWindow(grid, halo, begin, end);
  const Grid evalGrid = whole ? grid : grid.window(grown.first, grown.end - grown.first);
  Stopwatch evaluate;
  if (r.tiles > 1 && !(evalGrid == *lastEvaluated)) {
    // Each tile has its own grid, so no cache entry serves another tile: keep none, so that
    // memory stays that of one tile's evaluation (what --tile promises). Tiles evaluated on the
    // same grid (windows grown by modifiers to the whole grid) share one evaluation.
    evaluator.clearCache();
  }
  *lastEvaluated = evalGrid;
  EvalOptions surfelCountOnly;
  surfelCountOnly.measureRoot = false;
  EvalResult result = evaluator.evaluateOn(scene, evalGrid, progress, surfelCountOnly);
  if (!(evalGrid == tileGrid) && result.measure.surfels > 0) {
    result.root = evaluator.backend().crop(result.root, tileGrid, progress);
    result.measure.surfels = result.root->surfelCount();
  }
  r.evaluateSeconds += evaluate.seconds();
  r.surfels += result.measure.surfels;
  r.tileLdiBytes = std::max(r.tileLdiBytes, result.cacheBytes);
  if (result.modifySeconds > 0.0) {
    r.modifySeconds += result.modifySeconds;
    r.modifiedNodes += double(evalGrid.nodeCount());
  }
  addWarnings(result.warnings, &r);
  if (result.measure.surfels == 0) return;
  // The evaluation is over: a long contour of a job of one tile no longer shows "evaluate".
  progress.report("contour", 0.0);
  Stopwatch contour;
  TileContour tile = evaluator.backend().contourTile(result.root, grid.cells, begin, end, progress);
  r.contourSeconds += contour.seconds();
  r.synthesizedCrossings += tile.synthesizedCrossings;
  r.signDisagreements += tile.signDisagreements;
  out->push_back(std::move(tile));
}

// Puts a tile's arrays in key order: its cell vertices come in key order and its face-segment
// vertices (keys with the top bit: after every cell key) after them in polygon order, its
// triangles in edge order; whatever breaks that expectation is sorted.
void sortTile(TileContour* tile) {
  constexpr uint64_t kFaceBit = uint64_t(1) << 63;
  auto& v = tile->vertices;
  const auto byKey = [](const ContourVertex& a, const ContourVertex& b) { return a.key < b.key; };
  const auto faces = std::partition_point(
      v.begin(), v.end(), [](const ContourVertex& x) { return (x.key & kFaceBit) == 0; });
  std::sort(faces, v.end(), byKey);
  if (!std::is_sorted(v.begin(), v.end(), byKey))
    parallelSortByKey(v, [](const ContourVertex& x) { return x.key; });
  auto& t = tile->triangles;
  if (!std::is_sorted(t.begin(), t.end(), [](const ContourTriangle& a, const ContourTriangle& b) {
        return a.order < b.order;
      }))
    parallelSortByKey(t, [](const ContourTriangle& x) { return x.order; });
}

// Vertices: one per key (neighbouring tiles computed their shared halo cells identically), in
// key order; triangles in edge order (orders are unique: an edge belongs to one tile). Both
// orders are independent of the tiling. Here each tile's arrays are put in order (one tile's
// repeated keys dropped); indexedMesh merges them as it goes (parallel_merge.h).
void sortTiles(TiledContour* c, Progress& progress) {
  parallelFor(0, int64_t(c->tiles.size()), 1, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) sortTile(&c->tiles[size_t(i)]);
  });
  progress.check();
  if (c->tiles.size() == 1) {
    auto& v = c->tiles[0].vertices;
    v.erase(
        std::unique(v.begin(), v.end(),
                    [](const ContourVertex& a, const ContourVertex& b) { return a.key == b.key; }),
        v.end());
  }
}

// The index of a vertex key among the merged vertices' keys (sorted): a table of where each
// bucket of cell keys starts, then a search within the bucket (a few vertices), where a binary
// search over all vertices took most of the merge. Face-segment keys (the top bit) sort after
// every cell key and are few: searched among themselves.
class KeyIndex {
 public:
  static constexpr uint32_t kMissing = 0xffffffffu;

  explicit KeyIndex(const std::vector<uint64_t>& keys) : keys_(keys) {
    constexpr uint64_t kFaceBit = uint64_t(1) << 63;
    faceBegin_ = size_t(std::partition_point(keys.begin(), keys.end(),
                                             [](uint64_t k) { return (k & kFaceBit) == 0; }) -
                        keys.begin());
    if (faceBegin_ == 0) return;
    lo_ = keys[0];
    const uint64_t span = keys[faceBegin_ - 1] - lo_;
    size_t buckets = 1;
    while (buckets < faceBegin_) buckets *= 2;
    while ((span >> shift_) >= buckets) ++shift_;
    // start_[b]: the first vertex whose bucket is b or later. Keys are sorted, so vertex i
    // starts the buckets after its predecessor's up to its own: each written once, in parallel.
    start_.resize(buckets + 1);
    const auto bucketOf = [&](size_t i) { return size_t((keys[i] - lo_) >> shift_); };
    parallelFor(0, int64_t(faceBegin_), 1 << 16, [&](int64_t first, int64_t last) {
      for (int64_t i = first; i < last; ++i) {
        const size_t bucket = bucketOf(size_t(i));
        for (size_t b = i == 0 ? 0 : bucketOf(size_t(i) - 1) + 1; b <= bucket; ++b)
          start_[b] = uint32_t(i);
      }
    });
    const size_t lastBucket = bucketOf(faceBegin_ - 1);
    parallelFor(int64_t(lastBucket) + 1, int64_t(buckets) + 1, 1 << 18,
                [&](int64_t first, int64_t last) {
                  for (int64_t b = first; b < last; ++b) start_[size_t(b)] = uint32_t(faceBegin_);
                });
  }

  uint32_t find(uint64_t key) const {
    size_t first = faceBegin_, last = keys_.size();
    if (!(key >> 63)) {
      if (faceBegin_ == 0 || key < lo_) return kMissing;
      const uint64_t bucket = (key - lo_) >> shift_;
      if (bucket + 1 >= start_.size()) return kMissing;
      first = start_[size_t(bucket)];
      last = start_[size_t(bucket) + 1];
    }
    const auto it =
        std::lower_bound(keys_.begin() + int64_t(first), keys_.begin() + int64_t(last), key);
    if (it == keys_.begin() + int64_t(last) || *it != key) return kMissing;
    return uint32_t(it - keys_.begin());
  }

 private:
  const std::vector<uint64_t>& keys_;
  size_t faceBegin_ = 0;  // cell keys before, face-segment keys from here
  uint64_t lo_ = 0;       // the smallest cell key
  int shift_ = 0;         // bucket = (key - lo_) >> shift_
  std::vector<uint32_t> start_;
};

// The indexed mesh in scene units, each triangle tagged with its leaf: the tiles' triangles
// taken in merged (edge) order straight into the mesh's arrays, then released.
ExportMesh indexedMesh(const Scene& scene, const Grid& grid, TiledContour& c, ContourReport& r,
                       std::vector<uint8_t>* resolved) {
  ExportMesh out;
  out.unit = scene.settings.unit;
  collectLeafStyles(scene.root, &out.leaves);
  // An open mesh's rays through its holes are left empty (normalizeLeafRay), so no node of its
  // inside has all three rays agreeing: the speck rule (drop_specks.h) would take all of it for
  // an artefact, and did (an open cube beside another part vanished from the export, which the
  // preview showed solid: an artist's test). Its triangles count as resolved; only the size
  // rule applies to them.
  std::vector<uint32_t> openLeaves;
  collectOpenLeaves(scene.root, &openLeaves);
  std::sort(openLeaves.begin(), openLeaves.end());
  const auto resolvedBits = [&openLeaves](const ContourTriangle& t) {
    if (openLeaves.empty() || !std::binary_search(openLeaves.begin(), openLeaves.end(), t.leaf))
      return t.resolved;
    return uint8_t(t.resolved | kInsideResolved | kOutsideResolved);
  };
  {
    // The tiles' vertices in merged order: positions into the mesh, keys kept; then released.
    // One tile's are in order already (sortTiles); several tiles share their halo's keys.
    std::vector<SortedRun<ContourVertex>> runs;
    for (const TileContour& t : c.tiles) runs.push_back({t.vertices.data(), t.vertices.size()});
    const RunMerge vertices(
        runs, [](const ContourVertex& v) { return v.key; }, c.tiles.size() > 1);
    out.mesh.positions.resize(vertices.size());
    c.keys.resize(vertices.size());
    std::atomic<double> maxPlane{0.0};  // a maximum: the same in any order
    vertices.each([&](size_t i, const ContourVertex& v) {
      out.mesh.positions[i] =
          grid.origin + grid.h * glm::dvec3(v.position[0], v.position[1], v.position[2]);
      c.keys[i] = v.key;
      const double d = v.planeDistance * grid.h;
      double seen = maxPlane.load(std::memory_order_relaxed);
      while (d > seen && !maxPlane.compare_exchange_weak(seen, d)) {
      }
    });
    r.maxPlaneDistance = std::max(r.maxPlaneDistance, maxPlane.load());
    for (TileContour& t : c.tiles) t.vertices = HostArray<ContourVertex>();
  }
  std::vector<SortedRun<ContourTriangle>> runs;
  for (const TileContour& t : c.tiles) runs.push_back({t.triangles.data(), t.triangles.size()});
  const RunMerge triangles(
      runs, [](const ContourTriangle& t) { return t.order; }, false);
  out.mesh.triangles.resize(triangles.size());
  out.triangleLeaf.resize(triangles.size());
  resolved->resize(triangles.size());
  const KeyIndex keys(c.keys);
  auto indexOf = [&](uint64_t key) {
    const uint32_t index = keys.find(key);
    if (index == KeyIndex::kMissing)
      throw Error("internal: a triangle refers to a vertex no tile produced");
    return index;
  };
  // The keys found last, by a hash of the key, in each stretch of triangles a worker visits:
  // triangles in edge order share most corners with the few before them, and a hit costs one
  // compare where the index costs a search. Each entry is a true (key, index) pair from its
  // first use on.
  constexpr size_t kRecent = 256;
  struct Recent {
    uint64_t key[kRecent];
    uint32_t index[kRecent];
    bool filled = false;
  };
  triangles.eachWith<Recent>([&](Recent& recent, size_t i, const ContourTriangle& t) {
    const auto cachedIndexOf = [&](uint64_t key) {
      if (!recent.filled) {
        std::fill(recent.key, recent.key + kRecent, key);
        std::fill(recent.index, recent.index + kRecent, indexOf(key));
        recent.filled = true;
      }
      const size_t slot = size_t((key ^ (key >> 7) ^ (key >> 19)) & (kRecent - 1));
      if (recent.key[slot] != key) {
        recent.key[slot] = key;
        recent.index[slot] = indexOf(key);
      }
      return recent.index[slot];
    };
    out.mesh.triangles[i] = {cachedIndexOf(t.vertex[0]), cachedIndexOf(t.vertex[1]),
                             cachedIndexOf(t.vertex[2])};
    out.triangleLeaf[i] = t.leaf;
    (*resolved)[i] = resolvedBits(t);
  });
  c.tiles.clear();
  c.tiles.shrink_to_fit();
  // Every leaf the triangles name has a style: the leaves met, gathered per chunk (neighbouring
  // triangles mostly share a leaf).
  constexpr int64_t kChunk = 1 << 18;
  const int64_t count = int64_t(out.triangleLeaf.size());
  std::vector<std::vector<uint32_t>> met(size_t((count + kChunk - 1) / kChunk));
  parallelFor(0, int64_t(met.size()), 1, [&](int64_t b, int64_t e) {
    for (int64_t chunk = b; chunk < e; ++chunk) {
      uint32_t previous = 0xffffffffu;
      std::vector<uint32_t>& leaves = met[size_t(chunk)];
      for (int64_t t = chunk * kChunk; t < std::min(count, (chunk + 1) * kChunk); ++t) {
        const uint32_t leaf = out.triangleLeaf[size_t(t)];
        if (leaf == previous) continue;
        previous = leaf;
        leaves.push_back(leaf);
      }
      std::sort(leaves.begin(), leaves.end());
      leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
    }
  });
  for (const std::vector<uint32_t>& leaves : met)
    for (uint32_t leaf : leaves)
      if (!out.leaves.count(leaf)) out.leaves[leaf] = LeafStyle{"unknown", glm::vec3(0.8f)};
  return out;
}

}  // namespace

glm::dvec3 grownTileCells(const Grid& grid, int tileCells, int halo) {
  return grownTileCells(grid, glm::ivec3(tileCells), halo);
}

glm::dvec3 grownTileCells(const Grid& grid, const glm::ivec3& size, int halo) {
  glm::dvec3 cells;
  for (int a = 0; a < 3; ++a)
    cells[a] = double(std::min(int64_t(size[a]) + 2 * int64_t(halo), int64_t(grid.cells[a])));
  return cells;
}

int exportTileCells(const Grid& grid, uint64_t memoryBytes, int halo, uint64_t offsetBytesPerNode) {
  const uint64_t perNode = halo > 0 ? offsetBytesPerNode : kContourBytesPerNode;
  const int longest = std::max({grid.cells.x, grid.cells.y, grid.cells.z, 8});
  for (int parts = 1;; ++parts) {
    const int tile = std::max(8, (longest + parts - 1) / parts);
    // The evaluation window, with the contour's cell of halo on each side (+ 2 cells, + 3
    // nodes).
    const glm::dvec3 window = grownTileCells(grid, tile, halo);
    const double cells = (window.x + 2) * (window.y + 2) * (window.z + 2);
    const double nodes = (window.x + 3) * (window.y + 3) * (window.z + 3);
    const bool indexable = halo == 0 || cells <= double(UINT32_MAX);
    const bool fits =
        memoryBytes == 0 ? tile <= 256 : nodes * double(perNode) <= double(memoryBytes / 4);
    if (tile <= kMaxTileCells && indexable && fits) return tile;
    // With a halo, tiles smaller than it barely shrink the window (at least 3 halos wide) and
    // multiply the evaluations: none fits.
    if (halo > 0 && tile <= std::max(8, halo)) return 0;
    if (tile == 8) return indexable ? 8 : 0;
  }
}

void addWarnings(const std::vector<std::string>& from, ContourReport* into) {
  for (const std::string& w : from)
    if (std::find(into->warnings.begin(), into->warnings.end(), w) == into->warnings.end())
      into->warnings.push_back(w);
}

void addTileCounts(const ContourReport& from, ContourReport* into) {
  into->surfels += from.surfels;
  into->tileLdiBytes = std::max(into->tileLdiBytes, from.tileLdiBytes);
  into->synthesizedCrossings += from.synthesizedCrossings;
  into->signDisagreements += from.signDisagreements;
  addWarnings(from.warnings, into);
}

EvaluationWindow evaluationWindow(const Grid& grid, int halo, const glm::ivec3& begin,
                                  const glm::ivec3& end) {
  const TileWindow window = tileWindow(begin, end, grid.cells);
  EvaluationWindow w;
  w.first = glm::max(window.first - halo, glm::ivec3(0));
  w.end = glm::min(window.first + window.cells + halo, grid.cells);
  return w;
}

double ExportTiling::evaluatedNodes() const {
  double nodes = 0.0;
  for (int t = 0; t < count(); ++t) {
    const EvaluationWindow w = evaluationWindow(grid, halo, begin(t), end(t));
    const glm::dvec3 n = glm::dvec3(w.end - w.first) + 1.0;
    nodes += n.x * n.y * n.z;
  }
  return nodes;
}

int ExportTiling::count() const {
  return counts.x * counts.y * counts.z;
}

glm::ivec3 ExportTiling::begin(int tile) const {
  return glm::ivec3(tile % counts.x, (tile / counts.x) % counts.y, tile / (counts.x * counts.y)) *
         size;
}

glm::ivec3 ExportTiling::end(int tile) const {
  return glm::min(begin(tile) + size, grid.cells);
}

ExportTiling exportTiling(const Scene& scene, const ContourOptions& options, uint64_t memoryBytes,
                          uint64_t offsetBytesPerNode) {
  ExportTiling t;
  t.grid = Evaluator::gridFor(scene, options.resolution);
  const Grid& grid = t.grid;
  t.halo = modifierHaloCells(scene.root, grid.h);
  t.tileCells = options.tileCells > 0
                    ? options.tileCells
                    : exportTileCells(grid, memoryBytes, t.halo, offsetBytesPerNode);
  if (t.tileCells == 0)
    throw Error("offset, shell, round and fillet nodes read " + std::to_string(t.halo) +
                " cells around each point at this resolution (their amounts, nested ones "
                "added up): no tile's window grown by that fits in a quarter of the " +
                std::to_string(memoryBytes >> 20) +
                " MiB the backend has free. Lower --resolution or the amounts");
  return exportTilingOfSize(scene, options, glm::ivec3(t.tileCells));
}

ExportTiling exportTilingOfSize(const Scene& scene, const ContourOptions& options,
                                const glm::ivec3& size) {
  ExportTiling t;
  t.grid = Evaluator::gridFor(scene, options.resolution);
  const Grid& grid = t.grid;
  t.halo = modifierHaloCells(scene.root, grid.h);
  t.size = size;
  t.tileCells = size.x == size.y && size.y == size.z ? size.x : size.z;
  if (t.halo > 0) {
    // The grown window's cells, within 2^32 (asked for with --tile as well).
    const glm::dvec3 window = grownTileCells(grid, size, t.halo);
    if ((window.x + 2) * (window.y + 2) * (window.z + 2) > double(UINT32_MAX))
      throw Error("a tile of " + std::to_string(std::max({size.x, size.y, size.z})) +
                  " cells grown by the modifiers' " + std::to_string(t.halo) +
                  " cells a side holds more than 2^32 cells: use a "
                  "smaller --tile");
  }
  t.counts = tileCounts(grid, size);
  return t;
}

void contourTiles(const Scene& scene, Evaluator& evaluator, const ExportTiling& tiling,
                  const std::function<bool(int)>& mine, Progress& progress, ContourReport& r,
                  std::vector<TileContour>* out, const std::function<void(int)>& afterTile) {
  r.grid = tiling.grid;
  r.tileCells = tiling.tileCells;
  r.tiles = tiling.count();
  int done = 0, share = 0;
  // The node planes kept from tile to tile are the backend's until the last tile is done.
  struct ReleaseContourArrays {
    Backend& backend;
    ~ReleaseContourArrays() { backend.releaseContourArrays(); }
  } release{evaluator.backend()};
  Grid lastEvaluated;  // none yet (no tile's grid has zero cells)
  lastEvaluated.cells = glm::ivec3(0);
  if (!afterTile)
    for (int t = 0; t < tiling.count(); ++t) share += !mine || mine(t) ? 1 : 0;
  for (int t = 0; t < tiling.count(); ++t) {
    if (mine && !mine(t)) continue;
    // Tiles one after the other: after the first (whose evaluation is the stage "evaluate"), a
    // tile's own stages move the bar of "export" within the tile's share (its evaluation to
    // 80%, then its contour), never back, where each tile's "evaluate" restarted from 0 and a
    // long one (a modifier's) held the bar still.
    double tileAt = 0.0;
    Progress tileProgress(&progress, [&](const std::string& stage, double f) {
      f = std::clamp(f, 0.0, 1.0);
      tileAt = std::max(tileAt, stage == "evaluate" ? 0.8 * f : 0.8 + 0.2 * f);
      progress.report("export", (double(done) + tileAt) / double(share));
    });
    const bool mapped = !afterTile && tiling.count() > 1 && done > 0;
    contourOneTile(scene, evaluator, tiling.grid, tiling.halo, tiling.begin(t), tiling.end(t),
                   mapped ? tileProgress : progress, r, out, &lastEvaluated);
    ++done;
    if (afterTile)
      afterTile(t);
    else
      progress.report("export", double(done) / share);
  }
}

Error emptyResultError(const std::string& path, const ContourReport& r) {
  std::string why;
  for (const std::string& w : r.warnings) why += (why.empty() ? "" : "; ") + w;
  if (why.empty())
    why =
        "its parts are hidden, cut away, do not overlap where they intersect, or are "
        "thinner than a cell at this resolution";
  return Error("the result is empty, so nothing was written to " + path + ": " + why);
}

MergedTiles mergeTiles(const Scene& scene, std::vector<TileContour> tiles, Progress& progress,
                       ContourReport& r, double* sortSeconds) {
  TiledContour contour;
  contour.tiles = std::move(tiles);
  Stopwatch sort;
  sortTiles(&contour, progress);
  if (sortSeconds) *sortSeconds = sort.seconds();
  MergedTiles out;
  out.mesh = indexedMesh(scene, r.grid, contour, r, &out.resolved);
  out.keys = std::move(contour.keys);
  return out;
}

ExportMesh meshFromTiles(const Scene& scene, std::vector<TileContour> tiles, Progress& progress,
                         ContourReport& r) {
  const Grid& grid = r.grid;
  // Timed step by step (the report's merge_steps): what a pipelined merge would overlap.
  Stopwatch merge;
  double sortSeconds = 0.0;
  // Its steps' shares of the bar: about their shares of the time (the report's merge_steps on
  // the boolean set: sort 0.24, index 0.34, components 0.09, unfold 0.21, specks 0.09 s).
  progress.report("merge", 0.0);
  MergedTiles merged = mergeTiles(scene, std::move(tiles), progress, r, &sortSeconds);
  progress.report("merge", 0.6);
  r.mergeSteps.push_back({"sort", sortSeconds});
  r.mergeSteps.push_back({"index", merge.seconds() - sortSeconds});
  ExportMesh out = std::move(merged.mesh);
  std::vector<uint8_t>& resolved = merged.resolved;
  // Components once, for both (unfolding moves vertices, not triangles).
  Stopwatch step;
  const std::vector<uint32_t> roots = vertexComponentRoots(out.mesh);
  r.mergeSteps.push_back({"components", step.seconds()});
  progress.report("merge", 0.7);
  step.restart();
  r.unfoldedShells = unfoldInvertedShells(grid, merged.keys, roots, &out.mesh);
  r.mergeSteps.push_back({"unfold", step.seconds()});
  progress.report("merge", 0.9);
  step.restart();
  r.droppedSpecks = dropUnresolvedSpecks(&out, &resolved, grid.h, &roots);
  r.mergeSteps.push_back({"specks", step.seconds()});
  progress.report("merge", 1.0);
  r.mergeSeconds = merge.seconds();
  r.deviationBound = std::sqrt(3.0) * grid.h;
  r.peakBytes = peakResidentBytes();
  return out;
}

ExportMesh contourScene(const Scene& scene, Evaluator& evaluator, const ContourOptions& options,
                        Progress& progress, ContourReport* report) {
  ContourReport local;
  ContourReport& r = report ? *report : local;
  r = ContourReport();
  const Backend& backend = evaluator.backend();
  const ExportTiling tiling =
      exportTiling(scene, options, backend.memoryAvailable(), backend.offsetBytesPerNode());
  std::vector<TileContour> tiles;
  contourTiles(scene, evaluator, tiling, {}, progress, r, &tiles);
  return meshFromTiles(scene, std::move(tiles), progress, r);
}

}  // namespace strata
