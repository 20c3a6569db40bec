// Mesh readers: every malformed input names the file, the line or byte, and the problem; every
// format round-trips a unit cube written here into a temporary directory; the reference meshes
// in tests/data read watertight with their known volumes and genera.
#include "engine/io/mesh_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <utility>

#include "engine/geometry/mesh_check.h"
#include "engine/util/error.h"

namespace strata {
namespace {

// ---- A unit cube, and writers for each format ----

const double kCubeCorners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
// Outward, counter-clockwise seen from outside.
const int kCubeTriangles[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                   {0, 1, 5}, {0, 5, 4}, {3, 7, 6}, {3, 6, 2},
                                   {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};

// OBJ text of the cube; `flipped` lists triangles written with reversed winding, `skip` one
// triangle left out (-1: none), `offset` moves and `size` scales it.
std::string cubeObj(std::initializer_list<int> flipped = {}, int skip = -1, double offset = 0.0,
                    double size = 1.0, int firstIndex = 1) {
  std::ostringstream s;
  s.precision(17);
  for (const auto& c : kCubeCorners) {
    s << "v " << offset + size * c[0] << " " << offset + size * c[1] << " " << offset + size * c[2]
      << "\n";
  }
  for (int t = 0; t < 12; ++t) {
    if (t == skip) continue;
    bool flip = false;
    for (int f : flipped) flip |= f == t;
    const int* v = kCubeTriangles[t];
    s << "f " << firstIndex + v[0] << " " << firstIndex + (flip ? v[2] : v[1]) << " "
      << firstIndex + (flip ? v[1] : v[2]) << "\n";
  }
  return s.str();
}

std::initializer_list<int> allTriangles() {
  static const std::initializer_list<int> all = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  return all;
}

std::string cubeAsciiStl(double size = 1.0) {
  std::ostringstream s;
  s << "solid cube\n";
  for (const auto& t : kCubeTriangles) {
    s << "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const double* c = kCubeCorners[t[k]];
      s << "      vertex " << size * c[0] << " " << size * c[1] << " " << size * c[2] << "\n";
    }
    s << "    endloop\n  endfacet\n";
  }
  s << "endsolid cube\n";
  return s.str();
}

template <typename T>
void putLittle(std::string& out, T value) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(reinterpret_cast<const char*>(raw), sizeof(T));  // the test hosts are little-endian
}

template <typename T>
void putBig(std::string& out, T value) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  for (size_t i = sizeof(T); i-- > 0;) out.push_back(static_cast<char>(raw[i]));
}

std::string cubeBinaryStl(const std::string& headerStart = "binary cube",
                          uint32_t claimedCount = 12) {
  std::string s = headerStart;
  s.resize(80, ' ');
  putLittle<uint32_t>(s, claimedCount);
  for (const auto& t : kCubeTriangles) {
    for (int k = 0; k < 3; ++k) putLittle<float>(s, 0.0f);
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a < 3; ++a) putLittle<float>(s, static_cast<float>(kCubeCorners[t[k]][a]));
    }
    putLittle<uint16_t>(s, 0);
  }
  return s;
}

// PLY with vertex x y z (plus a colour), face vertex_indices, and an extra `edge` element with
// a list property that readers must skip. `vertexCount` may lie.
std::string cubePlyHeader(const std::string& format, int vertexCount = 8,
                          const std::string& coordType = "float",
                          const std::string& indexName = "vertex_indices") {
  std::ostringstream s;
  s << "ply\nformat " << format << " 1.0\ncomment made by the test\n"
    << "element vertex " << vertexCount << "\n"
    << "property " << coordType << " x\nproperty " << coordType << " y\nproperty " << coordType
    << " z\nproperty uchar red\n"
    << "element face 12\nproperty list uchar int " << indexName << "\n"
    << "element edge 1\nproperty list ushort short ends\nproperty int weight\n"
    << "end_header\n";
  return s.str();
}

std::string cubeAsciiPly(int vertexCount = 8, const std::string& indexName = "vertex_indices",
                         double size = 1.0) {
  std::string s = cubePlyHeader("ascii", vertexCount, size == 1.0 ? "float" : "double", indexName);
  std::ostringstream b;
  for (const auto& c : kCubeCorners) {
    b << size * c[0] << " " << size * c[1] << " " << size * c[2] << " 255\n";
  }
  for (const auto& t : kCubeTriangles) b << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  b << "2 0 1 7\n";
  return s + b.str();
}

std::string cubeBinaryPly(bool bigEndian, bool doubles = false, int vertexCount = 8) {
  std::string s = cubePlyHeader(bigEndian ? "binary_big_endian" : "binary_little_endian",
                                vertexCount, doubles ? "double" : "float");
  auto put = [&](auto value) {
    if (bigEndian) {
      putBig(s, value);
    } else {
      putLittle(s, value);
    }
  };
  for (const auto& c : kCubeCorners) {
    for (int a = 0; a < 3; ++a) {
      if (doubles) {
        put(c[a]);
      } else {
        put(static_cast<float>(c[a]));
      }
    }
    put(static_cast<uint8_t>(255));
  }
  for (const auto& t : kCubeTriangles) {
    put(static_cast<uint8_t>(3));
    for (int k = 0; k < 3; ++k) put(static_cast<int32_t>(t[k]));
  }
  put(static_cast<uint16_t>(2));
  put(static_cast<int16_t>(0));
  put(static_cast<int16_t>(1));
  put(static_cast<int32_t>(7));
  return s;
}

std::string cubeOff(int vertexCount = 8, int faceCount = 12, double size = 1.0) {
  std::ostringstream s;
  s << "OFF\n# a unit cube\n" << vertexCount << " " << faceCount << " 18\n";
  for (const auto& c : kCubeCorners) {
    s << size * c[0] << " " << size * c[1] << " " << size * c[2] << "\n";
  }
  for (const auto& t : kCubeTriangles) {
    s << "3 " << t[0] << " " << t[1] << " " << t[2] << " 0.5 0.5 0.5\n";
  }
  return s.str();
}

std::string writeTemp(const std::string& fileName, const std::string& bytes) {
  const std::string path = testing::TempDir() + "/strata_mesh_io_" + fileName;
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  return path;
}

// Reads `bytes` as `name` and expects a strata::Error containing every part.
void expectReadError(const std::string& name, const std::string& bytes,
                     std::initializer_list<std::string> parts, MeshReadOptions options = {}) {
  try {
    readMeshBytes(name, bytes, options);
    ADD_FAILURE() << name << ": read without error, expected one mentioning " << *parts.begin();
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos)
          << "message \"" << message << "\" lacks \"" << part << "\"";
    }
  }
}

bool anyWarningContains(const MeshReadReport& report, const std::string& part) {
  for (const auto& w : report.warnings) {
    if (w.find(part) != std::string::npos) return true;
  }
  return false;
}

void expectUnitCube(const TriangleMesh& mesh) {
  const MeshCheck c = checkMesh(mesh);
  EXPECT_EQ(c.vertices, 8u);
  EXPECT_EQ(c.triangles, 12u);
  EXPECT_TRUE(c.watertight());
  EXPECT_EQ(c.genus, 0);
  EXPECT_NEAR(c.volume, 1.0, 1e-12);
}

// ---- Round trips ----

TEST(MeshIoRoundTrip, Obj) {
  MeshReadReport report;
  const TriangleMesh m = readMeshFile(writeTemp("cube.obj", cubeObj()), {}, &report);
  expectUnitCube(m);
  EXPECT_EQ(report.fileVertices, 8u);
  EXPECT_EQ(report.fileFaces, 12u);
  EXPECT_TRUE(report.warnings.empty());
}

TEST(MeshIoRoundTrip, ObjWithQuadsSlashesNegativeIndicesAndIgnoredStatements) {
  const std::string text =
      "# quads, i/t/n references, relative indices\nmtllib cube.mtl\no cube\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1 1.0\nv 1 0 1 0.5 0.5 0.5\nv 1 1 1\nv 0 1 1\n"
      "vt 0 0\nvn 0 0 1\ng all\nusemtl red\ns off\n"
      "f 1/1/1 4/1/1 3/1/1 2/1/1\nf 5//1 6//1 7//1 8//1\nf -8/1 -7/1 -3/1 -4/1\n"
      "f 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\nl 1 2\np 3\n";
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("quads.OBJ", text, {}, &report);
  expectUnitCube(m);
  EXPECT_EQ(report.fileFaces, 6u);
  EXPECT_TRUE(anyWarningContains(report, "line/point"));
}

// Text files written by Windows editors start with a UTF-8 byte order mark: OBJ, ASCII STL, OFF
// and ASCII PLY read the same with it (an OBJ was refused with "vertex index 8 is out of range",
// an ASCII STL read as binary); a binary STL whose header starts with those bytes stays binary.
TEST(MeshIoRoundTrip, AByteOrderMarkBeforeATextFormatIsSkipped) {
  const std::string bom = "\xEF\xBB\xBF";
  expectUnitCube(readMeshBytes("bom.obj", bom + cubeObj()));
  expectUnitCube(readMeshBytes("bom.stl", bom + cubeAsciiStl()));
  expectUnitCube(readMeshBytes("bom.off", bom + cubeOff()));
  expectUnitCube(readMeshBytes("bom.ply", bom + cubeAsciiPly()));
  expectUnitCube(readMeshBytes("bom_binary.stl", cubeBinaryStl(bom + "solid binary")));
}

TEST(MeshIoRoundTrip, ObjUnknownStatementIsAWarning) {
  MeshReadReport report;
  readMeshBytes("odd.obj", "frobnicate 1 2\n" + cubeObj() + "frobnicate 3\n", {}, &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("odd.obj"), std::string::npos);
  EXPECT_NE(report.warnings[0].find("2 unknown"), std::string::npos);
  EXPECT_NE(report.warnings[0].find("'frobnicate' at line 1"), std::string::npos);
}

TEST(MeshIoRoundTrip, AsciiStl) {
  expectUnitCube(readMeshFile(writeTemp("cube_ascii.stl", cubeAsciiStl())));
}

TEST(MeshIoRoundTrip, BinaryStlWeldsVertices) {
  MeshReadReport report;
  const TriangleMesh m = readMeshFile(writeTemp("cube_binary.stl", cubeBinaryStl()), {}, &report);
  expectUnitCube(m);
  EXPECT_EQ(report.fileVertices, 36u);
  EXPECT_EQ(report.fileFaces, 12u);
  EXPECT_TRUE(report.warnings.empty());  // welding STL is normal, not a repair
}

TEST(MeshIoRoundTrip, BinaryStlWhoseHeaderStartsWithSolid) {
  expectUnitCube(readMeshBytes("solid.stl", cubeBinaryStl("solid cube exported as binary")));
}

TEST(MeshIoRoundTrip, AsciiPly) {
  MeshReadReport report;
  expectUnitCube(readMeshFile(writeTemp("cube_ascii.ply", cubeAsciiPly()), {}, &report));
  EXPECT_EQ(report.fileVertices, 8u);
  EXPECT_EQ(report.fileFaces, 12u);
}

TEST(MeshIoRoundTrip, BinaryLittleEndianPly) {
  expectUnitCube(readMeshFile(writeTemp("cube_le.ply", cubeBinaryPly(false))));
}

TEST(MeshIoRoundTrip, BinaryBigEndianPlyWithDoubles) {
  expectUnitCube(readMeshFile(writeTemp("cube_be.ply", cubeBinaryPly(true, true))));
}

TEST(MeshIoRoundTrip, PlyWithVertexIndexName) {
  expectUnitCube(readMeshBytes("cube.ply", cubeAsciiPly(8, "vertex_index")));
}

TEST(MeshIoRoundTrip, Off) {
  MeshReadReport report;
  expectUnitCube(readMeshFile(writeTemp("cube.off", cubeOff()), {}, &report));
  EXPECT_EQ(report.fileFaces, 12u);
}

TEST(MeshIoRoundTrip, UnitScale) {
  MeshReadOptions options;
  options.unitScale = 25.4;
  const TriangleMesh m = readMeshBytes("inch.obj", cubeObj(), options);
  EXPECT_NEAR(checkMesh(m).volume, 25.4 * 25.4 * 25.4, 1e-9);
}

// ---- Files ----

TEST(MeshIoErrors, MissingFileNamesThePath) {
  try {
    readMeshFile("/nonexistent/dir/missing.obj");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/missing.obj: cannot open"),
              std::string::npos)
        << e.what();
  }
}

TEST(MeshIoErrors, UnknownExtension) {
  expectReadError("model.3ds", "x", {"model.3ds", "unknown mesh format", ".3ds"});
}

// ---- OBJ ----

TEST(MeshIoObj, IndexOutOfRange) {
  expectReadError("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
                  {"bad.obj: line 4:", "vertex index 9 is out of range", "3 vertices"});
}

TEST(MeshIoObj, NegativeIndexOutOfRange) {
  expectReadError("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                  {"bad.obj: line 4:", "negative vertex index -4", "out of range"});
}

TEST(MeshIoObj, IndexZero) {
  expectReadError("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 0 1 2\n",
                  {"bad.obj: line 5:", "index 0"});
}

TEST(MeshIoObj, NaNCoordinate) {
  expectReadError("bad.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", {"bad.obj: line 2:", "NaN"});
}

TEST(MeshIoObj, InfCoordinate) {
  expectReadError("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n",
                  {"bad.obj: line 3:", "infinite"});
  expectReadError("bad.obj", "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                  {"bad.obj: line 1:", "infinite", "1e999"});
}

TEST(MeshIoObj, UnparsableNumber) {
  expectReadError("bad.obj", "v 0 0 0\nv 1 2 abc\n", {"bad.obj: line 2:", "not a number", "'abc'"});
  expectReadError("bad.obj", "v 0 0 0\nv 1 2 3.5x\n", {"bad.obj: line 2:", "'3.5x'"});
}

TEST(MeshIoObj, MalformedFaceReference) {
  expectReadError("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/ 3\n",
                  {"bad.obj: line 4:", "bad vertex reference", "'2/'"});
  expectReadError("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
                  {"bad.obj: line 4:", "at least 3 vertices"});
}

TEST(MeshIoObj, EmptyMesh) {
  expectReadError("empty.obj", "", {"empty.obj", "contains no triangles"});
  expectReadError("points.obj", "v 0 0 0\nv 1 0 0\n", {"points.obj", "contains no triangles"});
}

TEST(MeshIoObj, AllDegenerateIsEmpty) {
  expectReadError("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
                  {"flat.obj", "contains no triangles", "degenerate"});
}

// ---- STL ----

TEST(MeshIoStl, TruncatedBinary) {
  std::string bytes = cubeBinaryStl();
  bytes.resize(bytes.size() - 20);
  expectReadError("cut.stl", bytes, {"cut.stl: byte 80:", "count 12", "684 bytes", "664 bytes"});
}

TEST(MeshIoStl, BinaryCountLies) {
  expectReadError("lies.stl", cubeBinaryStl("binary", 13),
                  {"lies.stl: byte 80:", "count 13", "734 bytes", "684 bytes"});
}

TEST(MeshIoStl, BinaryTooShort) {
  expectReadError("short.stl", std::string(40, '\0'), {"short.stl: byte 40:", "too short"});
}

TEST(MeshIoStl, BinaryNaN) {
  std::string bytes = cubeBinaryStl();
  const float nan = std::nanf("");
  std::memcpy(&bytes[84 + 50 * 2 + 12 + 4], &nan, 4);  // facet 2, first vertex, y
  expectReadError("nan.stl", bytes, {"nan.stl: byte 200:", "NaN"});
}

TEST(MeshIoStl, BinaryWithZeroFacetsIsEmpty) {
  expectReadError("zero.stl", cubeBinaryStl("binary", 0).substr(0, 84),
                  {"zero.stl", "contains no triangles"});
}

TEST(MeshIoStl, AsciiTruncated) {
  const std::string text = cubeAsciiStl();
  const std::string cut =
      text.substr(0, text.rfind('\n', text.find("endloop", text.size() / 2)) + 1);
  const size_t lines = std::count(cut.begin(), cut.end(), '\n');
  expectReadError("cut.stl", cut,
                  {"cut.stl: line " + std::to_string(lines + 1) + ":", "unexpected end of file"});
}

TEST(MeshIoStl, AsciiBadVertex) {
  std::string text = cubeAsciiStl();
  text.replace(text.find("vertex 1 0 0"), 12, "vertex 1 0 nan");
  expectReadError("nan.stl", text, {"nan.stl: line ", "NaN"});
  expectReadError("kw.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertx 0 0 0\n",
                  {"kw.stl: line 4:", "expected 'vertex' or 'endloop'", "'vertx'"});
}

// ---- PLY ----

TEST(MeshIoPly, AsciiVertexCountLies) {
  // 9 vertices: the first face line is taken as a vertex, so the last face reads the edge
  // line (35) and finds only 2 indices.
  expectReadError("lies.ply", cubeAsciiPly(9), {"lies.ply: line 35:", "face 11 has 2 vertices"});
  // 7 vertices: the eighth vertex line (22) is taken as a face of 0 vertices.
  expectReadError("lies.ply", cubeAsciiPly(7), {"lies.ply: line 22:", "face 0 has 0 vertices"});
  // 30 vertices: every line after the header is a vertex, and the vertices run out.
  expectReadError("lies.ply", cubeAsciiPly(30),
                  {"lies.ply: line 36:", "expected 30 'vertex' elements, found 21"});
}

TEST(MeshIoPly, AsciiTruncated) {
  std::string text = cubeAsciiPly();
  text.resize(text.find("3 1 6 5"));
  expectReadError("cut.ply", text,
                  {"cut.ply: line", "unexpected end of file", "expected 12 'face' elements"});
}

TEST(MeshIoPly, BinaryTruncated) {
  std::string bytes = cubeBinaryPly(false);
  bytes.resize(bytes.size() - 3);  // inside the last element
  expectReadError("cut.ply", bytes,
                  {"cut.ply: byte " + std::to_string(bytes.size()) + ":", "unexpected end of file",
                   "element 'edge' 0 of 1"});
  bytes.resize(bytes.size() - 150);  // inside the faces
  expectReadError("cut.ply", bytes,
                  {"cut.ply: byte ", "unexpected end of file in element 'face'", "truncated"});
}

TEST(MeshIoPly, BinaryVertexCountLies) {
  // 9 vertices: the first face is read as a vertex, the last face then reads the edge element.
  expectReadError("lies.ply", cubeBinaryPly(false, false, 9),
                  {"lies.ply: byte 541:", "face 11 has 2 vertices"});
  // 1000 vertices cannot fit in what follows the header.
  expectReadError("lies.ply", cubeBinaryPly(false, false, 1000),
                  {"lies.ply: byte ", "the header says 1000 'vertex' elements", "truncated"});
  expectReadError("lies.ply", cubeBinaryPly(false, false, 7),
                  {"lies.ply: byte ", "face 0 has 0 vertices"});
}

TEST(MeshIoPly, MissingVertexIndices) {
  expectReadError("noidx.ply", cubeAsciiPly(8, "corners"),
                  {"noidx.ply: line 9:", "no vertex_indices"});
}

TEST(MeshIoPly, IndexOutOfRange) {
  std::string text = cubeAsciiPly();
  text.replace(text.find("3 1 6 5"), 7, "3 1 6 8");
  expectReadError("idx.ply", text, {"idx.ply: line 34:", "vertex index 8 is out of range"});
  text.replace(text.find("3 1 6 8"), 7, "3 1 -6 5");
  expectReadError("idx.ply", text, {"idx.ply: line 34:", "vertex index -6 is out of range"});
}

TEST(MeshIoPly, NaNCoordinate) {
  std::string text = cubeAsciiPly();
  text.replace(text.find("1 1 1 255"), 9, "1 inf 1 255");
  expectReadError("inf.ply", text, {"inf.ply: line 21:", "infinite"});
}

TEST(MeshIoPly, RepeatedVertexOrFaceElement) {
  std::string text = cubeAsciiPly();
  const size_t headerEnd = text.find("end_header");
  expectReadError("twice.ply", std::string(text).insert(headerEnd, "element vertex 8\n"),
                  {"twice.ply: line 14:", "element 'vertex' is declared twice (first at line 4)"});
  expectReadError("twice.ply", text.insert(headerEnd, "element face 0\n"),
                  {"twice.ply: line 14:", "element 'face' is declared twice (first at line 9)"});
}

// ---- OFF ----

TEST(MeshIoOff, CountsLie) {
  expectReadError("lies.off", cubeOff(9, 12),
                  {"lies.off: line 24:", "unexpected end of file", "expected 12 faces, found 11"});
  expectReadError("lies.off", cubeOff(8, 11), {"lies.off: line 23:", "data after the last face"});
  expectReadError("lies.off", cubeOff(8, 13), {"lies.off: line 24:", "expected 13 faces"});
}

TEST(MeshIoOff, IndexOutOfRange) {
  std::string text = cubeOff();
  text.replace(text.find("3 1 6 5"), 7, "3 1 6 8");
  expectReadError("idx.off", text, {"idx.off: line 23:", "vertex index 8 is out of range"});
  text.replace(text.find("3 1 6 8"), 7, "3 -1 6 5");
  expectReadError("idx.off", text, {"idx.off: line 23:", "vertex index -1 is out of range"});
}

TEST(MeshIoOff, BadHeaderAndNaN) {
  expectReadError("bad.off", "OFX\n", {"bad.off: line 1:", "not an OFF file"});
  std::string text = cubeOff();
  text.replace(text.find("\n1 1 1\n"), 7, "\n1 NaN 1\n");
  expectReadError("nan.off", text, {"nan.off: line 10:", "NaN"});
}

// ---- Classic Mac OS line ends (a lone CR) ----

std::string crOnly(std::string text) {
  std::replace(text.begin(), text.end(), '\n', '\r');
  return text;
}

TEST(MeshIoCrLineEnds, EveryTextFormatReads) {
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"cr.obj", cubeObj()},
                                   {"cr.off", cubeOff()},
                                   {"cr.stl", cubeAsciiStl()},
                                   {"cr.ply", cubeAsciiPly()}}) {
    MeshReadReport report;
    expectUnitCube(readMeshBytes(name, crOnly(text), {}, &report));
    EXPECT_TRUE(report.warnings.empty()) << name;
  }
}

TEST(MeshIoCrLineEnds, BinaryPlyHeader) {
  std::string bytes = cubeBinaryPly(false);
  const size_t body = bytes.find("end_header\n") + 11;
  bytes = crOnly(bytes.substr(0, body)) + bytes.substr(body);
  expectUnitCube(readMeshBytes("cr.ply", bytes));
  // A body whose first byte is LF: the header's last CR is still its line end (the first x is
  // then a denormal float, next to 0).
  bytes[body] = '\n';
  expectUnitCube(readMeshBytes("cr.ply", bytes));
}

TEST(MeshIoCrLineEnds, ErrorsNameTheLine) {
  expectReadError("cr.obj", crOnly("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
                  {"cr.obj: line 2:", "NaN"});
  std::string off = cubeOff();
  off.replace(off.find("\n1 1 1\n"), 7, "\n1 NaN 1\n");
  expectReadError("cr.off", crOnly(off), {"cr.off: line 10:", "NaN"});
  expectReadError("cr.stl", crOnly("solid x\nfacet normal 0 0 1\nouter loop\nvertx 0 0 0\n"),
                  {"cr.stl: line 4:", "expected 'vertex' or 'endloop'", "'vertx'"});
  std::string ply = cubeAsciiPly();
  ply.replace(ply.find("1 1 1 255"), 9, "1 inf 1 255");
  expectReadError("cr.ply", crOnly(ply), {"cr.ply: line 21:", "infinite"});
}

TEST(MeshIoCrLineEnds, CrLfAndStrayCrAreUnchanged) {
  std::string crlf;
  for (char c : cubeObj()) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  expectUnitCube(readMeshBytes("crlf.obj", crlf));
  expectReadError("crlf.obj", "v 0 0 0\r\nv 1 2 abc\r\n", {"crlf.obj: line 2:", "'abc'"});
  // After an LF-ended first line, a CR is whitespace as before; "\r\r\n" is a CRLF line end.
  std::string stray = "# cube\n" + cubeObj();
  stray.replace(stray.find("v 0 0 0"), 7, "v 0\r0\r0");
  expectUnitCube(readMeshBytes("stray.obj", stray));
  expectReadError("stray.obj", "v 0 0 0\r\r\nv 1 2 abc\r\r\n", {"stray.obj: line 2:", "'abc'"});
}

// ---- Coordinates whose volume a double cannot hold ----

// The cube of side `size` in every text format.
std::vector<std::pair<std::string, std::string>> cubesOfSize(double size) {
  return {{"cube.obj", cubeObj({}, -1, 0.0, size)},
          {"cube.off", cubeOff(8, 12, size)},
          {"cube.stl", cubeAsciiStl(size)},
          {"cube.ply", cubeAsciiPly(8, "vertex_indices", size)}};
}

TEST(MeshIoRange, HugeMeshIsRefused) {
  for (const auto& [name, text] : cubesOfSize(1e200)) {
    expectReadError(name, text,
                    {name + ": coordinates span 1e+200, more than 2.24e+102",
                     "volume and area would overflow a double", "rescale the mesh"});
  }
}

TEST(MeshIoRange, TinyMeshIsRefused) {
  for (const auto& [name, text] : cubesOfSize(1e-200)) {
    expectReadError(name, text,
                    {name + ": coordinates span only 1e-200, less than 4.46e-103",
                     "would underflow a double", "rescale the mesh"});
  }
}

TEST(MeshIoRange, MeshesNearTheLimitsRead) {
  for (const double size : {1e100, 1e-100}) {
    for (const auto& [name, text] : cubesOfSize(size)) {
      MeshReadReport report;
      const MeshCheck c = checkMesh(readMeshBytes(name, text, {}, &report));
      EXPECT_TRUE(report.warnings.empty()) << name << " " << size;
      EXPECT_TRUE(c.watertight()) << name << " " << size;
      EXPECT_NEAR(c.volume / (size * size * size), 1.0, 1e-12) << name << " " << size;
      EXPECT_NEAR(c.area / (size * size), 6.0, 1e-12) << name << " " << size;
    }
  }
}

TEST(MeshIoRange, UnusedVertexOutOfRangeIsOnlyDropped) {
  MeshReadReport report;
  expectUnitCube(readMeshBytes("stray.obj", cubeObj() + "v 1e200 0 0\n", {}, &report));
  EXPECT_TRUE(anyWarningContains(report, "dropped 1 vertex"));
}

TEST(MeshIoRange, MeshCollapsedFarFromTheOriginIsAPoint) {
  // 1e300 + 1 == 1e300: the unit cube's corners are one point.
  expectReadError("far.obj", cubeObj({}, -1, 1e300),
                  {"far.obj: all vertices lie at one point (1e+300, 1e+300, 1e+300)",
                   "the mesh has no size", "16 significant digits"});
}

TEST(MeshIoRange, DistantMeshReadsWithoutFalseFlips) {
  // A unit cube 1e15 from the origin: volumes about the origin cancel to noise there.
  MeshReadReport report;
  const MeshCheck far = checkMesh(readMeshBytes("far.obj", cubeObj({}, -1, 1e15), {}, &report));
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_EQ(far.volume, 1.0);
  readMeshBytes("far_inv.obj", cubeObj(allTriangles(), -1, 1e15), {}, &report);
  EXPECT_TRUE(anyWarningContains(report, "far_inv.obj: mesh was inside out"));
}

// ---- Preparation through the reader ----

TEST(MeshIoPrepare, OpenMeshRejectedUnlessAllowed) {
  const std::string open = cubeObj({}, /*skip=*/5);
  expectReadError("open.obj", open, {"open.obj", "3 open (boundary) edges", "allow-open"});
  MeshReadOptions options;
  options.allowOpen = true;
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("open.obj", open, options, &report);
  EXPECT_EQ(m.triangles.size(), 11u);
  EXPECT_TRUE(anyWarningContains(report, "open (boundary) edges"));
  EXPECT_EQ(report.openProblem, "3 open (boundary) edges");
  MeshReadReport closed;
  readMeshBytes("closed.obj", cubeObj(), options, &closed);
  EXPECT_EQ(closed.openProblem, "");
}

TEST(MeshIoPrepare, NonManifoldRejected) {
  std::string text = cubeObj() + "v 0.5 -1 0.5\nf 1 2 9\n";
  expectReadError("fin.obj", text, {"fin.obj", "non-manifold", "allow-open"});
}

TEST(MeshIoPrepare, InvertedMeshIsFlippedWithWarning) {
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("inv.obj", cubeObj(allTriangles()), {}, &report);
  EXPECT_TRUE(anyWarningContains(report, "inv.obj: mesh was inside out"));
  EXPECT_NEAR(signedVolume(m), 1.0, 1e-12);
}

TEST(MeshIoPrepare, InconsistentOrientationIsRepaired) {
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("mixed.obj", cubeObj({3, 8}), {}, &report);
  EXPECT_TRUE(anyWarningContains(report, "flipped 2 triangles"));
  EXPECT_TRUE(checkMesh(m).watertight());
  EXPECT_NEAR(signedVolume(m), 1.0, 1e-12);
}

TEST(MeshIoPrepare, CavityStaysInward) {
  // Outer cube of side 3, inner cube of side 1 written inward (a correct cavity).
  const std::string text =
      cubeObj({}, -1, 0.0, 3.0) + cubeObj(allTriangles(), -1, 1.0, 1.0, /*firstIndex=*/9);
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("cavity.obj", text, {}, &report);
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_NEAR(signedVolume(m), 27.0 - 1.0, 1e-12);
  EXPECT_EQ(checkMesh(m).components, 2);
}

// A shell inside another, both pointing outward: taken as a cavity (the even-odd rule) and said
// so, not called "inside out" (it was not).
TEST(MeshIoPrepare, AnOutwardShellInsideAnotherIsACavityAndSaysSo) {
  const std::string text = cubeObj({}, -1, 0.0, 3.0) + cubeObj({}, -1, 1.0, 1.0, /*firstIndex=*/9);
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("nested.obj", text, {}, &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_TRUE(anyWarningContains(
      report,
      "nested.obj: 1 closed shell lies inside another and pointed outward: taken as a "
      "cavity"));
  EXPECT_FALSE(anyWarningContains(report, "inside out"));
  EXPECT_NEAR(signedVolume(m), 27.0 - 1.0, 1e-12);
}

// One of two separate shells inside out: the warning counts it, not "the mesh".
TEST(MeshIoPrepare, OneInvertedShellOfTwoIsCounted) {
  const std::string text =
      cubeObj({}, -1, 0.0, 1.0) + cubeObj(allTriangles(), -1, 3.0, 1.0, /*firstIndex=*/9);
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("two.obj", text, {}, &report);
  EXPECT_TRUE(anyWarningContains(report, "two.obj: flipped 1 shell of 2 that pointed inward"));
  EXPECT_NEAR(signedVolume(m), 2.0, 1e-12);
}

TEST(MeshIoPrepare, DuplicateVerticesAreWeldedWithWarning) {
  const std::string text = cubeObj() + "v 0 0 0\n";  // unused duplicate of vertex 1
  MeshReadReport report;
  const TriangleMesh m = readMeshBytes("dup.obj", text, {}, &report);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_TRUE(anyWarningContains(report, "welded 1 duplicate vertex"));
}

// ---- Reference meshes ----

struct Reference {
  const char* file;
  double volume;
  int genus;                 // -1: not checked
  double relativeTolerance;  // of the volume: 1e-6, or the precision the reference is known to
};

class MeshIoReference : public testing::TestWithParam<Reference> {};

TEST_P(MeshIoReference, ReadsWatertightWithKnownVolume) {
  const Reference& ref = GetParam();
  MeshReadReport report;
  const TriangleMesh m = readMeshFile(std::string(STRATA_TEST_DATA) + "/" + ref.file, {}, &report);
  const MeshCheck c = checkMesh(m);
  EXPECT_TRUE(c.watertight()) << ref.file;
  EXPECT_EQ(c.degenerateTriangles, 0u);
  EXPECT_NEAR(c.volume, ref.volume, ref.relativeTolerance * ref.volume) << ref.file;
  if (ref.genus >= 0) {
    EXPECT_EQ(c.genus, ref.genus) << ref.file;
  }
  for (const auto& w : report.warnings) ADD_FAILURE() << "unexpected warning: " << w;
}

INSTANTIATE_TEST_SUITE_P(
    MeshIoData, MeshIoReference,
    testing::Values(Reference{"bunny.obj", 194.288371812, 0, 1e-6},
                    Reference{"armadillo.obj", 237850.3168, -1, 1e-6},
                    // fandisk: reference known to 5 digits only (true 0.1403603163).
                    Reference{"fandisk.obj", 0.14036, -1, 4e-5},
                    Reference{"eight.obj", 0.0401729, 2, 1e-6},
                    Reference{"knot1.obj", 0.0951747, 1, 1e-6}),
    [](const testing::TestParamInfo<Reference>& info) {
      std::string name = info.param.file;
      return name.substr(0, name.find('.'));
    });

// Every format is held to the triangle limit, before the mesh is prepared; the message names
// the file, the count, the limit and the option that raises it.
TEST(MeshIoLimits, TrianglesOverTheLimitAreRefusedInEveryFormat) {
  const uint64_t saved = maxInputTriangles();
  setMaxInputTriangles(11);  // a cube has 12
  std::vector<std::pair<std::string, std::string>> files = {
      {"c.obj", cubeObj()}, {"c.stl", cubeAsciiStl()}, {"b.stl", cubeBinaryStl()}};
  std::vector<std::string> messages;
  for (const auto& [name, bytes] : files) {
    try {
      readMeshBytes(name, bytes);
      messages.push_back("(read)");
    } catch (const Error& e) {
      messages.push_back(e.what());
    }
  }
  setMaxInputTriangles(12);
  const size_t atTheLimit = readMeshBytes("c.obj", cubeObj()).triangles.size();
  setMaxInputTriangles(saved);
  for (size_t k = 0; k < files.size(); ++k) {
    SCOPED_TRACE(files[k].first);
    EXPECT_NE(messages[k].find(files[k].first + ": 12 triangles, more than the limit of 11"),
              std::string::npos)
        << messages[k];
    EXPECT_NE(messages[k].find("--max-triangles"), std::string::npos) << messages[k];
  }
  EXPECT_EQ(atTheLimit, 12u);
}

}  // namespace
}  // namespace strata
