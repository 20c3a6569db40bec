#include "engine/geometry/mesh_world_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <unordered_map>

namespace strata {
namespace {

// Meshes with fewer vertices are scanned: their scan costs less than a tree's upkeep.
constexpr size_t kTreeMinPoints = 2048;
// A mesh's first bounds are scanned, its tree built when they are asked again and again: a
// command that asks a mesh's bounds twice (its grid, then its sampling) or a few copies' does not
// pay for a tree (30-40 scans' time to build), an editor or a pattern's many copies do.
constexpr int kScansBeforeTree = 16;
constexpr uint32_t kLeafPoints = 16;

// One vertex placed in the world: the same arithmetic for the scan and the tree's search, so
// that both find the same doubles (the build compiles with -ffp-contract=off).
glm::dvec3 placed(const glm::dmat4& world, const glm::dvec3& p) {
  return glm::dvec3(world * glm::dvec4(p, 1.0));
}

bool finiteMatrix(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// Median splits of the vertices by the longest side of their box, down to leaves of
// kLeafPoints; each node keeps the box of its vertices (in the mesh's frame). Holds vertex
// indices, not copies: the search reads the mesh's own positions.
class VertexTree {
 public:
  explicit VertexTree(const std::vector<glm::dvec3>& points) {
    for (const glm::dvec3& p : points) {
      usable_ = usable_ && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      maxAbs_ = glm::max(maxAbs_, glm::abs(p));
    }
    if (!usable_ || points.empty()) return;
    // The splits reorder copies of the points (contiguous: faster than indices into the
    // mesh); only their order is kept.
    struct Item {
      glm::dvec3 p;
      uint32_t index;
    };
    std::vector<Item> items(points.size());
    for (uint32_t i = 0; i < items.size(); ++i) items[i] = Item{points[i], i};
    // Top down, each node split at the median of the longest side of a box that holds its
    // points (its parent's, cut at the parent's median: no pass over the points), then each
    // node's own box bottom up (children come after their parent in nodes_).
    struct Work {
      uint32_t node, begin, end;
      Bounds box;
    };
    nodes_.reserve(2 * points.size() / kLeafPoints + 2);
    nodes_.emplace_back();
    Bounds all;
    for (const glm::dvec3& p : points) all.include(p);
    std::vector<Work> work{{0, 0, uint32_t(points.size()), all}};
    while (!work.empty()) {
      const Work w = work.back();
      work.pop_back();
      const glm::dvec3 size = w.box.size();
      if (w.end - w.begin <= kLeafPoints || (size.x <= 0.0 && size.y <= 0.0 && size.z <= 0.0)) {
        nodes_[w.node].first = w.begin;
        nodes_[w.node].count = w.end - w.begin;
        continue;
      }
      const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
      const uint32_t mid = w.begin + (w.end - w.begin) / 2;
      std::nth_element(items.begin() + w.begin, items.begin() + mid, items.begin() + w.end,
                       [axis](const Item& a, const Item& b) { return a.p[axis] < b.p[axis]; });
      const double cut = items[mid].p[axis];
      const uint32_t children = uint32_t(nodes_.size());
      nodes_.emplace_back();
      nodes_.emplace_back();
      nodes_[w.node].first = children;
      nodes_[w.node].count = 0;
      Work left{children, w.begin, mid, w.box}, right{children + 1, mid, w.end, w.box};
      left.box.max[axis] = cut;
      right.box.min[axis] = cut;
      work.push_back(left);
      work.push_back(right);
    }
    order_.resize(items.size());
    for (size_t k = 0; k < items.size(); ++k) order_[k] = items[k].index;
    for (size_t n = nodes_.size(); n-- > 0;) {
      Node& node = nodes_[n];
      node.box = Bounds();
      if (node.count > 0) {
        for (uint32_t k = node.first; k < node.first + node.count; ++k)
          node.box.include(items[k].p);
      } else {
        node.box.include(nodes_[node.first].box);
        node.box.include(nodes_[node.first + 1].box);
      }
    }
  }

  // The tree answers for points with finite coordinates only (the scan's min and max of a NaN
  // depend on the order of the points).
  bool usable() const { return usable_ && !nodes_.empty(); }

  // max over the points of sign * placed(world, p)[axis] (sign +1 or -1), the same double the
  // scan finds; false where the transform's numbers are too large for the search's bound.
  bool extreme(const std::vector<glm::dvec3>& points, const glm::dmat4& world, int axis,
               double sign, double* out) const {
    const glm::dvec3 row(world[0][axis], world[1][axis], world[2][axis]);
    const double shift = world[3][axis];
    // Every value below (a vertex's, a box corner's) sums terms no larger than `scale`, so its
    // rounding is within 8e-16 * scale of the exact value: a box whose corner bound stays below
    // the best vertex found by more than 1e-12 * scale holds no vertex that could beat it.
    const double scale = std::abs(row.x) * maxAbs_.x + std::abs(row.y) * maxAbs_.y +
                         std::abs(row.z) * maxAbs_.z + std::abs(shift);
    if (!std::isfinite(scale) || scale > 1e300) return false;
    const double slack = 1e-12 * scale;
    const glm::dvec3 weight = sign * row;
    auto upper = [&](const Bounds& b) {
      double v = sign * shift;
      for (int i = 0; i < 3; ++i) v += weight[i] * (weight[i] > 0.0 ? b.max[i] : b.min[i]);
      return v;
    };
    double best = -std::numeric_limits<double>::infinity();
    // Median splits keep the depth at most log2(points) + 1 < 40: one pending sibling a level.
    uint32_t stack[96];
    int size = 0;
    stack[size++] = 0;
    while (size > 0) {
      const Node& node = nodes_[stack[--size]];
      if (upper(node.box) + slack < best) continue;
      if (node.count > 0) {
        for (uint32_t k = node.first; k < node.first + node.count; ++k)
          best = std::max(best, sign * placed(world, points[order_[k]])[axis]);
        continue;
      }
      const bool leftFirst = upper(nodes_[node.first].box) >= upper(nodes_[node.first + 1].box);
      stack[size++] = leftFirst ? node.first + 1 : node.first;  // searched second
      stack[size++] = leftFirst ? node.first : node.first + 1;  // searched first
    }
    *out = sign * best;
    return true;
  }

 private:
  struct Node {
    Bounds box;
    uint32_t first = 0;  // a leaf's first index into order_, else its first child
    uint32_t count = 0;  // a leaf's vertices; 0 for an inner node
  };
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
  glm::dvec3 maxAbs_{0.0};
  bool usable_ = true;
};

// The trees of the meshes alive, keyed by address; an entry whose mesh died (or whose address
// a new mesh took) is rebuilt or dropped.
struct TreeCache {
  struct Entry {
    std::weak_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const VertexTree> tree;  // null until built
    int scans = 0;                           // bounds scanned while there was no tree
  };
  std::mutex mutex;
  std::unordered_map<const TriangleMesh*, Entry> entries;
};

TreeCache& treeCache() {
  static TreeCache* cache = new TreeCache;  // never destroyed: asked from threads at exit
  return *cache;
}

bool sameOwner(const std::weak_ptr<const TriangleMesh>& a,
               const std::shared_ptr<const TriangleMesh>& b) {
  return !a.owner_before(b) && !b.owner_before(a);
}

// The mesh's tree; null while the mesh has been scanned fewer than kScansBeforeTree times
// (counting this call) unless `now`.
std::shared_ptr<const VertexTree> treeFor(const std::shared_ptr<const TriangleMesh>& mesh,
                                          bool now) {
  TreeCache& cache = treeCache();
  {
    std::lock_guard<std::mutex> lock(cache.mutex);
    auto it = cache.entries.find(mesh.get());
    if (it == cache.entries.end() || !sameOwner(it->second.mesh, mesh)) {
      for (auto e = cache.entries.begin(); e != cache.entries.end();)
        e = e->second.mesh.expired() ? cache.entries.erase(e) : std::next(e);
      it = cache.entries.insert_or_assign(mesh.get(), TreeCache::Entry{mesh, nullptr, 0}).first;
    }
    if (it->second.tree) return it->second.tree;
    if (!now && it->second.scans++ < kScansBeforeTree) return nullptr;
  }
  auto tree = std::make_shared<const VertexTree>(mesh->positions);  // outside the lock
  std::lock_guard<std::mutex> lock(cache.mutex);
  auto it = cache.entries.find(mesh.get());
  if (it != cache.entries.end() && sameOwner(it->second.mesh, mesh)) it->second.tree = tree;
  return tree;
}

}  // namespace

Bounds transformedBounds(const std::vector<glm::dvec3>& points, const glm::dmat4& world) {
  Bounds b;
  for (const glm::dvec3& p : points) b.include(placed(world, p));
  return b;
}

Bounds meshWorldBounds(const std::shared_ptr<const TriangleMesh>& mesh, const glm::dmat4& world) {
  if (!mesh || mesh->positions.empty()) return Bounds();
  if (mesh->positions.size() < kTreeMinPoints || !finiteMatrix(world))
    return transformedBounds(mesh->positions, world);
  const std::shared_ptr<const VertexTree> tree = treeFor(mesh, false);
  if (!tree || !tree->usable()) return transformedBounds(mesh->positions, world);
  Bounds b;
  for (int a = 0; a < 3; ++a)
    if (!tree->extreme(mesh->positions, world, a, 1.0, &b.max[a]) ||
        !tree->extreme(mesh->positions, world, a, -1.0, &b.min[a]))
      return transformedBounds(mesh->positions, world);
  return b;
}

void prepareMeshWorldBounds(const std::shared_ptr<const TriangleMesh>& mesh) {
  if (mesh && mesh->positions.size() >= kTreeMinPoints) treeFor(mesh, true);
}

}  // namespace strata
