// See check_streamed.h.
#include "engine/export/check_streamed.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/hash.h"
#include "engine/util/union_find.h"
#include "engine/util/window_hash_map.h"

namespace strata {
namespace {

struct PositionKey {
  uint64_t x, y, z;
  bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
  uint64_t operator()(const PositionKey& k) const {
    return avalanche64(k.x ^ avalanche64(k.y ^ avalanche64(k.z)));
  }
};

// A few values inline, more on the heap: most vertices have a handful of edges and one
// component around them.
template <typename T, size_t N>
class SmallList {
 public:
  size_t size() const { return size_ <= N ? size_ : more_.size(); }
  T& operator[](size_t i) { return size_ <= N ? inline_[i] : more_[i]; }
  void push_back(const T& x) {
    if (size_ < N) {
      inline_[size_++] = x;
      return;
    }
    if (size_ == N) more_.assign(inline_.begin(), inline_.end());
    more_.push_back(x);
    size_ = N + 1;
  }

 private:
  std::array<T, N> inline_{};
  std::vector<T> more_;
  size_t size_ = 0;  // N + 1: the values are in more_
};

// checkMesh's counts over a stream of facets in the file's order (check_streamed.h). Vertices
// are numbered as they first come and kept in a queue by number (they leave it roughly in that
// order, layer by layer); each edge is kept by its smaller-numbered end, counted when that end
// leaves (no later facet can use the edge then).
class WindowCheck {
 public:
  WindowCheck(const Grid& grid, size_t triangles, const glm::dvec3& lo, const glm::dvec3& hi)
      : grid_(grid), sets_(triangles), chi_(triangles, 1), measures_(lo, hi) {}

  void add(const glm::dvec3* c) {
    if (next_ >= sets_.parent.size()) throw Error("the file holds more facets than its count says");
    const uint32_t t = uint32_t(next_++);
    uint32_t w[3];
    int highest = INT_MIN;
    for (int k = 0; k < 3; ++k) {
      w[k] = weld(c[k]);
      highest = std::max(highest, vertex(w[k]).layer);
    }
    const bool repeated = w[0] == w[1] || w[1] == w[2] || w[0] == w[2];
    measures_.add(c[0], c[1], c[2], repeated);
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = w[k], b = w[(k + 1) % 3];
      if (a == b) continue;  // checkMesh leaves such edges out
      Vertex& owner = vertex(std::min(a, b));
      const uint32_t other = std::max(a, b);
      Edge* e = nullptr;
      for (size_t i = 0; i < owner.edges.size() && !e; ++i)
        if (owner.edges[i].other == other) e = &owner.edges[i];
      if (!e) {
        owner.edges.push_back(Edge{other, t, 0, a < b, false});
        e = &owner.edges[owner.edges.size() - 1];
      } else {
        if (e->count == 1) e->forward1 = a < b;
        sets_.unite(e->first, t);
      }
      ++e->count;
    }
    // Each vertex keeps a facet of each component around it: t where it is in none of theirs
    // yet (components only ever join, so a facet joined to a kept one stays redundant).
    const uint32_t root = sets_.find(t);
    for (int k = 0; k < 3; ++k) {
      Vertex& x = vertex(w[k]);
      bool known = false;
      for (size_t i = 0; i < x.reps.size() && !known; ++i) known = sets_.find(x.reps[i]) == root;
      if (!known) x.reps.push_back(t);
    }
    // Facets come in the order of their edges' z layers, and a facet's corners lie at most a
    // layer above its edge's: no later facet reaches below this.
    if (highest - 1 > front_) {
      front_ = highest - 1;
      evictBelow(front_ - kWindowLayers);
    }
  }

  MeshCheck finish() {
    if (next_ != sets_.parent.size())
      throw Error("the file holds fewer facets than its count says");
    evictBelow(INT_MAX);
    MeshCheck c;
    c.vertices = welded_;
    c.triangles = sets_.parent.size();
    c.boundaryEdges = boundary_;
    c.nonManifoldEdges = nonManifold_;
    c.misorientedEdges = misoriented_;
    measures_.finish(&c);
    // Each component's V - E + F: the facets' shares added up by root.
    std::map<uint32_t, long long> chi;
    long long* last = nullptr;  // neighbouring facets mostly share a component
    uint32_t lastRoot = UINT32_MAX;
    for (size_t t = 0; t < sets_.parent.size(); ++t) {
      const uint32_t root = sets_.find(uint32_t(t));
      if (root != lastRoot) {
        last = &chi[root];
        lastRoot = root;
      }
      *last += chi_[t];
    }
    // Vertices counted once for each component around them when they left, where components
    // joined later: counted once per final component.
    for (const std::vector<uint32_t>& reps : shared_) {
      std::vector<uint32_t> roots;
      for (uint32_t t : reps) roots.push_back(sets_.find(t));
      std::sort(roots.begin(), roots.end());
      for (size_t i = 1; i < roots.size(); ++i)
        if (roots[i] == roots[i - 1]) chi[roots[i]] -= 1;
    }
    c.components = int(chi.size());
    if (!c.watertight() || sets_.parent.empty()) return c;
    int genus = 0;
    for (const auto& [root, sum] : chi) {
      const long long twiceGenus = 2 - sum;
      if (twiceGenus < 0 || twiceGenus % 2 != 0) return c;  // not a closed surface after all
      genus += int(twiceGenus / 2);
    }
    c.genus = genus;
    return c;
  }

 private:
  struct Edge {
    uint32_t other;  // its larger-numbered end
    uint32_t first;  // its first facet
    uint32_t count;  // half-edges
    bool forward0, forward1;
  };
  struct Vertex {
    PositionKey key{0, 0, 0};
    int layer = 0;
    bool gone = false;
    SmallList<Edge, 4> edges;     // to larger-numbered vertices
    SmallList<uint32_t, 2> reps;  // a facet of each component around it (usually one)
  };

  Vertex& vertex(uint32_t id) { return ring_[(head_ + (id - first_)) & (ring_.size() - 1)]; }

  int layerOf(double z) const {
    const double layer = std::floor((z - grid_.origin.z) / grid_.h);
    return int(std::clamp(layer, double(INT_MIN / 2), double(INT_MAX / 2)));
  }

  uint32_t weld(const glm::dvec3& p) {
    const PositionKey key{coordinateBits(p.x), coordinateBits(p.y), coordinateBits(p.z)};
    bool fresh = false;
    uint32_t* id = ids_.insert(key, &fresh);
    if (!fresh) return *id;
    *id = uint32_t(welded_++);
    const int layer = layerOf(p.z);
    if (count_ == ring_.size()) {  // full: twice the room, the live ones from the start
      std::vector<Vertex> grown(2 * ring_.size());
      for (size_t i = 0; i < count_; ++i)
        grown[i] = std::move(ring_[(head_ + i) & (ring_.size() - 1)]);
      ring_ = std::move(grown);
      head_ = 0;
    }
    Vertex& v = ring_[(head_ + count_++) & (ring_.size() - 1)];
    v = Vertex();
    v.key = key;
    v.layer = layer;
    vertexLayers_[layer].push_back(*id);
    return *id;
  }

  // The vertices of the layers below `layer`, which no later facet reaches, and the edges they
  // keep: counted, and let go.
  void evictBelow(int layer) {
    while (!vertexLayers_.empty() && vertexLayers_.begin()->first < layer) {
      for (uint32_t id : vertexLayers_.begin()->second) {
        Vertex& v = vertex(id);
        for (size_t i = 0; i < v.edges.size(); ++i) {
          const Edge& e = v.edges[i];
          if (e.count == 1) ++boundary_;
          if (e.count > 2) ++nonManifold_;
          if (e.count == 2 && e.forward0 == e.forward1) ++misoriented_;
          chi_[e.first] -= 1;  // E: for the component of its first facet
        }
        std::vector<uint32_t> reps;  // a facet per component around it now
        std::vector<uint32_t> roots;
        for (size_t i = 0; i < v.reps.size(); ++i) {
          const uint32_t r = sets_.find(v.reps[i]);
          if (std::find(roots.begin(), roots.end(), r) != roots.end()) continue;
          roots.push_back(r);
          reps.push_back(v.reps[i]);
          chi_[v.reps[i]] += 1;  // V: once for each component around it
        }
        if (reps.size() > 1) shared_.push_back(std::move(reps));
        ids_.erase(v.key);
        v = Vertex();
        v.gone = true;
      }
      vertexLayers_.erase(vertexLayers_.begin());
    }
    while (count_ > 0 && ring_[head_].gone) {
      head_ = (head_ + 1) & (ring_.size() - 1);
      --count_;
      ++first_;
    }
  }

  const Grid grid_;
  UnionFind sets_;            // over facets: edge-connected components
  std::vector<int32_t> chi_;  // per facet: its share of its component's V - E + F
  TriangleMeasures measures_;
  size_t next_ = 0;
  size_t welded_ = 0;
  int front_ = INT_MIN;
  WindowHashMap<PositionKey, uint32_t, PositionHash> ids_;
  // Vertices first_, first_ + 1, ..., count_ of them from ring_[head_] on (a power of two).
  std::vector<Vertex> ring_ = std::vector<Vertex>(1024);
  size_t head_ = 0, count_ = 0;
  uint32_t first_ = 0;
  std::map<int, std::vector<uint32_t>> vertexLayers_;
  std::vector<std::vector<uint32_t>> shared_;  // vertices between components: a facet of each
  size_t boundary_ = 0, nonManifold_ = 0, misoriented_ = 0;
};

}  // namespace

struct StreamedMeshCheck::State {
  State(const Grid& grid, size_t facets, const glm::dvec3& lo, const glm::dvec3& hi,
        const Progress& parent)
      : window(grid, facets, lo, hi), progress(&parent) {}
  WindowCheck window;
  Progress progress;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::vector<glm::dvec3>> blocks;
  bool ended = false;
  std::exception_ptr failure;
  MeshCheck result;
  std::thread thread;
};

StreamedMeshCheck::StreamedMeshCheck(const Grid& grid, size_t facets, const glm::dvec3& usedLo,
                                     const glm::dvec3& usedHi, const Progress& progress)
    : state_(std::make_unique<State>(grid, facets, usedLo, usedHi, progress)) {
  State* s = state_.get();
  s->thread = std::thread([s] {
    try {
      for (;;) {
        std::vector<glm::dvec3> block;
        {
          std::unique_lock<std::mutex> lock(s->mutex);
          s->changed.wait(lock, [s] { return !s->blocks.empty() || s->ended; });
          if (s->blocks.empty()) break;
          block = std::move(s->blocks.front());
          s->blocks.pop_front();
        }
        s->changed.notify_all();
        s->progress.check();
        for (size_t t = 0; 3 * t < block.size(); ++t) s->window.add(&block[3 * t]);
      }
      s->result = s->window.finish();
    } catch (...) {
      std::lock_guard<std::mutex> lock(s->mutex);
      s->failure = std::current_exception();
      s->blocks.clear();
    }
    s->changed.notify_all();
  });
}

StreamedMeshCheck::~StreamedMeshCheck() {
  state_->progress.cancel();
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->ended = true;
    state_->blocks.clear();
  }
  state_->changed.notify_all();
  if (state_->thread.joinable()) state_->thread.join();
}

void StreamedMeshCheck::add(std::vector<glm::dvec3> corners) {
  State& s = *state_;
  std::unique_lock<std::mutex> lock(s.mutex);
  s.changed.wait(lock, [&] { return s.blocks.size() < kQueuedBlocks || s.failure; });
  if (s.failure) return;  // finish() rethrows it
  s.blocks.push_back(std::move(corners));
  lock.unlock();
  s.changed.notify_all();
}

MeshCheck StreamedMeshCheck::finish() {
  State& s = *state_;
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    s.ended = true;
  }
  s.changed.notify_all();
  if (s.thread.joinable()) s.thread.join();
  if (s.failure) std::rethrow_exception(s.failure);
  return s.result;
}

WrittenCheck compareStreamedFile(const std::string& path, const MeshCheck& measured,
                                 const TriangleFingerprint& expected, Progress& progress) {
  WrittenCheck result;
  progress.report("check", 0.0);
  const InputLimitLifted ownFile;  // the file just written: no input limit refuses it
  result.fileDifference = fingerprintDifference(path, fingerprintFile(path, progress), expected);
  result.check =
      result.fileDifference.empty() ? measured : checkMesh(readMeshFileRaw(path), &progress);
  progress.report("check", 1.0);
  return result;
}

WrittenCheck checkStreamedStl(const std::string& path, const Grid& grid, const glm::dvec3& usedLo,
                              const glm::dvec3& usedHi, const TriangleFingerprint& expected,
                              Progress& progress) {
  WrittenCheck result;
  progress.report("check", 0.0);
  const InputLimitLifted ownFile;  // the file just written: no input limit refuses it
  TriangleFingerprint found;
  WindowCheck window(grid, expected.triangles, usedLo, usedHi);
  bool countMatches = true;
  const bool inPieces = visitFileTrianglesInOrder(
      path,
      [&](uint64_t first, const glm::dvec3* corners, size_t count) {
        for (size_t t = 0; t < count; ++t) {
          const glm::dvec3* c = corners + 3 * t;
          addToFingerprint(c[0], c[1], c[2], &found);
          if (first + t < expected.triangles)
            window.add(c);
          else
            countMatches = false;
        }
        progress.report("check", expected.triangles == 0
                                     ? 1.0
                                     : double(first + count) / double(expected.triangles));
      },
      &progress);
  if (!inPieces) found = fingerprintTriangles(readMeshFileVerbatim(path, nullptr, &progress));
  result.fileDifference = fingerprintDifference(path, found, expected);
  if (inPieces && countMatches && result.fileDifference.empty())
    result.check = window.finish();
  else
    result.check = checkMesh(readMeshFileRaw(path), &progress);
  progress.report("check", 1.0);
  return result;
}

}  // namespace strata
