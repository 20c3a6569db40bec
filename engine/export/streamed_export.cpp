// See streamed_export.h.
#include "engine/export/streamed_export.h"

#include <errno.h>
#include <fcntl.h>
#include <unistd.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <future>
#include <limits>
#include <map>
#include <mutex>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "engine/export/check_streamed.h"
#include "engine/export/check_written.h"
#include "engine/export/contour_scene.h"
#include "engine/export/contour_workers.h"
#include "engine/export/drop_specks.h"
#include "engine/export/fallback.h"
#include "engine/export/unfold_shells.h"
#include "engine/geometry/degenerate_repair.h"
#include "engine/io/mesh_formats.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/parallel_for.h"
#include "engine/util/timer.h"
#include "engine/util/union_find.h"

namespace strata {
namespace {

constexpr uint64_t kFaceKeyBit = uint64_t(1) << 63;  // faceSegmentKey (contour_cells.h)
constexpr uint8_t kHasTriangle = 4;                  // beside the resolved bits
constexpr uint32_t kNoId = std::numeric_limits<uint32_t>::max();
// The passes over a piece run in parallel over blocks of this many of its triangles (or
// vertices), each block's results gathered and then taken in order where the order counts.
constexpr size_t kBlock = 4096;
size_t blocksOf(size_t n) {
  return (n + kBlock - 1) / kBlock;
}
// Block b's range of [0, n).
size_t blockBegin(size_t b) {
  return b * kBlock;
}
size_t blockEnd(size_t b, size_t n) {
  return std::min(n, (b + 1) * kBlock);
}

// The scratch file the pieces are spilled to: created beside the output (the same file system,
// whose space the output needs anyway) and unlinked at once, so that it goes with the process
// whatever happens. Appends only; reads anywhere.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& besides) : path_(besides) {
    const size_t slash = besides.find_last_of('/');
    std::string name = (slash == std::string::npos ? std::string(".") : besides.substr(0, slash)) +
                       "/.strata-stream-XXXXXX";
    fd_ = mkstemp(&name[0]);
    if (fd_ < 0)
      throw Error(path_ + ": cannot create the streamed export's scratch file beside it (" +
                  std::strerror(errno) + ")");
    unlink(name.c_str());
  }
  ~ScratchFile() { close(fd_); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  uint64_t size() const { return end_; }

  template <typename T>
  void append(const std::vector<T>& values) {
    const char* data = reinterpret_cast<const char*>(values.data());
    size_t left = values.size() * sizeof(T);
    while (left > 0) {
      const ssize_t n = pwrite(fd_, data, std::min<size_t>(left, size_t(1) << 30), off_t(end_));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw Error(path_ + ": cannot write the streamed export's scratch file beside it (" +
                    std::strerror(n < 0 ? errno : ENOSPC) + ")");
      data += n;
      left -= size_t(n);
      end_ += uint64_t(n);
    }
  }

  template <typename T>
  void read(uint64_t* at, size_t count, std::vector<T>* values) const {
    values->resize(count);
    char* data = reinterpret_cast<char*>(values->data());
    size_t left = count * sizeof(T);
    while (left > 0) {
      const ssize_t n = pread(fd_, data, std::min<size_t>(left, size_t(1) << 30), off_t(*at));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw Error(path_ + ": cannot read the streamed export's scratch file back (" +
                    std::string(n < 0 ? std::strerror(errno) : "it ended early") + ")");
      data += n;
      left -= size_t(n);
      *at += uint64_t(n);
    }
  }

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t end_ = 0;
};

// One slab's piece: its merged mesh (mergeTiles) and each vertex's global id.
struct Piece {
  std::vector<uint64_t> keys;  // in key order
  std::vector<glm::dvec3> positions;
  std::vector<uint32_t> ids;
  std::vector<std::array<uint32_t, 3>> triangles;  // piece vertices, in edge order
  std::vector<uint8_t> resolved;
  std::vector<uint32_t> leaves;  // per triangle, where the file colours its vertices (PLY)
};

struct PieceRecord {
  uint64_t offset = 0;
  size_t vertices = 0, triangles = 0;
};

// The piece's leaves go with it where it has them (`leaves`: every piece of the export has).
void spill(ScratchFile& file, const Piece& p, std::vector<PieceRecord>* records) {
  records->push_back({file.size(), p.keys.size(), p.triangles.size()});
  file.append(p.keys);
  file.append(p.positions);
  file.append(p.ids);
  file.append(p.triangles);
  file.append(p.resolved);
  file.append(p.leaves);
}

void load(const ScratchFile& file, const PieceRecord& r, bool leaves, Piece* p) {
  uint64_t at = r.offset;
  file.read(&at, r.vertices, &p->keys);
  file.read(&at, r.vertices, &p->positions);
  file.read(&at, r.vertices, &p->ids);
  file.read(&at, r.triangles, &p->triangles);
  file.read(&at, r.triangles, &p->resolved);
  file.read(&at, leaves ? r.triangles : 0, &p->leaves);
}

// What the component steps know of a shell (a component with triangles), by its root id.
struct Shell {
  glm::dvec3 ref{0.0};  // the anchor of its first triangle's first corner
  bool hasRef = false;
  double anchored = 0.0, placed = 0.0;  // six volumes (unfold_shells.cpp)
  uint8_t bits = 0;                     // resolved bits ORed, and kHasTriangle
  uint64_t triangles = 0;
  bool inverted = false;
  bool kept = true;
};

// The passes, in order; each a method over the pieces in the scratch file.
}  // namespace

class StreamedExportWriter::Impl {
 public:
  Impl(const Scene& scene, const std::string& path, const ExportTiling& tiling, Progress& progress,
       ExportReport& report)
      : scene_(scene),
        path_(path),
        tiling_(tiling),
        progress_(progress),
        report_(report),
        r_(report.contour),
        stored_(storedCoordinate(path)),
        scratch_(path),
        grid_(tiling.grid),
        indexed_(lowerExtension(path) == "ply") {
    r_.grid = tiling.grid;
    r_.tileCells = tiling.tileCells;
    r_.tiles = tiling.count();
  }

  void finish() {
    if (nextSlab_ != tiling_.counts.z)
      throw Error(path_ + ": internal: the streamed export ended after " +
                  std::to_string(nextSlab_) + " of " + std::to_string(tiling_.counts.z) + " slabs");
    if (spilling_.valid()) {
      Stopwatch spill;
      spilling_.get();
      spilled_ = Piece();
      r_.mergeSeconds += spill.seconds();
    }
    r_.mergeSteps.push_back({"slabs", r_.mergeSeconds});
    Stopwatch steps, step;
    const auto timed = [&](const char* name) {
      r_.mergeSteps.push_back({name, step.seconds()});
      step.restart();
    };
    finishPieces();
    timed("roots");
    progress_.report("merge", 0.0);
    sumShells();
    timed("shells");
    progress_.report("merge", 0.4);
    unfoldShells();
    timed("unfold");
    dropSpecks();
    timed("specks");
    progress_.report("merge", 0.7);
    repairFlaws();
    timed("repair");
    progress_.report("merge", 1.0);
    r_.mergeSeconds += steps.seconds();
    r_.deviationBound = std::sqrt(3.0) * r_.grid.h;
    // The facets measured as checkMesh would (check_streamed.h) on a thread of their own as they
    // are written; the file read back while the last chunks are measured, and compared by
    // fingerprint.
    if (keptTriangles_ == 0) throw emptyResultError(path_, r_);
    if (!indexed_ && keptTriangles_ > std::numeric_limits<uint32_t>::max())
      throw Error(path_ + ": too many triangles for STL (" + std::to_string(keptTriangles_) + ")");
    if (keptTriangles_ >= std::numeric_limits<uint32_t>::max())  // the check numbers facets so
      throw Error(path_ + ": too many triangles for one streamed export (" +
                  std::to_string(keptTriangles_) + ")");
    Stopwatch write;
    if (indexed_) numberVertices();
    StreamedMeshCheck measures(grid_, keptTriangles_, used_.min, used_.max, progress_);
    writeFile(&measures);
    report_.writeSeconds = write.seconds();
    Stopwatch check;
    const WrittenCheck written = compareStreamedFile(path_, measures, fingerprint_, progress_);
    r_.peakBytes = peakResidentBytes();
    report_.check = written.check;
    // An indexed file's vertices are what checkMesh counts of it (the measures count the distinct
    // positions the facets use: the same, but for a vertex a collapse left unused or two
    // vertices at one position).
    if (indexed_ && written.fileDifference.empty()) report_.check.vertices = plyVertices_;
    report_.fileDifference = written.fileDifference;
    report_.checkSeconds = check.seconds();
  }

  uint32_t newId() {
    sets_.parent.push_back(uint32_t(sets_.parent.size()));
    if (sets_.parent.size() >= size_t(kNoId))
      throw Error(path_ + ": more than 2^32 vertices: too many for one export");
    return uint32_t(sets_.parent.size() - 1);
  }

  // Pass 1, a slab at a time: its tiles merged into a piece, given global vertex ids (a vertex
  // shared with the slab below keeps its id there) and joined into components, spilled.
  void addSlab(int z, std::vector<TileContour> tiles) {
    if (z != nextSlab_)
      throw Error(path_ + ": internal: slab " + std::to_string(z) + " came before slab " +
                  std::to_string(nextSlab_));
    ++nextSlab_;
    Stopwatch merge;
    const int perSlab = tiling_.counts.x * tiling_.counts.y;
    const uint64_t layerKeys = uint64_t(grid_.cells.x) * uint64_t(grid_.cells.y) * 4;
    const uint64_t firstKey = uint64_t(tiling_.begin(z * perSlab).z) * layerKeys;
    const uint64_t topKey = uint64_t(tiling_.end(z * perSlab).z - 1) * layerKeys;
    Piece piece;
    if (!tiles.empty()) {
      MergedTiles merged = mergeTiles(scene_, std::move(tiles), progress_, r_);
      unit_ = merged.mesh.unit;
      piece.keys = std::move(merged.keys);
      piece.positions = std::move(merged.mesh.mesh.positions);
      piece.triangles = std::move(merged.mesh.mesh.triangles);
      piece.resolved = std::move(merged.resolved);
      if (indexed_) {
        piece.leaves = std::move(merged.mesh.triangleLeaf);
        for (const auto& [leaf, style] : merged.mesh.leaves) leafStyles_.emplace(leaf, style);
      }
    }
    piece.ids.resize(piece.keys.size());
    std::unordered_map<uint64_t, uint32_t> top;
    for (size_t i = 0; i < piece.keys.size(); ++i) {
      const uint64_t key = piece.keys[i];
      uint32_t id;
      if (key & kFaceKeyBit) {
        const auto found = faces_.find(key);
        id = found != faces_.end() ? found->second : (faces_[key] = newId());
      } else if (key < firstKey) {
        // A halo cell of the slab below: its vertex was that slab's.
        const auto found = below_.find(key);
        if (found == below_.end())
          throw Error(path_ + ": internal: a vertex of the slab below was not merged there");
        id = found->second;
      } else {
        id = newId();
      }
      piece.ids[i] = id;
      if (!(key & kFaceKeyBit) && key >= topKey) top[key] = id;
    }
    // The piece's components joined in parallel over its own vertices (ConcurrentUnionFind),
    // then each vertex's id joined to its local root's: the same sets (and roots: a set's
    // smallest id) as joining the ends of every triangle, with a quarter of the unions on
    // this thread.
    {
      ConcurrentUnionFind local(piece.keys.size());
      eachBlock(piece.triangles.size(), [&](size_t, size_t begin, size_t end) {
        for (size_t t = begin; t < end; ++t) {
          const auto& tri = piece.triangles[t];
          local.unite(tri[0], tri[1]);
          local.unite(tri[0], tri[2]);
        }
      });
      std::vector<uint32_t> localRoot(piece.keys.size());
      eachBlock(piece.keys.size(), [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) localRoot[i] = local.find(uint32_t(i));
      });
      for (size_t i = 0; i < piece.keys.size(); ++i)
        if (localRoot[i] != i) sets_.unite(piece.ids[i], piece.ids[localRoot[i]]);
    }
    triangles_ += piece.triangles.size();
    // Spilled on a thread of its own while the next slab is merged (one piece at a time).
    if (spilling_.valid()) spilling_.get();
    spilled_ = std::move(piece);
    spilling_ = std::async(std::launch::async, [this] {
      spill(scratch_, spilled_, &pieces_);
      spilled_ = Piece();  // let go as soon as written, not when the next slab comes
    });
    below_ = std::move(top);
    r_.mergeSeconds += merge.seconds();
  }

 private:
  // After the last slab: each id's root, and how many ids each root has.
  void finishPieces() {
    below_.clear();
    // The face vertices' ids by key (the file lists them after the others, in key order).
    if (indexed_) {
      faceIds_.assign(faces_.begin(), faces_.end());
      std::sort(faceIds_.begin(), faceIds_.end());
    }
    faces_.clear();
    const size_t n = sets_.parent.size();
    for (size_t i = 0; i < n; ++i) sets_.parent[i] = sets_.find(uint32_t(i));
    vertexCount_.assign(n, 0);
    for (size_t i = 0; i < n; ++i) ++vertexCount_[sets_.parent[i]];
  }

  uint32_t rootOf(uint32_t id) const { return sets_.parent[id]; }

  // The pieces in order, each read from the scratch file on a thread of its own while the one
  // before it is visited (two pieces held at a time).
  template <typename Visit>
  void eachPiece(Visit visit) {
    if (pieces_.empty()) return;
    std::array<Piece, 2> loaded;
    load(scratch_, pieces_[0], indexed_, &loaded[0]);
    for (size_t k = 0; k < pieces_.size(); ++k) {
      progress_.check();
      std::future<void> next;  // waited for by its destructor if visit throws
      if (k + 1 < pieces_.size())
        next = std::async(std::launch::async, [&, k] {
          load(scratch_, pieces_[k + 1], indexed_, &loaded[(k + 1) % 2]);
        });
      visit(static_cast<const Piece&>(loaded[k % 2]));
      if (next.valid()) next.get();
    }
  }

  // body(b, begin, end) for each block of [0, n) (kBlock), on several threads at once.
  template <typename Body>
  static void eachBlock(size_t n, const Body& body) {
    parallelFor(0, int64_t(blocksOf(n)), 1, [&](int64_t b, int64_t e) {
      for (int64_t k = b; k < e; ++k)
        body(size_t(k), blockBegin(size_t(k)), blockEnd(size_t(k), n));
    });
  }

  static std::vector<glm::dvec3> anchorsOf(const Grid& grid, const Piece& p) {
    std::vector<glm::dvec3> anchors(p.keys.size());
    eachBlock(p.keys.size(), [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i)
        anchors[i] = shellAnchor(grid, p.keys[i], sharesCell(p.keys, i), p.positions[i]);
    });
    return anchors;
  }

  // The place among the kept triangles of the mesh of each block's first triangle of `p`
  // (blocks + 1 entries, the last past the piece), counted on from *place, which moves past
  // the piece.
  std::vector<uint64_t> keptPlaces(const Piece& p, uint64_t* place) const {
    const size_t blocks = blocksOf(p.triangles.size());
    std::vector<uint64_t> at(blocks + 1, 0);
    eachBlock(p.triangles.size(), [&](size_t b, size_t begin, size_t end) {
      uint64_t kept = 0;
      for (size_t t = begin; t < end; ++t) kept += keptTriangle(p, t) ? 1 : 0;
      at[b + 1] = kept;
    });
    at[0] = *place;
    for (size_t b = 0; b < blocks; ++b) at[b + 1] += at[b];
    *place = at[blocks];
    return at;
  }

  // The index into repaired_ of the first replacement at or after `place` (replacementAt's
  // cursor for a block beginning there).
  size_t replacementCursor(uint64_t place) const {
    return size_t(std::lower_bound(repaired_.begin(), repaired_.end(), place,
                                   [](const std::pair<uint64_t, Replacement>& r, uint64_t x) {
                                     return r.first < x;
                                   }) -
                  repaired_.begin());
  }

  // Pass 2: each shell's six volumes, anchored and placed, summed as unfoldInvertedShells sums
  // them (relative to its first triangle's first anchor, in the runs ShellRunSums fixes: the
  // same sums bit for bit); its resolved bits and triangle count; the boxes of the components
  // small enough for the speck rule to measure.
  void sumShells() {
    ShellRunSums runs;
    const auto flush = [&](const ShellRun& run) {
      Shell& s = shells_[run.shell];
      s.anchored += run.anchored;
      s.placed += run.placed;
    };
    std::vector<uint32_t> roots;
    std::vector<const Shell*> shellOf;
    eachPiece([&](const Piece& p) {
      const std::vector<glm::dvec3> anchors = anchorsOf(grid_, p);
      {
        // The small components' vertices (few: found in parallel, their boxes grown here).
        std::vector<std::vector<uint32_t>> small(blocksOf(p.ids.size()));
        eachBlock(p.ids.size(), [&](size_t b, size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i)
            if (vertexCount_[rootOf(p.ids[i])] <= kMeasuredSpeckVertices)
              small[b].push_back(uint32_t(i));
        });
        for (const std::vector<uint32_t>& block : small)
          for (uint32_t i : block) boxes_[rootOf(p.ids[i])].include(p.positions[i]);
      }
      const size_t n = p.triangles.size();
      roots.resize(n);
      shellOf.resize(n);
      eachBlock(n, [&](size_t, size_t begin, size_t end) {
        for (size_t t = begin; t < end; ++t) roots[t] = rootOf(p.ids[p.triangles[t][0]]);
      });
      // In order on this thread (a comparison a triangle: a shell's triangles come in long
      // runs): each shell's first triangle's first anchor, its bits and count.
      uint32_t lastShell = kNoId;
      Shell* last = nullptr;
      for (size_t t = 0; t < n; ++t) {
        if (roots[t] != lastShell) {
          last = &shells_[roots[t]];  // pointers into an unordered_map stay valid
          lastShell = roots[t];
        }
        if (!last->hasRef) {
          last->ref = anchors[p.triangles[t][0]];
          last->hasRef = true;
        }
        last->bits |= uint8_t(p.resolved[t] | kHasTriangle);
        ++last->triangles;
        shellOf[t] = last;
      }
      runs.add(
          n,
          [&](uint64_t t, uint32_t* shell, double* anchored, double* placed) {
            const auto& tri = p.triangles[t];
            const glm::dvec3& ref = shellOf[t]->ref;
            *shell = roots[t];
            *anchored =
                sixVolumeTerm(anchors[tri[0]] - ref, anchors[tri[1]] - ref, anchors[tri[2]] - ref);
            *placed = sixVolumeTerm(p.positions[tri[0]] - ref, p.positions[tri[1]] - ref,
                                    p.positions[tri[2]] - ref);
          },
          flush);
    });
    runs.finish(flush);
    for (auto& [root, s] : shells_) {
      const int want = volumeSign(s.anchored);
      s.inverted = want != 0 && volumeSign(s.placed) != want;
      anyInverted_ = anyInverted_ || s.inverted;
    }
  }

  // Pass 3 (where a shell is inverted): its triangles gathered (few: shells thinner than a
  // cell), pulled back from their anchors as unfoldInvertedShells pulls them.
  void unfoldShells() {
    if (!anyInverted_) return;
    struct Gathered {
      std::unordered_map<uint32_t, uint32_t> local;  // id -> index below
      std::vector<uint32_t> ids;
      std::vector<glm::dvec3> anchors, positions;
      std::vector<std::array<uint32_t, 3>> triangles;
    };
    std::unordered_map<uint32_t, Gathered> gathered;
    std::vector<uint8_t> invertedRoot(sets_.parent.size(), 0);  // a byte per id
    for (const auto& [root, s] : shells_) invertedRoot[root] = s.inverted ? 1 : 0;
    eachPiece([&](const Piece& p) {
      // The inverted shells' triangles (few), found in parallel and gathered in order.
      std::vector<std::vector<uint32_t>> inverted(blocksOf(p.triangles.size()));
      eachBlock(p.triangles.size(), [&](size_t b, size_t begin, size_t end) {
        for (size_t t = begin; t < end; ++t)
          if (invertedRoot[rootOf(p.ids[p.triangles[t][0]])]) inverted[b].push_back(uint32_t(t));
      });
      std::vector<glm::dvec3> anchors;
      for (const std::vector<uint32_t>& block : inverted)
        for (uint32_t t : block) {
          const auto& tri = p.triangles[t];
          const uint32_t shell = rootOf(p.ids[tri[0]]);
          if (anchors.empty()) anchors = anchorsOf(grid_, p);
          Gathered& g = gathered[shell];
          std::array<uint32_t, 3> corners;
          for (int k = 0; k < 3; ++k) {
            const uint32_t v = tri[size_t(k)], id = p.ids[v];
            const auto found = g.local.find(id);
            if (found != g.local.end()) {
              corners[size_t(k)] = found->second;
              continue;
            }
            corners[size_t(k)] = g.local[id] = uint32_t(g.ids.size());
            g.ids.push_back(id);
            g.anchors.push_back(anchors[v]);
            g.positions.push_back(p.positions[v]);
          }
          g.triangles.push_back(corners);
        }
    });
    for (auto& [shell, g] : gathered) {
      const Shell& s = shells_[shell];
      const double keep =
          pullBackKeep(g.triangles, g.anchors, g.positions, s.ref, volumeSign(s.anchored));
      Bounds box;
      for (size_t i = 0; i < g.ids.size(); ++i) {
        const glm::dvec3 p = g.anchors[i] + keep * (g.positions[i] - g.anchors[i]);
        moved_[g.ids[i]] = p;
        box.include(p);
      }
      if (boxes_.count(shell)) boxes_[shell] = box;
      ++r_.unfoldedShells;
    }
  }

  // The speck rule per component (drop_specks.h), with its exception: where every component
  // would go, none does.
  void dropSpecks() {
    DroppedSpecks dropped;
    bool anyKept = false;
    for (auto& [root, s] : shells_) {
      const auto box = boxes_.find(root);
      s.kept = box == boxes_.end() ? keepComponent(s.bits, vertexCount_[root], glm::dvec3(0.0),
                                                   glm::dvec3(0.0), grid_.h)
                                   : keepComponent(s.bits, vertexCount_[root], box->second.min,
                                                   box->second.max, grid_.h);
      anyKept = anyKept || s.kept;
      if (!s.kept) {
        ++dropped.components;
        dropped.triangles += s.triangles;
      }
    }
    if (!anyKept) {
      for (auto& [root, s] : shells_) s.kept = true;
      dropped = DroppedSpecks();
    }
    r_.droppedSpecks = dropped;
    keptTriangles_ = triangles_ - dropped.triangles;
    boxes_.clear();
    // From here on a byte per id says whether its component was dropped (a lookup a triangle in
    // every later pass); the counts are read no more.
    vertexCount_ = std::vector<uint32_t>();
    if (dropped.components > 0) {
      droppedRoot_.assign(sets_.parent.size(), 0);
      for (const auto& [root, s] : shells_) droppedRoot_[root] = s.kept ? 0 : 1;
    }
  }

  glm::dvec3 finalPosition(const Piece& p, uint32_t v) const {
    if (moved_.empty()) return p.positions[v];
    const auto found = moved_.find(p.ids[v]);
    return found == moved_.end() ? p.positions[v] : found->second;
  }

  // What the repair of flat triangles made of one it read: removed, or these corners.
  struct Replacement {
    bool alive = false;
    std::array<glm::dvec3, 3> corners{};
    std::array<uint32_t, 3> ids{};  // the corners' global ids
  };

  bool keptTriangle(const Piece& p, size_t t) const {
    return droppedRoot_.empty() || droppedRoot_[rootOf(p.ids[p.triangles[t][0]])] == 0;
  }

  // The repair's replacement of the kept triangle at `place` or null, for places asked in
  // increasing order from `*next` (an index into repaired_, sorted by place).
  const Replacement* replacementAt(uint64_t place, size_t* next) const {
    if (*next >= repaired_.size() || repaired_[*next].first != place) return nullptr;
    return &repaired_[(*next)++].second;
  }

  // Pass 4: the triangles flawed as the file stores them (degenerate_repair.h), repaired on the
  // part of the mesh around them: the triangles around every vertex within `rings` of their
  // corners, grown until the repair found the ring of each corner it read there.
  void repairFlaws() {
    std::vector<uint32_t> region;  // ids of flawed triangles' corners (repeats allowed)
    const auto storedAt = [&](const glm::dvec3& x) {
      return glm::dvec3(stored_(x.x), stored_(x.y), stored_(x.z));
    };
    eachPiece([&](const Piece& p) {
      // In parallel: each block's box and flawed corners, then taken in order.
      const size_t blocks = blocksOf(p.triangles.size());
      std::vector<Bounds> boxes(blocks);
      std::vector<std::vector<uint32_t>> flawed(blocks);
      eachBlock(p.triangles.size(), [&](size_t blk, size_t begin, size_t end) {
        for (size_t t = begin; t < end; ++t) {
          if (!keptTriangle(p, t)) continue;
          const auto& tri = p.triangles[t];
          const glm::dvec3 a = finalPosition(p, tri[0]), b = finalPosition(p, tri[1]),
                           c = finalPosition(p, tri[2]);
          for (const glm::dvec3& x : {a, b, c}) boxes[blk].include(storedAt(x));
          if (storedFlawed(a, b, c, stored_))
            for (uint32_t v : tri) flawed[blk].push_back(p.ids[v]);
        }
      });
      for (size_t blk = 0; blk < blocks; ++blk) {
        if (!boxes[blk].empty()) used_.include(boxes[blk]);
        region.insert(region.end(), flawed[blk].begin(), flawed[blk].end());
      }
    });
    if (region.empty()) return;
    // The vertices whose rings the part holds whole (a flag per id: a lookup per corner of every
    // triangle in each pass below): the flawed corners and, a ring at a time (one more after
    // each try that needed it), the vertices around them.
    std::vector<bool> complete(sets_.parent.size(), false);
    for (uint32_t id : region) complete[id] = true;
    for (int rings = 1;; ++rings) {
      {
        std::vector<bool> grown = complete;
        eachPiece([&](const Piece& p) {
          // The ids around the complete ones (few), found in parallel and marked here.
          std::vector<std::vector<uint32_t>> around(blocksOf(p.triangles.size()));
          eachBlock(p.triangles.size(), [&](size_t blk, size_t begin, size_t end) {
            for (size_t t = begin; t < end; ++t) {
              if (!keptTriangle(p, t)) continue;
              const auto& tri = p.triangles[t];
              if (complete[p.ids[tri[0]]] || complete[p.ids[tri[1]]] || complete[p.ids[tri[2]]])
                for (uint32_t v : tri) around[blk].push_back(p.ids[v]);
            }
          });
          for (const std::vector<uint32_t>& block : around)
            for (uint32_t id : block) grown[id] = true;
        });
        complete = std::move(grown);
      }
      // The part: every kept triangle around a complete vertex, in the mesh's order; its
      // vertices in key order (the mesh's), each with its key.
      struct PartTriangle {
        uint64_t place;  // among the kept triangles
        std::array<uint64_t, 3> keys;
        std::array<glm::dvec3, 3> corners;
        std::array<uint32_t, 3> ids;
      };
      std::vector<PartTriangle> part;
      uint64_t place = 0;
      eachPiece([&](const Piece& p) {
        const std::vector<uint64_t> at = keptPlaces(p, &place);
        std::vector<std::vector<PartTriangle>> found(at.size() - 1);
        eachBlock(p.triangles.size(), [&](size_t blk, size_t begin, size_t end) {
          uint64_t here = at[blk];
          for (size_t t = begin; t < end; ++t) {
            if (!keptTriangle(p, t)) continue;
            const auto& tri = p.triangles[t];
            if (complete[p.ids[tri[0]]] || complete[p.ids[tri[1]]] || complete[p.ids[tri[2]]]) {
              PartTriangle pt{here, {}, {}, {}};
              for (int k = 0; k < 3; ++k) {
                pt.keys[size_t(k)] = p.keys[tri[size_t(k)]];
                pt.corners[size_t(k)] = finalPosition(p, tri[size_t(k)]);
                pt.ids[size_t(k)] = p.ids[tri[size_t(k)]];
              }
              found[blk].push_back(pt);
            }
            ++here;
          }
        });
        for (const std::vector<PartTriangle>& block : found)
          part.insert(part.end(), block.begin(), block.end());
      });
      std::vector<std::pair<uint64_t, uint32_t>> byKey;  // (key, id)
      for (const PartTriangle& pt : part)
        for (int k = 0; k < 3; ++k) byKey.push_back({pt.keys[size_t(k)], pt.ids[size_t(k)]});
      std::sort(byKey.begin(), byKey.end());
      byKey.erase(std::unique(byKey.begin(), byKey.end()), byKey.end());
      TriangleMesh mesh;
      std::vector<uint8_t> ringComplete(byKey.size());
      std::unordered_map<uint32_t, uint32_t> local;  // id -> part vertex
      mesh.positions.resize(byKey.size());
      for (size_t i = 0; i < byKey.size(); ++i) {
        local[byKey[i].second] = uint32_t(i);
        ringComplete[i] = complete[byKey[i].second] ? 1 : 0;
      }
      std::vector<uint32_t> partIndex(part.size());
      for (size_t t = 0; t < part.size(); ++t) {
        std::array<uint32_t, 3> tri;
        for (int k = 0; k < 3; ++k) {
          tri[size_t(k)] = local.at(part[t].ids[size_t(k)]);
          mesh.positions[tri[size_t(k)]] = part[t].corners[size_t(k)];
        }
        mesh.triangles.push_back(tri);
        partIndex[t] = uint32_t(t);
      }
      DegenerateRepair repair;
      if (!repairDegenerateTriangles(&mesh, stored_, &partIndex, &ringComplete, &repair)) {
        if (rings >= 64)
          throw Error(path_ + ": internal: the repair of flat triangles reached too far");
        continue;
      }
      report_.degenerateRepair = repair;
      // What the repair left of the part, by place (the part's order: increasing): the
      // surviving triangles' corners; the rest removed.
      repaired_.assign(part.size(), {});
      for (size_t t = 0; t < part.size(); ++t) repaired_[t].first = part[t].place;
      for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        std::array<glm::dvec3, 3> corners;
        std::array<uint32_t, 3> ids;
        for (int k = 0; k < 3; ++k) {
          corners[size_t(k)] = mesh.positions[mesh.triangles[t][size_t(k)]];
          ids[size_t(k)] = byKey[mesh.triangles[t][size_t(k)]].second;
        }
        repaired_[partIndex[t]].second = Replacement{true, corners, ids};
      }
      keptTriangles_ -= 2 * repair.collapsed;
      if (repair.collapsed > 0) {
        // A collapse lets a corner go: the box of the corners the facets still use.
        used_ = Bounds();
        uint64_t kept = 0;
        eachPiece([&](const Piece& p) {
          const std::vector<uint64_t> at = keptPlaces(p, &kept);
          std::vector<Bounds> boxes(at.size() - 1);
          eachBlock(p.triangles.size(), [&](size_t blk, size_t begin, size_t end) {
            uint64_t here = at[blk];
            size_t next = replacementCursor(here);
            for (size_t t = begin; t < end; ++t) {
              if (!keptTriangle(p, t)) continue;
              if (const Replacement* r = replacementAt(here++, &next)) {
                if (r->alive)
                  for (const glm::dvec3& x : r->corners) boxes[blk].include(storedAt(x));
                continue;
              }
              for (uint32_t v : p.triangles[t]) boxes[blk].include(storedAt(finalPosition(p, v)));
            }
          });
          for (const Bounds& box : boxes)
            if (!box.empty()) used_.include(box);
        });
      }
      return;
    }
  }

  // A block of facets encoded as the file stores them (writeFile).
  struct EncodedBlock {
    std::string bytes;                     // binary STL facets or PLY faces
    std::vector<glm::vec3> corners;        // as stored, STL (float32: exact), for the measures
    std::vector<glm::dvec3> exactCorners;  // as stored, PLY (doubles), for the measures
    TriangleFingerprint fingerprint;
  };

  void requireFinite(const glm::dvec3& x) const {
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
      throw Error(path_ + ": cannot write: a vertex is not finite");
  }

  void encodeFacet(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                   EncodedBlock* out) const {
    for (const glm::dvec3* x : {&a, &b, &c}) {
      requireFinite(*x);
      checkStlCoordinates(path_, *x);
    }
    const size_t at = out->bytes.size();
    out->bytes.resize(at + kStlFacetBytes);
    encodeStlFacet(a, b, c, &out->bytes[at]);
    const auto s = [&](const glm::dvec3& p) {
      return glm::dvec3(stored_(p.x), stored_(p.y), stored_(p.z));
    };
    const glm::dvec3 sa = s(a), sb = s(b), sc = s(c);
    addToFingerprint(sa, sb, sc, &out->fingerprint);
    for (const glm::dvec3* x : {&sa, &sb, &sc}) {
      out->corners.push_back(glm::vec3(*x));
      if (glm::dvec3(out->corners.back()) != *x)
        throw Error(path_ + ": internal: a stored coordinate is not a float32");
    }
  }

  // A PLY face: its corners' indices in the file (numberVertices), its corners as stored
  // (doubles: exactly) for the fingerprint and the measures.
  void encodeFace(const std::array<uint32_t, 3>& ids, const glm::dvec3& a, const glm::dvec3& b,
                  const glm::dvec3& c, EncodedBlock* out) const {
    std::array<uint32_t, 3> corners;
    for (int k = 0; k < 3; ++k) {
      corners[size_t(k)] = index_[ids[size_t(k)]];
      if (corners[size_t(k)] == kNoId)
        throw Error(path_ + ": internal: a face uses a vertex the file does not list");
    }
    const size_t at = out->bytes.size();
    out->bytes.resize(at + kPlyFaceBytes);
    encodePlyFace(corners, &out->bytes[at]);
    addToFingerprint(a, b, c, &out->fingerprint);
    out->exactCorners.push_back(a);
    out->exactCorners.push_back(b);
    out->exactCorners.push_back(c);
  }

  // The facets of block `blk` of piece `p` (keptPlaces `at`) encoded into *block.
  void encodeBlock(const Piece& p, const std::vector<uint64_t>& at, size_t blk,
                   EncodedBlock* block) const {
    uint64_t here = at[blk];
    size_t next = replacementCursor(here);
    const auto emit = [&](const std::array<uint32_t, 3>& ids, const glm::dvec3& a,
                          const glm::dvec3& b, const glm::dvec3& c) {
      if (indexed_)
        encodeFace(ids, a, b, c, block);
      else
        encodeFacet(a, b, c, block);
    };
    for (size_t t = blockBegin(blk); t < blockEnd(blk, p.triangles.size()); ++t) {
      if (!keptTriangle(p, t)) continue;
      if (const Replacement* r = replacementAt(here++, &next)) {
        if (r->alive) emit(r->ids, r->corners[0], r->corners[1], r->corners[2]);
        continue;
      }
      const auto& tri = p.triangles[t];
      emit({p.ids[tri[0]], p.ids[tri[1]], p.ids[tri[2]]}, finalPosition(p, tri[0]),
           finalPosition(p, tri[1]), finalPosition(p, tri[2]));
    }
  }

  // PLY: which vertices the file lists, in what order, in which colour (as writePly lists and
  // colours the in-memory export's mesh): those a kept triangle uses (before the repair of flat
  // triangles, as dropUnresolvedSpecks keeps them), in key order (the ids of the vertices that
  // are not face vertices grow with their keys, slab after slab; the face vertices' keys sort
  // after every other), each coloured by the leaf of the first triangle of the file (after the
  // repair) that uses it. In parallel blocks of each piece: each block marks the vertices it
  // uses and lists the first use of each vertex not coloured before the piece (and a few
  // repeats), then the lists are taken in block order: the first use in the file wins.
  void numberVertices() {
    progress_.report("write PLY", 0.0);
    const size_t n = sets_.parent.size();
    constexpr uint8_t kUsed = 1, kColoured = 2;
    std::vector<std::atomic<uint8_t>> state(n);
    for (auto& s : state) s.store(0, std::memory_order_relaxed);
    colours_.assign(n, plyUnusedColour());
    std::unordered_map<uint32_t, std::array<uint8_t, 3>> palette;
    for (const auto& [leaf, style] : leafStyles_) palette[leaf] = plyColour(style);
    struct FirstUse {
      uint32_t id;
      std::array<uint8_t, 3> colour;
    };
    uint64_t kept = 0;
    eachPiece([&](const Piece& p) {
      const std::vector<uint64_t> at = keptPlaces(p, &kept);
      std::vector<std::vector<FirstUse>> uses(at.size() - 1);
      std::vector<std::exception_ptr> failed(at.size() - 1);
      eachBlock(p.triangles.size(), [&](size_t blk, size_t begin, size_t end) {
        try {
          uint64_t here = at[blk];
          size_t next = replacementCursor(here);
          uint32_t lastLeaf = kNoId;
          std::array<uint8_t, 3> colour{};
          std::array<uint32_t, 1024> recent;  // ids listed lately (a repeat skipped)
          recent.fill(kNoId);
          for (size_t t = begin; t < end; ++t) {
            if (!keptTriangle(p, t)) continue;
            const auto& tri = p.triangles[t];
            for (uint32_t v : tri) state[p.ids[v]].fetch_or(kUsed, std::memory_order_relaxed);
            const Replacement* r = replacementAt(here++, &next);
            if (r && !r->alive) continue;
            if (p.leaves[t] != lastLeaf) {
              const auto found = palette.find(p.leaves[t]);
              if (found == palette.end())
                throw Error(path_ + ": internal: a triangle's leaf has no style");
              colour = found->second;
              lastLeaf = p.leaves[t];
            }
            for (int k = 0; k < 3; ++k) {
              const uint32_t id = r ? r->ids[size_t(k)] : p.ids[tri[size_t(k)]];
              if (state[id].load(std::memory_order_relaxed) & kColoured) continue;
              uint32_t& slot = recent[id % recent.size()];
              if (slot == id) continue;
              slot = id;
              uses[blk].push_back({id, colour});
            }
          }
        } catch (...) {
          failed[blk] = std::current_exception();
        }
      });
      for (const std::exception_ptr& failure : failed)
        if (failure) std::rethrow_exception(failure);
      for (const std::vector<FirstUse>& block : uses)
        for (const FirstUse& use : block) {
          if (state[use.id].load(std::memory_order_relaxed) & kColoured) continue;
          state[use.id].fetch_or(kColoured, std::memory_order_relaxed);
          colours_[use.id] = use.colour;
        }
    });
    constexpr uint32_t kFaceVertex = kNoId - 1;
    index_.assign(n, kNoId);
    for (const auto& [key, id] : faceIds_) index_[id] = kFaceVertex;
    const auto used = [&](size_t id) {
      return (state[id].load(std::memory_order_relaxed) & kUsed) != 0;
    };
    uint64_t listed = 0;
    for (size_t id = 0; id < n; ++id)
      if (index_[id] != kFaceVertex && used(id)) index_[id] = uint32_t(listed++);
    faceVertexStart_ = listed;
    for (const auto& [key, id] : faceIds_) index_[id] = used(id) ? uint32_t(listed++) : kNoId;
    if (listed > uint64_t(std::numeric_limits<int32_t>::max()))
      throw Error(path_ + ": too many vertices for PLY's int indices (" + std::to_string(listed) +
                  ")");
    plyVertices_ = listed;
  }

  // Encodes blocks [0, blocks) with encode(b, &block) a group at a time on several threads
  // (a block's failure kept, the first block's rethrown: the same message on any thread count),
  // then hands each group, in order, to hand() on a thread of its own (*writing; *handing holds
  // the group) while the next is encoded.
  template <typename Block, typename Encode, typename Hand>
  void writeBlocks(size_t blocks, const Encode& encode, const Hand& hand,
                   std::vector<Block>* handing, std::future<void>* writing) {
    const size_t group = size_t(std::min(4 * workerCount(), 64));
    for (size_t first = 0; first < blocks; first += group) {
      const size_t count = std::min(group, blocks - first);
      std::vector<Block> encoded(count);
      std::vector<std::exception_ptr> failed(count);
      parallelFor(0, int64_t(count), 1, [&](int64_t b, int64_t e) {
        for (size_t k = size_t(b); k < size_t(e); ++k) {
          try {
            encode(first + k, &encoded[k]);
          } catch (...) {
            failed[k] = std::current_exception();
          }
        }
      });
      for (const std::exception_ptr& failure : failed)
        if (failure) std::rethrow_exception(failure);
      if (writing->valid()) writing->get();
      *handing = std::move(encoded);
      *writing = std::async(std::launch::async, hand);
    }
  }

  // PLY's vertex section: each piece's vertices the file lists there (not a face vertex, not
  // listed by the piece before: a vertex of the slab below has a smaller index), checked to come
  // in the order numberVertices gave them; then the face vertices, in key order.
  void writeVertices(std::ostream& out) {
    uint64_t listed = 0;
    std::vector<uint32_t> faceVertices;  // ids, in the file's order
    for (const auto& [key, id] : faceIds_)
      if (index_[id] != kNoId) faceVertices.push_back(id);
    std::vector<glm::dvec3> facePositions(faceVertices.size());
    std::vector<std::string> handing;
    std::future<void> writing;  // declared after it: waited for first if a throw
    const auto hand = [&] {
      for (const std::string& bytes : handing)
        out.write(bytes.data(), std::streamsize(bytes.size()));
    };
    eachPiece([&](const Piece& p) {
      const size_t blocks = blocksOf(p.keys.size());
      const uint64_t pieceStart = listed;
      const auto listedHere = [&](size_t i) {
        const uint32_t index = index_[p.ids[i]];
        return index != kNoId && !(p.keys[i] & kFaceKeyBit) && index >= pieceStart;
      };
      std::vector<uint64_t> first(blocks + 1, 0);  // the index of each block's first listed
      std::vector<std::vector<uint32_t>> faceHere(blocks);
      eachBlock(p.keys.size(), [&](size_t b, size_t begin, size_t end) {
        uint64_t count = 0;
        for (size_t i = begin; i < end; ++i) {
          if ((p.keys[i] & kFaceKeyBit) && index_[p.ids[i]] != kNoId)
            faceHere[b].push_back(uint32_t(i));
          if (listedHere(i)) ++count;
        }
        first[b + 1] = count;
      });
      first[0] = pieceStart;
      for (size_t b = 0; b < blocks; ++b) first[b + 1] += first[b];
      for (const std::vector<uint32_t>& block : faceHere)
        for (uint32_t i : block)
          facePositions[index_[p.ids[i]] - faceVertexStart_] = finalPosition(p, i);
      writeBlocks<std::string>(
          blocks,
          [&](size_t b, std::string* bytes) {
            bytes->resize(size_t(first[b + 1] - first[b]) * kPlyVertexBytes);
            uint64_t expected = first[b];
            for (size_t i = blockBegin(b); i < blockEnd(b, p.keys.size()); ++i) {
              if (!listedHere(i)) continue;
              if (index_[p.ids[i]] != expected)
                throw Error(path_ + ": internal: the vertices come out of their key order");
              const glm::dvec3 x = finalPosition(p, uint32_t(i));
              requireFinite(x);
              encodePlyVertex(x, colours_[p.ids[i]],
                              &(*bytes)[size_t(expected - first[b]) * kPlyVertexBytes]);
              ++expected;
            }
          },
          hand, &handing, &writing);
      listed = first[blocks];
      progress_.report("write PLY", double(listed) / double(plyVertices_ + keptTriangles_));
    });
    if (writing.valid()) writing.get();
    if (listed != faceVertexStart_)
      throw Error(path_ + ": internal: " + std::to_string(listed) + " vertices listed, not " +
                  std::to_string(faceVertexStart_));
    std::string bytes(facePositions.size() * kPlyVertexBytes, '\0');
    for (size_t k = 0; k < facePositions.size(); ++k) {
      requireFinite(facePositions[k]);
      encodePlyVertex(facePositions[k], colours_[faceVertices[k]], &bytes[k * kPlyVertexBytes]);
    }
    out.write(bytes.data(), std::streamsize(bytes.size()));
    colours_ = std::vector<std::array<uint8_t, 3>>();  // read no more
  }

  // The file: its header, PLY's vertices, then the facets in the mesh's order, encoded and
  // fingerprinted as stored in parallel blocks (a few per worker at a time), written and handed
  // to the measures in order on a thread of their own while the next group of blocks is
  // encoded.
  void writeFile(StreamedMeshCheck* measures) {
    const char* stage = indexed_ ? "write PLY" : "write STL";
    progress_.report(stage, 0.0);
    writeFileAtomically(path_, [&](std::ostream& out) {
      const std::string header = indexed_ ? binaryPlyHeader(unit_, plyVertices_, keptTriangles_)
                                          : binaryStlHeader(unit_, uint32_t(keptTriangles_));
      out.write(header.data(), std::streamsize(header.size()));
      if (indexed_) writeVertices(out);
      const double before = indexed_ ? double(plyVertices_) : 0.0;
      uint64_t kept = 0;
      std::vector<EncodedBlock> handing;  // the group being written and measured
      std::future<void> writing;          // declared after it: waited for first if a throw
      const auto hand = [&] {
        for (EncodedBlock& block : handing) {
          out.write(block.bytes.data(), std::streamsize(block.bytes.size()));
          if (!block.corners.empty()) measures->add(std::move(block.corners));
          if (!block.exactCorners.empty()) measures->add(std::move(block.exactCorners));
        }
      };
      eachPiece([&](const Piece& p) {
        const std::vector<uint64_t> at = keptPlaces(p, &kept);
        // Sized by the block's kept triangles on the worker, at least its facets (the measures'
        // bound on what they hold counts facets).
        writeBlocks<EncodedBlock>(
            at.size() - 1,
            [&](size_t b, EncodedBlock* block) {
              const size_t facets = size_t(at[b + 1] - at[b]);
              block->bytes.reserve(facets * (indexed_ ? kPlyFaceBytes : kStlFacetBytes));
              (indexed_ ? block->exactCorners.reserve(3 * facets)
                        : block->corners.reserve(3 * facets));
              encodeBlock(p, at, b, block);
            },
            [&] {
              for (const EncodedBlock& block : handing) {
                fingerprint_.triangles += block.fingerprint.triangles;
                fingerprint_.sum += block.fingerprint.sum;
                fingerprint_.mixedSum += block.fingerprint.mixedSum;
              }
              hand();
            },
            &handing, &writing);
        progress_.report(stage, (before + double(kept)) / (before + double(keptTriangles_)));
      });
      if (writing.valid()) writing.get();
      if (fingerprint_.triangles != keptTriangles_)
        throw Error(path_ + ": internal: " + std::to_string(fingerprint_.triangles) +
                    " facets written, not " + std::to_string(keptTriangles_));
      progress_.check();  // a cancel during the write replaces nothing
    });
  }

  const Scene& scene_;
  const std::string path_;
  const ExportTiling tiling_;
  Progress& progress_;
  ExportReport& report_;
  ContourReport& r_;
  const StoredCoordinate stored_;
  ScratchFile scratch_;
  const Grid grid_;
  int nextSlab_ = 0;
  std::unordered_map<uint64_t, uint32_t> below_, faces_;  // keys -> ids
  std::string unit_ = "millimetre";
  UnionFind sets_{0};  // over global vertex ids; after pass 1 each id's parent is its root
  std::vector<uint32_t> vertexCount_;  // per root, until dropSpecks
  std::vector<uint8_t> droppedRoot_;   // per root from dropSpecks on, where any was dropped
  std::vector<PieceRecord> pieces_;
  uint64_t triangles_ = 0, keptTriangles_ = 0;
  std::unordered_map<uint32_t, Shell> shells_;  // by root
  std::unordered_map<uint32_t, Bounds> boxes_;  // by root, the small components'
  bool anyInverted_ = false;
  std::unordered_map<uint32_t, glm::dvec3> moved_;  // ids of unfolded shells
  // By place among the kept triangles, increasing (replacementAt).
  std::vector<std::pair<uint64_t, Replacement>> repaired_;
  TriangleFingerprint fingerprint_;
  Bounds used_;  // around the corners the facets use, as stored
  // PLY (indexed_): the leaves' styles; the face vertices' (key, id), in key order; per id its
  // index in the file (kNoId: not listed) and colour; how many the file lists, and the index of
  // the first face vertex.
  const bool indexed_;
  std::map<uint32_t, LeafStyle> leafStyles_;
  std::vector<std::pair<uint64_t, uint32_t>> faceIds_;
  std::vector<uint32_t> index_;
  std::vector<std::array<uint8_t, 3>> colours_;
  uint64_t plyVertices_ = 0, faceVertexStart_ = 0;
  // The last piece merged, being spilled to the scratch file (into pieces_) by spilling_;
  // declared last: destroyed (waited for) first.
  Piece spilled_;
  std::future<void> spilling_;
};

StreamedExportWriter::StreamedExportWriter(const Scene& scene, const std::string& path,
                                           const ExportOptions& options, const ExportTiling& tiling,
                                           Progress& progress, ExportReport* report) {
  const std::string refusal = streamedExportRefusal(path, options);
  if (!refusal.empty()) throw Error(path + ": " + refusal);
  impl_ = std::make_unique<Impl>(scene, path, tiling, progress, *report);
}

StreamedExportWriter::~StreamedExportWriter() = default;

void StreamedExportWriter::addSlab(int z, std::vector<TileContour> tiles) {
  impl_->addSlab(z, std::move(tiles));
}

void StreamedExportWriter::finish() {
  impl_->finish();
}

ExportTiling streamedTiling(const Scene& scene, const ContourOptions& options, uint64_t memoryBytes,
                            uint64_t offsetBytesPerNode) {
  const ExportTiling cubes = exportTiling(scene, options, memoryBytes, offsetBytesPerNode);
  if (options.tileCells > 0) return cubes;  // --tile: the user's cubes
  // Slabs of the whole x and y extent whose windows hold no more nodes than a cube's (what the
  // memory allowed it), at least kStreamedSlabs of them, and cells indexed in 32 bits.
  const Grid& g = cubes.grid;
  const double plane = double(g.cells.x + 3) * double(g.cells.y + 3);
  const double cube = std::pow(double(cubes.tileCells + 2 * cubes.halo + 3), 3.0);
  int depth = std::min((g.cells.z + kStreamedSlabs - 1) / kStreamedSlabs,
                       int(cube / plane) - 2 * cubes.halo - 3);
  const double indexable = double(UINT32_MAX) / (double(g.cells.x + 2) * double(g.cells.y + 2));
  depth = std::min(depth, int(indexable) - 2 * cubes.halo - 2);
  if (depth < kMinStreamedTile) return cubes;
  // (A side under 8 cells is a tile's least: the tile then reaches past the grid there.)
  const ExportTiling slabs = exportTilingOfSize(
      scene, options, glm::ivec3(std::max(g.cells.x, 8), std::max(g.cells.y, 8), depth));
  // Where the modifiers' halo makes thin slabs evaluate more than twice the grid's nodes (each
  // slab's window grown by it along z: twice the halo over a slab's depth), cubes no larger
  // than the export's in at least kStreamedSlabs layers if they evaluate fewer: faster, and a
  // layer holds at most an eighth of the mesh, as a slab does at the least (but more than thin
  // slabs: the estimate follows the tiling chosen). Short of that the slabs' smaller share of
  // the mesh is worth their extra evaluation.
  const double gridNodes = double(g.cells.x + 1) * double(g.cells.y + 1) * double(g.cells.z + 1);
  const double slabNodes = slabs.evaluatedNodes();
  if (slabNodes <= kStreamedHaloWork * gridNodes) return slabs;
  const int edge = std::min(cubes.tileCells, (g.cells.z + kStreamedSlabs - 1) / kStreamedSlabs);
  const ExportTiling layers = exportTilingOfSize(scene, options, glm::ivec3(edge));
  return layers.evaluatedNodes() < slabNodes ? layers : slabs;
}

std::string streamedExportRefusal(const std::string& path, const ExportOptions& options) {
  const std::string extension = lowerExtension(path);
  if (extension != "stl" && extension != "ply")
    return "--stream writes binary STL (.stl) or PLY (.ply) only: OBJ and 3MF are written from "
           "the whole mesh";
  if (options.simplifyCells > 0.0)
    return "--stream and --simplify do not go together: simplifying needs the whole mesh";
  return "";
}

int streamedSlabsAhead(int workers, int slabs) {
  return std::clamp(workers, 1, std::max(1, slabs / kStreamedSlabs));
}

ExportReport exportSceneStreamed(const Scene& scene, const std::string& path,
                                 const ExportOptions& options, std::shared_ptr<Backend> backend,
                                 Progress& progress, const FallbackNotice& notice) {
  return exportSceneStreamed(scene, path, options, {std::move(backend)}, 1, progress, notice);
}

ExportReport exportSceneStreamed(const Scene& scene, const std::string& path,
                                 const ExportOptions& options,
                                 const std::vector<std::shared_ptr<Backend>>& backends,
                                 int workersPerMemory, Progress& progress,
                                 const FallbackNotice& notice) {
  ExportReport report;
  const WorkersMemory memory = workersMemory(backends, workersPerMemory);
  const ExportTiling tiling =
      streamedTiling(scene, options, memory.bytes, memory.offsetBytesPerNode);
  StreamedExportWriter writer(scene, path, options, tiling, progress, &report);
  // The workers contour the tiles (each on its own window; a backend that cannot evaluate the
  // modifiers or runs out of memory hands its tiles left to the CPU: fallback.h) at most
  // `ahead` slabs past the last slab handed to the writer, which merges it meanwhile on this
  // thread.
  const int perSlab = tiling.counts.x * tiling.counts.y, slabs = tiling.counts.z;
  const int ahead = streamedSlabsAhead(int(backends.size()), slabs);
  std::mutex mutex;  // guards the three below
  std::condition_variable changed;
  std::vector<std::vector<TileContour>> slabTiles(static_cast<size_t>(slabs));
  std::vector<int> slabDone(size_t(slabs), 0);
  int handed = 0;                                   // slabs handed to the writer
  const auto poll = std::chrono::milliseconds(50);  // for a cancel or a failure, not notified
  TileWorkers workers(
      scene, backends, tiling, progress,
      [&](const std::string& line) {
        report.notices.push_back(line);  // the workers call it one at a time
        if (notice) notice(line);
      },
      [&](int t, const Progress& stopping) {
        std::unique_lock<std::mutex> lock(mutex);
        while (t / perSlab >= handed + ahead && !stopping.cancelled()) changed.wait_for(lock, poll);
      },
      [&](int t, std::vector<TileContour> contours) {
        std::lock_guard<std::mutex> lock(mutex);
        std::vector<TileContour>& slab = slabTiles[size_t(t / perSlab)];
        for (TileContour& c : contours) slab.push_back(std::move(c));
        ++slabDone[size_t(t / perSlab)];
        changed.notify_all();
      });
  for (int z = 0; z < slabs; ++z) {
    std::vector<TileContour> slab;
    {
      std::unique_lock<std::mutex> lock(mutex);
      while (slabDone[size_t(z)] < perSlab && !workers.stopping()) changed.wait_for(lock, poll);
      if (slabDone[size_t(z)] < perSlab) break;  // stopped: join() says why
      slab = std::move(slabTiles[size_t(z)]);
      handed = z + 1;
    }
    changed.notify_all();
    writer.addSlab(z, std::move(slab));  // a throw stops and joins the workers
  }
  std::vector<TileContour> unhanded;
  workers.join(&report.contour, &unhanded);
  if (!unhanded.empty()) throw Error(path + ": internal: tiles left out of the streamed export");
  writer.finish();
  return report;
}

}  // namespace strata
