#include "engine/export/check_written.h"

#include <atomic>
#include <exception>
#include <future>
#include <thread>
#include <utility>

#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/hash.h"
#include "engine/util/parallel_for.h"

namespace strata {

namespace {

// One triangle's two hashes, added to the sums: two order-sensitive chains over the nine
// coordinates (each step a bijection of the chain: a changed coordinate changes it), finished
// by a full avalanche.
void addTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, uint64_t* sum,
                 uint64_t* mixedSum) {
  uint64_t h = 0x243f6a8885a308d3ull, g = 0x13198a2e03707344ull;
  for (const glm::dvec3* p : {&a, &b, &c})
    for (int k = 0; k < 3; ++k) {
      const uint64_t x = coordinateBits((*p)[k]);
      h = (h ^ x) * 0x100000001b3ull;
      g = (g + x) * 0x9e3779b97f4a7c15ull;
    }
  *sum += avalanche64(h);
  *mixedSum += avalanche64(g ^ 0xa4093822299f31d0ull);
}

}  // namespace

std::string fingerprintDifference(const std::string& path, const TriangleFingerprint& found,
                                  const TriangleFingerprint& expected) {
  if (found == expected) return "";
  if (found.triangles != expected.triangles)
    return path + ": the file holds " + std::to_string(found.triangles) + " triangles, not the " +
           std::to_string(expected.triangles) + " written";
  return path + ": the file's triangles are not those written (a coordinate or a winding differs)";
}

TriangleFingerprint fingerprintFile(const std::string& path, const Progress& progress) {
  std::atomic<uint64_t> triangles{0}, sum{0}, mixedSum{0};
  const bool inPieces = visitFileTriangles(
      path,
      [&](uint64_t, const glm::dvec3* corners, size_t count) {
        uint64_t s = 0, m = 0;
        for (size_t t = 0; t < count; ++t)
          addTriangle(corners[3 * t], corners[3 * t + 1], corners[3 * t + 2], &s, &m);
        triangles += count;
        sum += s;
        mixedSum += m;
      },
      &progress);
  if (!inPieces) return fingerprintTriangles(readMeshFileVerbatim(path, nullptr, &progress));
  TriangleFingerprint f;
  f.triangles = size_t(triangles.load());
  f.sum = sum.load();
  f.mixedSum = mixedSum.load();
  return f;
}

void addToFingerprint(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      TriangleFingerprint* f) {
  ++f->triangles;
  addTriangle(a, b, c, &f->sum, &f->mixedSum);
}

TriangleFingerprint fingerprintTriangles(const TriangleMesh& mesh) {
  TriangleFingerprint f;
  f.triangles = mesh.triangles.size();
  std::atomic<uint64_t> sum{0}, mixedSum{0};  // sums commute: the order of chunks does not matter
  parallelFor(0, int64_t(mesh.triangles.size()), 65536, [&](int64_t b, int64_t e) {
    uint64_t s = 0, m = 0;
    for (int64_t t = b; t < e; ++t) {
      const auto& tri = mesh.triangles[size_t(t)];
      addTriangle(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], &s, &m);
    }
    sum += s;
    mixedSum += m;
  });
  f.sum = sum.load();
  f.mixedSum = mixedSum.load();
  return f;
}

struct MeantMeshCheck::State {
  explicit State(const Progress& parent) : progress(&parent) {}
  Progress progress;  // a child of the caller's: cancelled with it, or alone by the destructor
  std::promise<void> copied, measured;
  std::future<void> copiedFuture = copied.get_future(), measuredFuture = measured.get_future();
  MeshCheck check;
  TriangleFingerprint fingerprint;
  std::thread thread;
};

MeantMeshCheck::MeantMeshCheck(const std::string& path, const TriangleMesh& written,
                               const Progress& progress)
    : state_(std::make_unique<State>(progress)) {
  State* s = state_.get();
  s->thread = std::thread([s, path, &written] {
    bool released = false;
    try {
      const TriangleMesh meant = storedMesh(path, written);
      released = true;
      s->copied.set_value();
      s->progress.check();
      s->fingerprint = fingerprintTriangles(meant);
      s->progress.check();
      s->check = checkMesh(meant, &s->progress);
      s->measured.set_value();
    } catch (...) {
      if (!released) s->copied.set_exception(std::current_exception());
      s->measured.set_exception(std::current_exception());
    }
  });
}

MeantMeshCheck::~MeantMeshCheck() {
  state_->progress.cancel();  // a no-op once measured
  state_->thread.join();
}

void MeantMeshCheck::released() {
  state_->copiedFuture.wait();
}

void MeantMeshCheck::wait(MeshCheck* check, TriangleFingerprint* fingerprint) {
  state_->measuredFuture.get();  // rethrows
  *check = state_->check;
  *fingerprint = state_->fingerprint;
}

WrittenCheck checkWrittenFile(const std::string& path, MeantMeshCheck& meant, Progress& progress) {
  WrittenCheck result;
  progress.report("check", 0.0);
  // The file is read back and fingerprinted on this thread while the other one measures the
  // mesh meant (it may have finished during the write): the two share nothing.
  TriangleFingerprint found;
  {
    const InputLimitLifted ownFile;  // the file just written: no input limit refuses it
    found = fingerprintFile(path, progress);
  }
  progress.report("check", 0.5);
  TriangleFingerprint expected;
  meant.wait(&result.check, &expected);
  progress.report("check", 0.9);
  result.fileDifference = fingerprintDifference(path, found, expected);
  if (!result.fileDifference.empty()) {
    progress.check();
    const InputLimitLifted ownFile;
    result.check = checkMesh(readMeshFileRaw(path), &progress);
  }
  progress.report("check", 1.0);
  return result;
}

WrittenCheck checkWrittenFile(const std::string& path, const TriangleMesh& written,
                              Progress& progress) {
  MeantMeshCheck meant(path, written, progress);
  return checkWrittenFile(path, meant, progress);
}

}  // namespace strata
