// See check_streamed.h.
#include "engine/export/check_streamed.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <future>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/hash.h"
#include "engine/util/parallel_for.h"
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

// Half-edges of one edge: `count` of them, the first two's directions (forward: from the end the
// edge is kept at to the other), and a facet of theirs (global index).
struct HalfEdges {
  uint32_t first = 0;
  uint32_t count = 0;
  bool forward0 = false, forward1 = false;
};

// The grid's z layer of a height (clamped to stay far from int's ends).
int layerOf(const Grid& grid, double z) {
  const double layer = std::floor((z - grid.origin.z) / grid.h);
  return int(std::clamp(layer, double(INT_MIN / 2), double(INT_MAX / 2)));
}

// What a chunk hands on (check_streamed.h): its open vertices, each with a facet of each
// component around it in the chunk, and the half-edges of its edges between open vertices.
struct OpenVertex {
  PositionKey key;
  int layer;
  SmallList<uint32_t, 2> reps;
};
struct OpenEdge {
  PositionKey from, to;  // forward: from `from` to `to`
  HalfEdges halves;
};

// The counts of a check, summed over chunks and the window that joins them.
struct Counts {
  size_t vertices = 0, boundary = 0, nonManifold = 0, misoriented = 0;
  std::vector<std::vector<uint32_t>> shared;  // vertices between components: a facet of each
  void add(Counts&& o) {
    vertices += o.vertices;
    boundary += o.boundary;
    nonManifold += o.nonManifold;
    misoriented += o.misoriented;
    for (auto& s : o.shared) shared.push_back(std::move(s));
  }
};

// checkMesh's counts over vertices welded by position in a window of z layers. Vertices are
// numbered as they first come and kept in a queue by number (they leave it roughly in that
// order, layer by layer); each edge is kept by its smaller-numbered end and counted when that end
// leaves. A chunk's window (facets added) hands its open vertices on when they leave; the
// joining window (chunks' open vertices and edges added) counts every vertex itself.
//
// `sets` and `chi` (per facet: its share of its component's V - E + F) are the check's, over all
// facets; a chunk's window touches only its own facets' entries, the joining window those of
// chunks already done.
class Window {
 public:
  Window(UnionFind* sets, std::vector<int32_t>* chi) : sets_(*sets), chi_(*chi) {}

  // The vertex at `key` (numbered now where it is new; `openStart`: a new one may have been
  // used before this window's first facet).
  uint32_t weld(const PositionKey& key, int layer, bool openStart) {
    bool fresh = false;
    uint32_t* id = ids_.insert(key, &fresh);
    if (!fresh) return *id;
    *id = next_++;
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
    v.openStart = openStart;
    vertexLayers_[layer].push_back(*id);
    return *id;
  }

  // The vertex at `key`, which is here.
  uint32_t idOf(const PositionKey& key) {
    const uint32_t* id = ids_.find(key);
    if (!id) throw Error("internal: the streamed check lost an open vertex");
    return *id;
  }

  // Half-edges `h` of the edge from vertex a to vertex b (a != b).
  void addHalfEdges(uint32_t a, uint32_t b, HalfEdges h) {
    if (a > b) {
      std::swap(a, b);
      h.forward0 = !h.forward0;
      h.forward1 = !h.forward1;
    }
    Vertex& owner = vertex(a);
    Edge* e = nullptr;
    for (size_t i = 0; i < owner.edges.size() && !e; ++i)
      if (owner.edges[i].other == b) e = &owner.edges[i];
    if (!e) {
      owner.edges.push_back(Edge{b, h});
      return;
    }
    if (e->halves.count == 1) e->halves.forward1 = h.forward0;
    e->halves.count += h.count;
    sets_.unite(e->halves.first, h.first);
  }

  // A facet of a component around vertex `id` (kept where it is in none of theirs yet:
  // components only ever join, so a facet joined to a kept one stays redundant). `root`: the
  // facet's component now (sets.find(facet)).
  void addRep(uint32_t id, uint32_t facet, uint32_t root) {
    Vertex& x = vertex(id);
    for (size_t i = 0; i < x.reps.size(); ++i)
      if (sets_.find(x.reps[i]) == root) return;
    x.reps.push_back(facet);
  }

  // The vertices of the layers below `layer` and the edges they keep: counted and let go, or,
  // with `open` (a chunk's window), the open ones handed on to it. `atEnd`: the window's last
  // call (every vertex still here is open).
  void evictBelow(int layer, std::vector<OpenVertex>* openVertices,
                  std::vector<OpenEdge>* openEdges, bool atEnd = false) {
    while (!vertexLayers_.empty() && vertexLayers_.begin()->first < layer) {
      for (uint32_t id : vertexLayers_.begin()->second) evict(id, openVertices, openEdges, atEnd);
      vertexLayers_.erase(vertexLayers_.begin());
    }
    while (count_ > 0 && ring_[head_].gone) {
      head_ = (head_ + 1) & (ring_.size() - 1);
      --count_;
      ++first_;
    }
  }

  Counts& counts() { return counts_; }
  uint32_t rootOf(uint32_t facet) { return sets_.find(facet); }

 private:
  struct Edge {
    uint32_t other;  // its larger-numbered end
    HalfEdges halves;
  };
  struct Vertex {
    PositionKey key{0, 0, 0};
    int layer = 0;
    bool openStart = false;
    bool gone = false;            // let go (its key and openStart stay for its edges' owners)
    bool leftEarly = false;       // let go before the window's last call (a chunk's end)
    SmallList<Edge, 4> edges;     // to larger-numbered vertices
    SmallList<uint32_t, 2> reps;  // a facet of each component around it (usually one)
  };

  Vertex& vertex(uint32_t id) { return ring_[(head_ + (id - first_)) & (ring_.size() - 1)]; }

  void evict(uint32_t id, std::vector<OpenVertex>* openVertices, std::vector<OpenEdge>* openEdges,
             bool atEnd) {
    Vertex& v = vertex(id);
    // Open (a chunk's window): used before this window's first facet, or maybe after its last.
    const bool open = openVertices && (v.openStart || atEnd);
    for (size_t i = 0; i < v.edges.size(); ++i) {
      const Edge& e = v.edges[i];
      const Vertex& o = vertex(e.other);
      // An edge another chunk may also hold: both ends used before this chunk, or both after it.
      // Any other edge has all its half-edges here (an end used only here, or one end used only
      // before and the other only after: no other chunk holds both).
      if (open && ((v.openStart && o.openStart) || (atEnd && !o.leftEarly))) {
        openEdges->push_back(OpenEdge{v.key, o.key, e.halves});
        continue;
      }
      if (e.halves.count == 1) ++counts_.boundary;
      if (e.halves.count > 2) ++counts_.nonManifold;
      if (e.halves.count == 2 && e.halves.forward0 == e.halves.forward1) ++counts_.misoriented;
      chi_[e.halves.first] -= 1;  // E: for the component of its first facet
    }
    // A facet per component around it now (kept in members: no allocation per vertex).
    reps_.clear();
    roots_.clear();
    for (size_t i = 0; i < v.reps.size(); ++i) {
      const uint32_t r = sets_.find(v.reps[i]);
      if (std::find(roots_.begin(), roots_.end(), r) != roots_.end()) continue;
      roots_.push_back(r);
      reps_.push_back(v.reps[i]);
    }
    if (open) {
      openVertices->push_back(OpenVertex{v.key, v.layer, {}});
      for (uint32_t t : reps_) openVertices->back().reps.push_back(t);
    } else {
      ++counts_.vertices;
      for (uint32_t t : reps_) chi_[t] += 1;  // V: once for each component around it
      if (reps_.size() > 1) counts_.shared.push_back(reps_);
    }
    ids_.erase(v.key);
    const PositionKey key = v.key;
    const bool openStart = v.openStart;
    v = Vertex();
    v.key = key;
    v.openStart = openStart;
    v.gone = true;
    v.leftEarly = !atEnd;
  }

  UnionFind& sets_;
  std::vector<int32_t>& chi_;
  WindowHashMap<PositionKey, uint32_t, PositionHash> ids_;
  uint32_t next_ = 0;
  // Vertices first_, first_ + 1, ..., count_ of them from ring_[head_] on (a power of two).
  std::vector<Vertex> ring_ = std::vector<Vertex>(1024);
  size_t head_ = 0, count_ = 0;
  uint32_t first_ = 0;
  std::map<int, std::vector<uint32_t>> vertexLayers_;
  Counts counts_;
  std::vector<uint32_t> reps_, roots_;  // evict's
};

// Facets added, three corners each, in one of the two precisions a file stores (float32: STL;
// double: PLY).
struct CornerBlock {
  std::vector<glm::vec3> floats;
  std::vector<glm::dvec3> doubles;
  size_t facets() const { return (floats.size() + doubles.size()) / 3; }
};
std::vector<glm::vec3>& cornersOf(CornerBlock& b, const glm::vec3*) {
  return b.floats;
}
std::vector<glm::dvec3>& cornersOf(CornerBlock& b, const glm::dvec3*) {
  return b.doubles;
}

// What one chunk measured.
struct ChunkResult {
  ChunkResult(const glm::dvec3& lo, const glm::dvec3& hi) : measures(lo, hi) {}
  Counts counts;
  std::vector<OpenVertex> openVertices;
  std::vector<OpenEdge> openEdges;
  size_t facets = 0;
  int front = INT_MIN;  // the lowest edge layer its last facet may have
  TriangleMeasures measures;
};

// One chunk's measures: its facets added in the file's order, from facet `first` on.
// `openUpTo`: the highest layer of any corner before the chunk (its vertices up to that layer
// may have been used before it; INT_MIN for the first chunk).
class ChunkCheck {
 public:
  ChunkCheck(const Grid& grid, size_t first, int openUpTo, UnionFind* sets,
             std::vector<int32_t>* chi, const glm::dvec3& lo, const glm::dvec3& hi)
      : grid_(grid), r_(lo, hi), window_(sets, chi), next_(first), openUpTo_(openUpTo) {}

  // Corners as the file stores them: float32 (STL) or double (PLY).
  template <typename Corner>
  void add(const Corner* corners, size_t facets) {
    for (size_t t = 0; t < facets; ++t) {
      const uint32_t facet = uint32_t(next_++);
      glm::dvec3 c[3];
      uint32_t w[3];
      int highest = INT_MIN;
      for (int k = 0; k < 3; ++k) {
        c[k] = glm::dvec3(corners[3 * t + size_t(k)]);
        const int layer = layerOf(grid_, c[k].z);
        w[k] = window_.weld(
            PositionKey{coordinateBits(c[k].x), coordinateBits(c[k].y), coordinateBits(c[k].z)},
            layer, layer <= openUpTo_);
        highest = std::max(highest, layer);
      }
      r_.measures.add(c[0], c[1], c[2], w[0] == w[1] || w[1] == w[2] || w[0] == w[2]);
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = w[k], b = w[(k + 1) % 3];
        if (a != b) window_.addHalfEdges(a, b, HalfEdges{facet, 1, true, false});
      }
      const uint32_t root = window_.rootOf(facet);
      for (int k = 0; k < 3; ++k) window_.addRep(w[k], facet, root);
      // Facets come in the order of their edges' z layers, and a facet's corners lie at most a
      // layer above its edge's: no later facet reaches below this.
      if (highest - 1 > r_.front) {
        r_.front = highest - 1;
        window_.evictBelow(r_.front - kWindowLayers, &r_.openVertices, &r_.openEdges);
      }
    }
    r_.facets += facets;
  }

  ChunkResult finish() {
    window_.evictBelow(INT_MAX, &r_.openVertices, &r_.openEdges, true);
    r_.counts = std::move(window_.counts());
    return std::move(r_);
  }

 private:
  const Grid grid_;
  ChunkResult r_;
  Window window_;
  size_t next_;
  const int openUpTo_;
};

}  // namespace

// The facets arrive in blocks; they are cut into chunks, each taken by one worker thread as its
// first blocks arrive and measured as the rest come. The worker that finishes the next chunk to
// be joined joins it (and any finished after it) into the joining window, one worker at a time
// (`joiningNow`), so chunks are joined in order as they finish.
struct StreamedMeshCheck::State {
  State(const Grid& g, size_t facets, const glm::dvec3& l, const glm::dvec3& h,
        const Progress& parent, size_t chunk)
      : grid(g),
        facetCount(facets),
        lo(l),
        hi(h),
        chunkFacets(chunk),
        progress(&parent),
        sets(facets),
        chi(facets, 1),
        joining(&sets, &chi),
        measures(l, h) {}

  struct Chunk {
    size_t first;  // its first facet
    int openUpTo;  // ChunkCheck's
    std::deque<CornerBlock> blocks;
    size_t facets = 0;  // added so far
    bool complete = false;
  };

  const Grid grid;
  const size_t facetCount;
  const glm::dvec3 lo, hi;
  size_t chunkFacets;
  size_t maxHeldFacets = 0;  // add() waits while this many are held
  size_t maxUnjoined = 0;    // no chunk is taken while this many are taken and not joined
  Progress progress;
  UnionFind sets;            // over facets: edge-connected components
  std::vector<int32_t> chi;  // per facet: its share of its component's V - E + F

  std::mutex mutex;  // guards what follows up to the joining window
  std::condition_variable changed;
  std::deque<std::shared_ptr<Chunk>> waiting;  // not taken yet, in order
  std::shared_ptr<Chunk> filling;              // the chunk being added to (in `waiting` or taken)
  size_t added = 0;                            // facets added
  int highestLayer = INT_MIN;                  // of every corner added
  size_t held = 0;                             // facets added and not measured yet
  size_t unjoined = 0;                         // chunks taken and not joined yet
  std::map<size_t, ChunkResult> done;          // by first facet, not joined yet
  size_t nextToJoin = 0;                       // the first facet of the chunk joined next
  bool joiningNow = false;
  bool ended = false;
  std::exception_ptr failure;
  std::vector<std::thread> workers;

  // The joining window's, touched by one worker at a time (joiningNow).
  Window joining;
  TriangleMeasures measures;
  Counts counts;

  void fail(std::exception_ptr e) {
    std::lock_guard<std::mutex> lock(mutex);
    if (!failure) failure = e;
    changed.notify_all();
  }

  void work() {
    try {
      for (;;) {
        std::shared_ptr<Chunk> chunk;
        {
          std::unique_lock<std::mutex> lock(mutex);
          changed.wait(lock, [&] {
            return failure || (ended && waiting.empty()) ||
                   (!waiting.empty() && unjoined < maxUnjoined &&
                    (!waiting.front()->blocks.empty() || waiting.front()->complete));
          });
          if (failure || waiting.empty()) return;
          chunk = waiting.front();
          waiting.pop_front();
          ++unjoined;
        }
        ChunkCheck check(grid, chunk->first, chunk->openUpTo, &sets, &chi, lo, hi);
        for (;;) {
          CornerBlock block;
          {
            std::unique_lock<std::mutex> lock(mutex);
            changed.wait(lock,
                         [&] { return failure || !chunk->blocks.empty() || chunk->complete; });
            if (failure) return;
            if (chunk->blocks.empty()) break;  // complete
            block = std::move(chunk->blocks.front());
            chunk->blocks.pop_front();
          }
          progress.check();
          check.add(block.floats.data(), block.floats.size() / 3);
          check.add(block.doubles.data(), block.doubles.size() / 3);
          std::lock_guard<std::mutex> lock(mutex);
          held -= block.facets();
          changed.notify_all();
        }
        ChunkResult r = check.finish();
        std::unique_lock<std::mutex> lock(mutex);
        done.emplace(chunk->first, std::move(r));
        if (joiningNow) continue;
        joiningNow = true;
        while (!failure && !done.empty() && done.begin()->first == nextToJoin) {
          ChunkResult next = std::move(done.begin()->second);
          done.erase(done.begin());
          lock.unlock();
          const size_t facets = join(std::move(next));
          lock.lock();
          nextToJoin += facets;
          --unjoined;
        }
        joiningNow = false;
        changed.notify_all();
      }
    } catch (...) {
      fail(std::current_exception());
    }
  }

  // A chunk's open vertices and edges welded across chunks; the vertices its last facet's
  // layer has passed counted. Returns its facet count.
  size_t join(ChunkResult r) {
    progress.check();
    for (OpenVertex& v : r.openVertices) {
      const uint32_t id = joining.weld(v.key, v.layer, false);
      for (size_t i = 0; i < v.reps.size(); ++i)
        joining.addRep(id, v.reps[i], joining.rootOf(v.reps[i]));
    }
    // Both ends are among the open vertices just welded.
    for (const OpenEdge& e : r.openEdges)
      joining.addHalfEdges(joining.idOf(e.from), joining.idOf(e.to), e.halves);
    joining.evictBelow(r.front - kWindowLayers, nullptr, nullptr);
    counts.add(std::move(r.counts));
    // Chunks of whole blocks: summed as checkMesh sums them.
    measures.append(std::move(r.measures));
    return r.facets;
  }
};

size_t streamedCheckChunkFacets(const Grid& grid, size_t facets) {
  const double perLayer = double(facets) / double(std::max(1, grid.cells.z));
  const double blocks = std::ceil(128.0 * perLayer / double(kMeasureBlock));
  return kMeasureBlock * size_t(std::clamp(blocks, 8.0, 32.0));
}

int streamedCheckThreads() {
  const int cores = workerCount();
  return cores <= 2 ? 1 : std::max(std::min(cores - 1, 4), std::min(cores / 2, 8));
}

namespace {
// One thread measures as the facets come (a few blocks held); more hold up to a chunk each
// besides the one filling.
size_t heldFacetsFor(int threads, size_t chunkFacets) {
  return threads == 1 ? 8 * kMeasureBlock : size_t(threads + 1) * chunkFacets;
}
}  // namespace

uint64_t streamedCheckBytes(const Grid& grid, size_t facets, bool doubles) {
  const size_t held = heldFacetsFor(streamedCheckThreads(), streamedCheckChunkFacets(grid, facets));
  return uint64_t(std::min(facets, held)) * 3 * (doubles ? sizeof(glm::dvec3) : sizeof(glm::vec3));
}

StreamedMeshCheck::StreamedMeshCheck(const Grid& grid, size_t facets, const glm::dvec3& usedLo,
                                     const glm::dvec3& usedHi, const Progress& progress,
                                     size_t chunkFacets, int threads)
    : state_(std::make_unique<State>(
          grid, facets, usedLo, usedHi, progress,
          chunkFacets > 0 ? chunkFacets : streamedCheckChunkFacets(grid, facets))) {
  if (state_->chunkFacets % kMeasureBlock != 0)
    throw Error("internal: the streamed check's chunks must be whole measure blocks");
  if (facets >= size_t(UINT32_MAX)) throw Error("too many facets for the streamed check");
  const int count = threads > 0 ? threads : streamedCheckThreads();
  // One thread: one chunk (nothing to join).
  if (count == 1 && chunkFacets == 0)
    state_->chunkFacets =
        kMeasureBlock * std::max<size_t>(1, (facets + kMeasureBlock - 1) / kMeasureBlock);
  state_->maxHeldFacets = heldFacetsFor(count, state_->chunkFacets);
  state_->maxUnjoined = size_t(count) + 1;
  State* s = state_.get();
  for (int i = 0; i < count; ++i) s->workers.emplace_back([s] { s->work(); });
}

StreamedMeshCheck::~StreamedMeshCheck() {
  State& s = *state_;
  s.progress.cancel();
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    if (!s.failure) s.failure = std::make_exception_ptr(Cancelled());
  }
  s.changed.notify_all();
  for (std::thread& t : s.workers)
    if (t.joinable()) t.join();
}

void StreamedMeshCheck::add(std::vector<glm::vec3> corners) {
  addCorners(std::move(corners));
}

void StreamedMeshCheck::add(std::vector<glm::dvec3> corners) {
  addCorners(std::move(corners));
}

template <typename Corner>
void StreamedMeshCheck::addCorners(std::vector<Corner> corners) {
  State& s = *state_;
  const size_t facets = corners.size() / 3;
  for (size_t at = 0; at < facets;) {
    // Only this thread changes the chunk being filled, what was added and the highest layer.
    size_t take = 0;
    {
      std::unique_lock<std::mutex> lock(s.mutex);
      if (s.failure) return;  // finish() rethrows it
      if (s.added + facets - at > s.facetCount) {
        s.failure =
            std::make_exception_ptr(Error("the file holds more facets than its count says"));
        s.changed.notify_all();
        return;
      }
      if (!s.filling || s.filling->facets == s.chunkFacets) {
        if (s.filling) s.filling->complete = true;
        s.filling = std::make_shared<State::Chunk>();
        s.filling->first = s.added;
        s.filling->openUpTo = s.highestLayer;
        s.waiting.push_back(s.filling);
        s.changed.notify_all();
      }
      s.changed.wait(lock, [&] { return s.held < s.maxHeldFacets || s.failure; });
      if (s.failure) return;
      take = std::min(facets - at, s.chunkFacets - s.filling->facets);
    }
    // The whole block kept as it came where it lies in one chunk (the usual case), else a copy
    // of its part in this chunk.
    CornerBlock block;
    std::vector<Corner>& kept = cornersOf(block, static_cast<const Corner*>(nullptr));
    kept = at == 0 && take == facets
               ? std::move(corners)
               : std::vector<Corner>(corners.begin() + ptrdiff_t(3 * at),
                                     corners.begin() + ptrdiff_t(3 * (at + take)));
    int highest = s.highestLayer;
    for (const Corner& c : kept) highest = std::max(highest, layerOf(s.grid, double(c.z)));
    {
      std::lock_guard<std::mutex> lock(s.mutex);
      s.filling->blocks.push_back(std::move(block));
      s.filling->facets += take;
      s.added += take;
      s.held += take;
      s.highestLayer = highest;
    }
    at += take;
    s.changed.notify_all();
  }
}

MeshCheck StreamedMeshCheck::finish() {
  State& s = *state_;
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    if (!s.failure && s.added != s.facetCount)
      s.failure = std::make_exception_ptr(Error("the file holds fewer facets than its count says"));
    if (s.filling) s.filling->complete = true;
    s.ended = true;
  }
  s.changed.notify_all();
  for (std::thread& t : s.workers)
    if (t.joinable()) t.join();
  if (s.failure) std::rethrow_exception(s.failure);
  if (!s.done.empty() || s.nextToJoin != s.facetCount)
    throw Error("internal: the streamed check joined " + std::to_string(s.nextToJoin) + " of " +
                std::to_string(s.facetCount) + " facets");
  s.joining.evictBelow(INT_MAX, nullptr, nullptr);
  s.counts.add(std::move(s.joining.counts()));

  MeshCheck c;
  c.vertices = s.counts.vertices;
  c.triangles = s.facetCount;
  c.boundaryEdges = s.counts.boundary;
  c.nonManifoldEdges = s.counts.nonManifold;
  c.misorientedEdges = s.counts.misoriented;
  s.measures.finish(&c);
  // Each component's V - E + F: the facets' shares added up by root (a root is its component's
  // smallest facet; the finds here only read), in parallel over runs of facets.
  const std::vector<uint32_t>& parent = s.sets.parent;
  const auto rootOf = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  std::mutex chiMutex;
  std::map<uint32_t, long long> chi;
  parallelFor(0, int64_t(s.facetCount), 1 << 20, [&](int64_t b, int64_t e) {
    std::map<uint32_t, long long> local;
    long long* last = nullptr;  // neighbouring facets mostly share a component
    uint32_t lastRoot = UINT32_MAX;
    for (int64_t t = b; t < e; ++t) {
      const uint32_t root = rootOf(uint32_t(t));
      if (root != lastRoot) {
        last = &local[root];
        lastRoot = root;
      }
      *last += s.chi[size_t(t)];
    }
    std::lock_guard<std::mutex> lock(chiMutex);
    for (const auto& [root, sum] : local) chi[root] += sum;
  });
  // Vertices counted once for each component around them when they left, where components
  // joined later: counted once per final component.
  for (const std::vector<uint32_t>& reps : s.counts.shared) {
    std::vector<uint32_t> roots;
    for (uint32_t t : reps) roots.push_back(rootOf(t));
    std::sort(roots.begin(), roots.end());
    for (size_t i = 1; i < roots.size(); ++i)
      if (roots[i] == roots[i - 1]) chi[roots[i]] -= 1;
  }
  c.components = int(chi.size());
  if (!c.watertight() || s.facetCount == 0) return c;
  int genus = 0;
  for (const auto& [root, sum] : chi) {
    const long long twiceGenus = 2 - sum;
    if (twiceGenus < 0 || twiceGenus % 2 != 0) return c;  // not a closed surface after all
    genus += int(twiceGenus / 2);
  }
  c.genus = genus;
  return c;
}

WrittenCheck compareStreamedFile(const std::string& path, StreamedMeshCheck& measures,
                                 const TriangleFingerprint& expected, Progress& progress) {
  WrittenCheck result;
  progress.report("check", 0.0);
  // The read-back has a progress of its own, a child of `progress`: cancelled with it, and on
  // its own where the measures fail (the future's destructor then waits for a read-back that
  // stops at once, not for the whole file).
  Progress reading(&progress);
  std::future<TriangleFingerprint> readBack = std::async(std::launch::async, [&] {
    const InputLimitLifted ownFile;  // the file just written: no input limit refuses it
    return fingerprintFile(path, reading);
  });
  MeshCheck measured;
  try {
    measured = measures.finish();
  } catch (...) {
    reading.cancel();
    readBack.wait();
    throw;
  }
  result.fileDifference = fingerprintDifference(path, readBack.get(), expected);
  if (result.fileDifference.empty()) {
    result.check = measured;
  } else {
    const InputLimitLifted ownFile;
    result.check = checkMesh(readMeshFileRaw(path), &progress);
  }
  progress.report("check", 1.0);
  return result;
}

}  // namespace strata
