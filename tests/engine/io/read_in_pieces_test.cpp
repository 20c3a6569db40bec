// visitFileTriangles: a file read in pieces lists exactly the triangles readMeshFileVerbatim
// lists (every triangle once, the same corners, across more than one piece), refuses what is
// not its form (so the caller reads the file whole and gets the reader's message), names a
// non-finite coordinate as the reader does, and honours cancel. Written against the format
// table: every format with a block reader is tested.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/mesh_formats.h"
#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/error.h"
#include "tests/support/fresh_path.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

std::string freshPath(const std::string& name) {
  return test::freshPath("strata_read_in_pieces", name);
}

// A strip of `count` triangles with coordinates no two triangles share (so that a triangle
// visited twice, or at the wrong index, shows).
ExportMesh strip(size_t count) {
  ExportMesh em;
  for (size_t i = 0; i < count + 2; ++i)
    em.mesh.positions.push_back(
        {double(i) * 0.25, double(i % 2) + 0.001 * double(i % 7), std::sin(double(i) * 0.01)});
  for (uint32_t i = 0; i < count; ++i) {
    em.mesh.triangles.push_back(i % 2 ? std::array<uint32_t, 3>{i, i + 2, i + 1}
                                      : std::array<uint32_t, 3>{i, i + 1, i + 2});
    em.triangleLeaf.push_back(1);
  }
  em.leaves[1] = {"strip", {1.0f, 1.0f, 1.0f}};
  return em;
}

struct Visited {
  std::vector<glm::dvec3> corners;
  std::vector<int> times;  // per triangle
};

Visited visitAll(const std::string& path, bool* inPieces, const Progress* progress = nullptr) {
  Visited v;
  std::mutex mutex;
  *inPieces = visitFileTriangles(
      path,
      [&](uint64_t first, const glm::dvec3* corners, size_t count) {
        std::lock_guard<std::mutex> lock(mutex);
        if (v.times.size() < first + count) {
          v.times.resize(first + count, 0);
          v.corners.resize(3 * (first + count));
        }
        for (size_t i = 0; i < 3 * count; ++i) v.corners[3 * first + i] = corners[i];
        for (size_t t = first; t < first + count; ++t) ++v.times[t];
      },
      progress);
  return v;
}

TEST(ReadInPieces, ListsWhatTheVerbatimReadListsAcrossPieces) {
  // More triangles than one piece holds (2^18), and not a multiple of a block.
  const ExportMesh em = strip((size_t(1) << 18) + 4099);
  int formats = 0;
  for (const MeshFormat& format : meshFormats()) {
    if (!format.blocks || !format.write) continue;
    ++formats;
    SCOPED_TRACE(format.label);
    const std::string path = freshPath("strip." + format.extensions[0]);
    writeMeshFile(path, em);
    bool inPieces = false;
    const Visited v = visitAll(path, &inPieces);
    ASSERT_TRUE(inPieces);
    const TriangleMesh whole = readMeshFileVerbatim(path);
    ASSERT_EQ(v.times.size(), whole.triangles.size());
    for (size_t t = 0; t < whole.triangles.size(); ++t) {
      ASSERT_EQ(v.times[t], 1) << t;
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(v.corners[3 * t + size_t(c)], whole.positions[whole.triangles[t][size_t(c)]])
            << t << " " << c;
    }
  }
  EXPECT_GE(formats, 2);  // binary STL and PLY at least
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What the whole read and the read in pieces say of `path` ("" where it reads); `inPieces`:
// whether the pieces took it.
std::pair<std::string, std::string> bothMessages(const std::string& path, bool* inPieces) {
  std::string whole, pieces;
  try {
    readMeshFileVerbatim(path);
  } catch (const Error& e) {
    whole = e.what();
  }
  try {
    visitAll(path, inPieces);
  } catch (const Error& e) {
    pieces = e.what();
  }
  return {whole, pieces};
}

// A binary PLY whose faces use vertices far apart (not the streamed export's order: pages read
// and let go as they come) is read as the whole read lists it, and what is wrong with one is
// named as the whole read names it: a coordinate not finite (the first in the file, even one no
// face uses), an index out of range, a file cut short, data after the faces.
TEST(ReadInPieces, BinaryPlyScatteredAndBrokenAsTheWholeRead) {
  ExportMesh em;
  const size_t n = 300000;  // vertices: five pages of 2^16
  for (size_t i = 0; i < n; ++i)
    em.mesh.positions.push_back({double(i), double(i % 13) * 0.5, double(i % 101) * 0.25});
  for (uint32_t t = 0; t < 200000; ++t) {
    const uint32_t a = uint32_t((uint64_t(t) * 7919) % n),
                   b = uint32_t((uint64_t(t) * 104729 + 1) % n),
                   c = uint32_t((uint64_t(t) * 15485863 + 2) % n);
    if (a == b || b == c || a == c) continue;
    em.mesh.triangles.push_back({a, b, c});
    em.triangleLeaf.push_back(1);
  }
  em.leaves[1] = {"scattered", {1.0f, 1.0f, 1.0f}};
  const std::string path = freshPath("scattered.ply");
  writeMeshFile(path, em);
  bool inPieces = false;
  const Visited v = visitAll(path, &inPieces);
  ASSERT_TRUE(inPieces);
  ASSERT_EQ(v.times.size(), em.mesh.triangles.size());
  for (size_t t = 0; t < em.mesh.triangles.size(); ++t) {
    ASSERT_EQ(v.times[t], 1) << t;
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(v.corners[3 * t + size_t(c)], em.mesh.positions[em.mesh.triangles[t][size_t(c)]]);
  }
  const std::string good = fileBytes(path);
  const size_t body = good.find("end_header\n") + 11;
  const size_t record = 3 * 8 + 3;
  const size_t faces = body + n * record;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto broken = [&](const std::string& name, const std::function<void(std::string&)>& edit,
                          const std::string& expected) {
    SCOPED_TRACE(name);
    std::string bytes = good;
    edit(bytes);
    const std::string file = freshPath(name + ".ply");
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
    bool taken = false;
    const auto [whole, pieces] = bothMessages(file, &taken);
    EXPECT_NE(whole.find(expected), std::string::npos) << whole;
    EXPECT_EQ(pieces, whole);
  };
  // Vertices 250,000 (page 3) and 70,000 (page 1): the earlier one is named.
  broken(
      "nan",
      [&](std::string& b) {
        for (size_t vertex : {250000u, 70000u})
          std::memcpy(&b[body + record * vertex + 8], &nan, 8);
      },
      std::to_string(body + record * 70000 + 8));
  broken(
      "index",
      [&](std::string& b) {
        const int32_t far = int32_t(n);
        std::memcpy(&b[faces + 13 * 150000 + 1 + 4], &far, 4);
      },
      "vertex index " + std::to_string(n) + " is out of range");
  broken(
      "cut", [&](std::string& b) { b.resize(b.size() - 20); }, "unexpected end of file");
  broken(
      "extra", [&](std::string& b) { b += "more"; }, "4 bytes of data after the last element");
}

// The first page read is not the first in the file and holds a coordinate not finite: the pages
// before it are read and checked first (one no face uses among them), and the error names the
// first in the file, as the whole read does.
TEST(ReadInPieces, ANonFiniteCoordinateInALaterPageIsNamedAfterTheEarlierOnes) {
  ExportMesh em;
  const size_t n = 200000;  // pages of 2^16: the faces use only the third
  for (size_t i = 0; i < n; ++i)
    em.mesh.positions.push_back({double(i), double(i % 7), double(i % 11) * 0.5});
  for (uint32_t v = 140000; v + 2 < 190000; v += 3) {
    em.mesh.triangles.push_back({v, v + 1, v + 2});
    em.triangleLeaf.push_back(1);
  }
  em.leaves[1] = {"late", {1.0f, 1.0f, 1.0f}};
  const std::string path = freshPath("late_nan.ply");
  writeMeshFile(path, em);
  std::string bytes = fileBytes(path);
  const size_t body = bytes.find("end_header\n") + 11, record = 3 * 8 + 3;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (size_t vertex : {150000u, 10000u}) std::memcpy(&bytes[body + record * vertex + 16], &nan, 8);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  bool inPieces = false;
  const auto [whole, pieces] = bothMessages(path, &inPieces);
  EXPECT_NE(whole.find(std::to_string(body + record * 10000 + 16)), std::string::npos) << whole;
  EXPECT_EQ(pieces, whole);
}

TEST(ReadInPieces, LeavesOtherFilesToTheWholeRead) {
  const ExportMesh em = strip(10);
  bool inPieces = true;
  // Another format.
  const std::string obj = freshPath("strip.obj");
  writeMeshFile(obj, em);
  visitAll(obj, &inPieces);
  EXPECT_FALSE(inPieces);
  // An ascii PLY.
  const std::string asciiPly = freshPath("ascii.ply");
  std::ofstream(asciiPly) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
                             "0 1 0\n3 0 1 2\n";
  visitAll(asciiPly, &inPieces);
  EXPECT_FALSE(inPieces);
  inPieces = true;
  // An ASCII STL.
  const std::string ascii = freshPath("ascii.stl");
  std::ofstream(ascii) << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                          "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
  inPieces = true;
  visitAll(ascii, &inPieces);
  EXPECT_FALSE(inPieces);
  // A binary STL whose count does not match its size: the whole read names the mismatch.
  const std::string cut = freshPath("cut.stl");
  writeMeshFile(cut, em);
  fs::resize_file(cut, fs::file_size(cut) - 7);
  inPieces = true;
  const Visited v = visitAll(cut, &inPieces);
  EXPECT_FALSE(inPieces);
  EXPECT_TRUE(v.times.empty());
  try {
    readMeshFileVerbatim(cut);
    ADD_FAILURE() << "a truncated STL was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

TEST(ReadInPieces, NamesANonFiniteCoordinateAsTheReaderDoes) {
  const ExportMesh em = strip(300000);
  const std::string path = freshPath("nan.stl");
  writeMeshFile(path, em);
  // Facet 290,000's second corner's z (in the second piece), then an earlier one in the same
  // piece: the first in file order is named.
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    bytes = s.str();
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (size_t facet : {290000u, 280000u})
    std::memcpy(&bytes[84 + 50 * facet + 12 + 12 + 8], &nan, 4);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  std::string whole, pieces;
  try {
    readMeshFileVerbatim(path);
  } catch (const Error& e) {
    whole = e.what();
  }
  bool inPieces = false;
  try {
    visitAll(path, &inPieces);
  } catch (const Error& e) {
    pieces = e.what();
  }
  EXPECT_NE(whole.find(std::to_string(84 + 50 * 280000 + 12 + 12 + 8)), std::string::npos) << whole;
  EXPECT_EQ(pieces, whole);
}

TEST(ReadInPieces, HonoursCancel) {
  const std::string path = freshPath("cancel.stl");
  writeMeshFile(path, strip(100));
  Progress cancelled;
  cancelled.cancel();
  bool inPieces = false;
  EXPECT_THROW(visitAll(path, &inPieces, &cancelled), Cancelled);
}

}  // namespace
}  // namespace strata
