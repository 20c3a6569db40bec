#include "engine/export/distributed_export.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <thread>
#include <utility>
#include <vector>

#include "engine/export/streamed_export.h"
#include "engine/util/error.h"
#include "engine/util/timer.h"

namespace strata {
namespace {

// Message tags.
constexpr int kTagTiling = 1;         // 0 -> all: int32 x 3, the tiles' cells per axis
constexpr int kTagTile = 2;           // r -> 0: a tile just finished (postTiles), then its arrays
constexpr int kTagDone = 3;           // r -> 0: the process's tiles are all sent; its counters
constexpr int kTagFailed = 4;         // r -> 0: the error's text
constexpr int kTagTileVertices = 5;   // r -> 0: a contour's vertices (postTiles)
constexpr int kTagTileTriangles = 6;  // r -> 0: a contour's triangles
// Streamed only (flow control: the slabs processes may work in, distributedSlabsAhead):
constexpr int kTagMerged = 7;  // 0 -> r: int32, the slabs merged so far (each time it grows)
constexpr int kTagFinish = 8;  // 0 -> r: r's kTagDone was read; nothing more comes to r
constexpr int kTagStop = 9;    // 0 -> r: process 0 failed; stop

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    putBytes(&value, sizeof(T));
  }
  void putBytes(const void* data, size_t size) {
    if (size == 0) return;
    const auto* p = static_cast<const uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  void putString(const std::string& s) {
    put(uint64_t(s.size()));
    putBytes(s.data(), s.size());
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

class ByteReader {
 public:
  ByteReader(const std::vector<uint8_t>& bytes, int source) : bytes_(bytes), source_(source) {}
  template <typename T>
  T get() {
    T value;
    getBytes(&value, sizeof(T));
    return value;
  }
  void getBytes(void* out, size_t size) {
    if (size == 0) return;  // an empty array's data() may be null, which memcpy must not get
    if (size > bytes_.size() - at_)
      throw Error("distributed export: process " + std::to_string(source_) +
                  " sent a truncated message");
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  std::string getString() {
    std::string s(get<uint64_t>(), '\0');
    getBytes(s.data(), s.size());
    return s;
  }
  template <typename T>
  std::vector<T> getArray() {
    const uint64_t count = get<uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(T))
      throw Error("distributed export: process " + std::to_string(source_) +
                  " sent a truncated message");
    std::vector<T> v(count);
    getBytes(v.data(), count * sizeof(T));
    return v;
  }

 private:
  const std::vector<uint8_t>& bytes_;
  int source_;
  size_t at_ = 0;
};

// One finished tile (or, when a tile had no surface, none: the tiles it added), posted to
// process 0 as soon as it is contoured so that the transfers overlap the tiles left: a header
// (the tile, then each contour's vertex and triangle counts), then each contour's vertices and
// triangles as messages of their own, straight from their arrays (the group keeps the contours
// until they are delivered) into the receiver's.
void postTiles(ProcessGroup& group, int32_t tile, std::vector<TileContour> contours) {
  ByteWriter header;
  header.put(tile);
  header.put(uint64_t(contours.size()));
  for (const TileContour& t : contours) {
    header.put(uint64_t(t.vertices.size()));
    header.put(uint64_t(t.triangles.size()));
  }
  group.post(0, kTagTile, header.bytes());
  for (TileContour& t : contours) {
    auto owner = std::make_shared<const TileContour>(std::move(t));
    group.post(0, kTagTileVertices, owner->vertices.data(),
               owner->vertices.size() * sizeof(ContourVertex), owner);
    group.post(0, kTagTileTriangles, owner->triangles.data(),
               owner->triangles.size() * sizeof(ContourTriangle), owner);
  }
}

// Appends the contours of the tile a kTagTile message announces to *tiles; returns the tile.
int32_t receiveTiles(ProcessGroup& group, const ProcessGroup::Message& m,
                     std::vector<TileContour>* tiles) {
  ByteReader in(m.bytes, m.source);
  const int32_t tile = in.get<int32_t>();
  const uint64_t count = in.get<uint64_t>();
  std::vector<std::pair<uint64_t, uint64_t>> sizes;
  for (uint64_t i = 0; i < count; ++i) {
    const uint64_t vertices = in.get<uint64_t>();
    sizes.push_back({vertices, in.get<uint64_t>()});
  }
  for (const auto& [vertices, triangles] : sizes) {
    TileContour t;
    t.vertices.resize(vertices);
    group.receiveInto(m.source, kTagTileVertices, t.vertices.data(),
                      vertices * sizeof(ContourVertex));
    t.triangles.resize(triangles);
    group.receiveInto(m.source, kTagTileTriangles, t.triangles.data(),
                      triangles * sizeof(ContourTriangle));
    tiles->push_back(std::move(t));
  }
  return tile;
}

// The process's contour counters, once its tiles are all posted.
std::vector<uint8_t> doneMessage(const ContourReport& r) {
  ByteWriter w;
  w.put(r.surfels);
  w.put(uint64_t(r.tileLdiBytes));
  w.put(r.synthesizedCrossings);
  w.put(r.signDisagreements);
  w.put(r.evaluateSeconds);
  w.put(r.contourSeconds);
  w.put(uint64_t(r.warnings.size()));
  for (const std::string& s : r.warnings) w.putString(s);
  return w.bytes();
}

void receiveDone(const ProcessGroup::Message& m, ContourReport* r) {
  ByteReader in(m.bytes, m.source);
  r->surfels += in.get<uint64_t>();
  r->tileLdiBytes = std::max<size_t>(r->tileLdiBytes, size_t(in.get<uint64_t>()));
  r->synthesizedCrossings += in.get<uint64_t>();
  r->signDisagreements += in.get<uint64_t>();
  r->evaluateSeconds += in.get<double>();
  r->contourSeconds += in.get<double>();
  std::vector<std::string> warnings;
  for (uint64_t i = 0, n = in.get<uint64_t>(); i < n; ++i) warnings.push_back(in.getString());
  addWarnings(warnings, r);
}

std::vector<uint8_t> int32Message(int32_t value) {
  std::vector<uint8_t> bytes(sizeof(value));
  std::memcpy(bytes.data(), &value, sizeof(value));
  return bytes;
}

// What process r (> 0) of a streamed export knows of process 0's merge: it reads process 0's
// messages (kTagMerged, kTagFinish, kTagStop) as they come and waits where it must.
class MergeWatch {
 public:
  MergeWatch(ProcessGroup& group, Progress& progress) : group_(group), progress_(progress) {}
  // Returns once fewer than `ahead` slabs before `slab` are still to be merged.
  void waitForRoom(int slab, int ahead) {
    readArrived();
    while (slab >= merged_ + ahead) waitForOne();
  }
  // Returns once process 0 read this process's last message (kTagFinish).
  void waitForFinish() {
    readArrived();
    while (!finished_) waitForOne();
  }

 private:
  void take(const ProcessGroup::Message& m) {
    if (m.source != 0 || (m.tag != kTagMerged && m.tag != kTagFinish && m.tag != kTagStop))
      throw Error("distributed export: unexpected message " + std::to_string(m.tag) +
                  " from process " + std::to_string(m.source));
    if (m.tag == kTagStop) throw Error("process 0 stopped the export");
    if (m.tag == kTagFinish) {
      finished_ = true;
      return;
    }
    if (m.bytes.size() != sizeof(int32_t))
      throw Error("distributed export: process 0 sent a merge count of the wrong size");
    int32_t merged = 0;
    std::memcpy(&merged, m.bytes.data(), sizeof(merged));
    merged_ = std::max(merged_, int(merged));
  }
  void readArrived() {
    ProcessGroup::Message m;
    while (group_.receive(&m, false)) take(m);
  }
  // Takes the next message; checks for a cancel (Ctrl-C) every millisecond meanwhile.
  void waitForOne() {
    ProcessGroup::Message m;
    while (!group_.receive(&m, false)) {
      progress_.check();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    take(m);
  }

  ProcessGroup& group_;
  Progress& progress_;
  int merged_ = 0;
  bool finished_ = false;
};

// Test hook (tests/app/cli_distributed_test.cpp): STRATA_TEST_KILL_PROCESS=R makes process R
// kill itself once its first tile is done, as a crashed or killed rank would.
void maybeKillForTest(int rank) {
  const char* env = std::getenv("STRATA_TEST_KILL_PROCESS");
  if (env && *env && std::atoi(env) == rank) std::raise(SIGKILL);
}

}  // namespace

ExportReport exportSceneDistributed(const Scene& scene, const std::string& path,
                                    const ExportOptions& options, std::shared_ptr<Backend> backend,
                                    ProcessGroup& group, Progress& progress,
                                    DistributedShare* share, const FallbackNotice& notice) {
  const int rank = group.rank(), size = group.size();
  ExportReport report;
  ContourReport& r = report.contour;
  std::vector<TileContour> tiles;
  Stopwatch own;
  int given = 0;  // tiles this process contoured (empty ones included)
  if (rank != 0) {
    try {
      ProcessGroup::Message m;
      group.receive(&m, true);
      if (m.tag != kTagTiling) throw Error("distributed export: expected the tiling first");
      if (m.bytes.size() != 3 * sizeof(int32_t))
        throw Error("distributed export: process 0 sent a tiling of the wrong size");
      int32_t cells[3];
      std::memcpy(cells, m.bytes.data(), sizeof(cells));
      const ExportTiling tiling =
          exportTilingOfSize(scene, options, glm::ivec3(cells[0], cells[1], cells[2]));
      const auto mine = [&](int t) { return t % size == rank; };
      const int perSlab = tiling.counts.x * tiling.counts.y;
      const int ahead = distributedSlabsAhead(size, perSlab);
      MergeWatch merge(group, progress);
      size_t posted = 0;  // tiles[0, posted) were posted, their arrays released
      contourTilesWithFallback(scene, backend, tiling, mine, progress, r, &tiles, notice,
                               [&](int t) {
                                 ++given;
                                 std::vector<TileContour> finished;
                                 for (; posted < tiles.size(); ++posted)
                                   finished.push_back(std::move(tiles[posted]));
                                 postTiles(group, t, std::move(finished));
                                 maybeKillForTest(rank);
                                 const int next = t + size;
                                 if (options.streamed && next < tiling.count())
                                   merge.waitForRoom(next / perSlab, ahead);
                               });
      group.post(0, kTagDone, doneMessage(r));
      group.flush();
      if (options.streamed) merge.waitForFinish();
    } catch (const std::exception& e) {
      const std::string text = e.what();
      group.send(0, kTagFailed, text.data(), text.size());
      throw;
    }
    if (share) *share = DistributedShare{size, r.tiles, given, own.seconds(), 0.0};
    return report;
  }

  const ExportTiling tiling =
      options.streamed
          ? streamedTiling(scene, options, backend->memoryAvailable(),
                           backend->offsetBytesPerNode())
          : exportTiling(scene, options, backend->memoryAvailable(), backend->offsetBytesPerNode());
  const int32_t tileSize[3] = {tiling.size.x, tiling.size.y, tiling.size.z};
  // Streamed (options.streamed): each slab of tiles goes to the writer once all its tiles are
  // in, from here or from the others, in increasing z; the tiles of slabs not complete yet wait.
  std::unique_ptr<StreamedExportWriter> writer;
  if (options.streamed)
    writer =
        std::make_unique<StreamedExportWriter>(scene, path, options, tiling, progress, &report);
  const int perSlab = tiling.counts.x * tiling.counts.y;
  const int ahead = distributedSlabsAhead(size, perSlab);
  std::map<int, std::vector<TileContour>> waiting;  // by slab
  std::vector<int> slabTilesIn(size_t(tiling.counts.z), 0);
  int nextSlab = 0, mostSlabsHeld = 0;
  // Streamed: the processes whose kTagDone was read (nothing more is sent to them but kTagFinish).
  std::vector<bool> done(size_t(size), false);
  const auto tileIn = [&](int tile, std::vector<TileContour>* contours) {
    const int z = tile / perSlab;
    std::vector<TileContour>& slab = waiting[z];
    for (TileContour& t : *contours) slab.push_back(std::move(t));
    contours->clear();
    ++slabTilesIn[size_t(z)];
    mostSlabsHeld = std::max(mostSlabsHeld, int(waiting.size()));
    const int merged = nextSlab;
    while (nextSlab < tiling.counts.z && slabTilesIn[size_t(nextSlab)] == perSlab) {
      std::vector<TileContour> complete = std::move(waiting[nextSlab]);
      waiting.erase(nextSlab);
      writer->addSlab(nextSlab++, std::move(complete));
    }
    if (nextSlab > merged)
      for (int p = 1; p < size; ++p)
        if (!done[size_t(p)]) group.post(p, kTagMerged, int32Message(nextSlab));
  };
  for (int p = 1; p < size; ++p) group.send(p, kTagTiling, tileSize, sizeof(tileSize));
  try {
    int finished = 0, reported = 1;  // tiles finished anywhere; processes whose tiles are in
    std::vector<TileContour> others;
    ContourReport fromOthers;
    const auto handle = [&](const ProcessGroup::Message& m) {
      if (m.tag == kTagTile) {
        if (writer) {
          std::vector<TileContour> contours;
          tileIn(receiveTiles(group, m, &contours), &contours);
        } else {
          receiveTiles(group, m, &others);
        }
        ++finished;
      } else if (m.tag == kTagDone) {
        receiveDone(m, &fromOthers);
        ++reported;
        if (writer && m.source > 0 && m.source < size && !done[size_t(m.source)]) {
          done[size_t(m.source)] = true;
          group.post(m.source, kTagFinish, std::vector<uint8_t>());
        }
      } else if (m.tag == kTagFailed) {
        throw Error("process " + std::to_string(m.source) + " of " + std::to_string(size) +
                    " failed: " + std::string(m.bytes.begin(), m.bytes.end()));
      } else {
        throw Error("distributed export: unexpected message " + std::to_string(m.tag) +
                    " from process " + std::to_string(m.source));
      }
      progress.report("export", double(finished) / tiling.count());
    };
    const auto drain = [&](bool wait) {
      ProcessGroup::Message m;
      while (group.receive(&m, wait)) {
        handle(m);
        if (wait) return;
      }
    };
    const auto mine = [&](int t) { return t % size == 0; };
    size_t taken = 0;  // tiles[0, taken) went to the writer
    contourTilesWithFallback(scene, backend, tiling, mine, progress, r, &tiles, notice, [&](int t) {
      ++given;
      ++finished;
      if (writer) {
        std::vector<TileContour> contours;
        for (; taken < tiles.size(); ++taken) contours.push_back(std::move(tiles[taken]));
        tileIn(t, &contours);
      }
      drain(false);
      progress.report("export", double(finished) / tiling.count());
      // Streamed: this process too starts its next tile only in the slabs the others may work in.
      const int next = t + size;
      while (writer && next < tiling.count() && next / perSlab >= nextSlab + ahead) {
        progress.check();
        drain(true);
      }
    });
    const double ownSeconds = own.seconds();
    while (reported < size) {
      progress.check();
      drain(true);
    }
    const double allTilesSeconds = own.seconds();
    group.flush();
    addTileCounts(fromOthers, &r);  // tileLdiBytes, surfels, crossings, disagreements, warnings
    r.evaluateSeconds += fromOthers.evaluateSeconds;
    r.contourSeconds += fromOthers.contourSeconds;
    if (writer) {
      writer->finish();
    } else {
      for (TileContour& t : others) tiles.push_back(std::move(t));
      others.clear();
      ExportMesh mesh = meshFromTiles(scene, std::move(tiles), progress, r);
      writeAndCheckExport(std::move(mesh), path, options, progress, &report);
    }
    if (share)
      *share =
          DistributedShare{size, tiling.count(), given, ownSeconds, allTilesSeconds, mostSlabsHeld};
    return report;
  } catch (...) {
    // The others may be waiting for room or for their kTagFinish: tell them to stop.
    if (writer)
      for (int p = 1; p < size; ++p)
        if (!done[size_t(p)]) {
          try {
            group.post(p, kTagStop, std::vector<uint8_t>());
          } catch (...) {  // a transport that failed: the error being thrown says why
          }
        }
    throw;
  }
}

int distributedSlabsAhead(int processes, int tilesPerSlab) {
  tilesPerSlab = std::max(1, tilesPerSlab);
  return 2 * std::max(1, (processes + tilesPerSlab - 1) / tilesPerSlab);
}

}  // namespace strata
