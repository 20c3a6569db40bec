#include "engine/export/check_written.h"

#include <atomic>
#include <exception>
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

// The fingerprint of the triangles the file at `path` lists, read back as
// readMeshFileVerbatim reads it: in pieces where the format allows (visitFileTriangles: a
// binary STL never held whole), else whole.
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

}  // namespace

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

WrittenCheck checkWrittenFile(const std::string& path, TriangleMesh written, Progress& progress) {
  WrittenCheck result;
  progress.report("check", 0.0);
  const TriangleMesh meant = storedMesh(path, std::move(written));
  // The file is read back and fingerprinted on a second thread while this one measures the
  // topology of the mesh meant: the two share nothing, and each alone leaves cores idle.
  TriangleFingerprint found;
  std::exception_ptr readError;
  std::thread reader([&] {
    try {
      const InputLimitLifted ownFile;  // the file just written: no input limit refuses it
      found = fingerprintFile(path, progress);
    } catch (...) {
      readError = std::current_exception();
    }
  });
  try {
    const TriangleFingerprint expected = fingerprintTriangles(meant);
    progress.report("check", 0.1);
    result.check = checkMesh(meant, &progress);
    reader.join();
    if (readError) std::rethrow_exception(readError);
    progress.report("check", 0.9);
    if (!(found == expected)) {
      result.fileDifference =
          found.triangles != expected.triangles
              ? path + ": the file holds " + std::to_string(found.triangles) +
                    " triangles, not the " + std::to_string(expected.triangles) + " written"
              : path +
                    ": the file's triangles are not those written (a coordinate or a winding "
                    "differs)";
      progress.check();
      const InputLimitLifted ownFile;
      result.check = checkMesh(readMeshFileRaw(path), &progress);
    }
  } catch (...) {
    if (reader.joinable()) reader.join();
    throw;
  }
  progress.report("check", 1.0);
  return result;
}

}  // namespace strata
