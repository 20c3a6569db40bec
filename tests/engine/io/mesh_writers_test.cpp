// Mesh writers: every format writes a closed mesh of several coloured leaves that reads back raw
// (readMeshFileRaw, no repairs) watertight with the same triangles and volume, and carries the
// colours, material names and unit; writes are atomic (cancelled or failed exports leave no
// file and no temporary file, and an existing file untouched). Also the 3MF reader's strictness.
#include "engine/io/mesh_writers.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/io/zip_archive.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "tests/fuzz/fuzz_entries.h"

namespace strata {
namespace {

// ---- Meshes to write ----

const double kCubeCorners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
// Outward, counter-clockwise seen from outside.
const uint32_t kCubeTriangles[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                        {0, 1, 5}, {0, 5, 4}, {3, 7, 6}, {3, 6, 2},
                                        {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};

void addBox(ExportMesh& em, glm::dvec3 at, double size, uint32_t leaf) {
  const uint32_t base = static_cast<uint32_t>(em.mesh.positions.size());
  for (const auto& c : kCubeCorners) {
    em.mesh.positions.push_back(at + size * glm::dvec3(c[0], c[1], c[2]));
  }
  for (const auto& t : kCubeTriangles) {
    em.mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    em.triangleLeaf.push_back(leaf);
  }
}

// A tetrahedron with legs `size` along the axes from `at`, outward.
void addTetrahedron(ExportMesh& em, glm::dvec3 at, double size, uint32_t leaf) {
  const uint32_t b = static_cast<uint32_t>(em.mesh.positions.size());
  em.mesh.positions.push_back(at);
  em.mesh.positions.push_back(at + glm::dvec3(size, 0, 0));
  em.mesh.positions.push_back(at + glm::dvec3(0, size, 0));
  em.mesh.positions.push_back(at + glm::dvec3(0, 0, size));
  for (std::array<uint32_t, 3> t :
       {std::array<uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
    em.mesh.triangles.push_back({b + t[0], b + t[1], b + t[2]});
    em.triangleLeaf.push_back(leaf);
  }
}

// Two cubes and a tetrahedron, three leaves; two leaf names sanitise to the same material name.
// Coordinates are exact in float32 (STL). Volume 1 + 8 + 1/6.
ExportMesh colouredScene() {
  ExportMesh em;
  addBox(em, {0, 0, 0}, 1.0, 7);
  addBox(em, {3, 0.5, -1}, 2.0, 3);
  addTetrahedron(em, {0, 4, 0}, 1.0, 9);
  em.leaves[7] = {"Body/main", {1.0f, 0.0f, 0.0f}};
  em.leaves[3] = {"hole #1", {0.0f, 0.0f, 1.0f}};
  em.leaves[9] = {"Body main", {0.0f, 1.0f, 0.0f}};
  return em;
}
constexpr double kSceneVolume = 1.0 + 8.0 + 1.0 / 6.0;

// Many disjoint tetrahedra: more triangles than one progress stride (65536).
ExportMesh largeMesh() {
  ExportMesh em;
  for (int i = 0; i < 20000; ++i) addTetrahedron(em, {2.0 * (i % 100), 2.0 * (i / 100), 0}, 1, 1);
  em.leaves[1] = {"many", {0.5f, 0.5f, 0.5f}};
  return em;
}

// ---- Files ----

// A path in a folder of this test's own (tests run in parallel processes).
std::string tempPath(const std::string& fileName) {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  return testing::TempDir() + "/strata_writers_" + info->test_suite_name() + "_" + info->name() +
         "_" + std::to_string(::getpid()) + "_" + fileName;
}

bool exists(const std::string& path) {
  return std::ifstream(path).good();
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void expectContains(const std::string& text, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    EXPECT_NE(text.find(part), std::string::npos) << "\"" << text << "\" lacks \"" << part << "\"";
  }
}

size_t countOf(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// Writes, reads back raw, and checks what every format must keep.
TriangleMesh writeAndCheck(const std::string& path, const ExportMesh& em = colouredScene()) {
  writeMeshFile(path, em);
  EXPECT_TRUE(temporaryFilesOf(path).empty());
  const TriangleMesh back = readMeshFileRaw(path);
  const MeshCheck check = checkMesh(back);
  EXPECT_TRUE(check.watertight()) << path << ": boundary " << check.boundaryEdges
                                  << ", non-manifold " << check.nonManifoldEdges << ", misoriented "
                                  << check.misorientedEdges;
  EXPECT_EQ(back.triangles.size(), em.mesh.triangles.size()) << path;
  const double volume = signedVolume(em.mesh);
  EXPECT_NEAR(check.volume, volume, 1e-6 * std::abs(volume)) << path;
  EXPECT_EQ(check.components, 3) << path;
  return back;
}

// ---- Formats ----

TEST(MeshWritersStl, RoundTripsWatertightWithUnitInHeader) {
  const std::string path = tempPath("scene.stl");
  writeAndCheck(path);
  EXPECT_NEAR(signedVolume(colouredScene().mesh), kSceneVolume, 1e-12);
  const std::string bytes = readWholeFile(path);
  ASSERT_EQ(bytes.size(), 84u + 50u * 28u);
  const std::string header = bytes.substr(0, 80);
  expectContains(header, {"Strata", "millimetre"});
  EXPECT_NE(header.substr(0, 5), "solid");
  // The first facet's normal: triangle {0, 2, 1} of the cube is the bottom face, -z.
  float normal[3];
  std::memcpy(normal, bytes.data() + 84, sizeof(normal));
  EXPECT_EQ(normal[0], 0.0f);
  EXPECT_EQ(normal[1], 0.0f);
  EXPECT_EQ(normal[2], -1.0f);
  EXPECT_EQ(bytes[84 + 48], 0);
  EXPECT_EQ(bytes[84 + 49], 0);
}

TEST(MeshWritersObj, RoundTripsWithOneMaterialPerLeaf) {
  const std::string path = tempPath("Scene.OBJ");
  writeAndCheck(path);
  const std::string obj = readWholeFile(path);
  const std::string mtlName = tempPath("Scene.mtl");
  const std::string mtl = readWholeFile(mtlName);
  const std::string mtlBase = mtlName.substr(mtlName.find_last_of('/') + 1);
  expectContains(obj, {"# unit: millimetre", "mtllib " + mtlBase + "\n"});
  EXPECT_EQ(countOf(obj, "\nusemtl "), 3u);
  EXPECT_EQ(countOf(obj, "\nv "), 8u + 8u + 4u);

  // Parse the MTL: material -> Kd.
  std::map<std::string, std::string> kd;
  std::istringstream lines(mtl);
  std::string line, current;
  while (std::getline(lines, line)) {
    if (line.rfind("newmtl ", 0) == 0) current = line.substr(7);
    if (line.rfind("Kd ", 0) == 0) kd[current] = line.substr(3);
  }
  ASSERT_EQ(kd.size(), 3u) << mtl;
  // Leaf ids in order 3, 7, 9: "hole #1", "Body/main", "Body main" (made unique).
  EXPECT_EQ(kd["hole__1"], "0 0 1");
  EXPECT_EQ(kd["Body_main"], "1 0 0");
  EXPECT_EQ(kd["Body_main_2"], "0 1 0");
  for (const auto& [name, colour] : kd) expectContains(obj, {"usemtl " + name + "\n"});
  // The leaf of each usemtl block: the red cube's faces follow "usemtl Body_main".
  const size_t red = obj.find("usemtl Body_main\n");
  EXPECT_EQ(obj.compare(red + 17, 8, "f 1 3 2\n"), 0) << obj.substr(red, 40);
}

TEST(MeshWritersObj, KdIsSrgbEncodedAndNumbersUse9Digits) {
  ExportMesh em;
  addBox(em, {0.1, 1.0 / 3.0, -2.5e-7}, 1.0, 1);
  em.leaves[1] = {"", {0.5f, 0.5f, 0.5f}};
  const std::string path = tempPath("grey.obj");
  writeMeshFile(path, em);
  const std::string mtl = readWholeFile(tempPath("grey.mtl"));
  expectContains(mtl, {"newmtl leaf_1\n", "Kd 0.735357 0.735357 0.735357\n"});
  const std::string obj = readWholeFile(path);
  expectContains(obj, {"v 0.1 0.333333333 -2.5e-07\n"});
}

// `mtllib` names are separated by white space: "part 256.obj" refers to "part_256.mtl", written
// under that name, so that other programs find the materials.
TEST(MeshWritersObj, ASpaceInTheNameDoesNotSplitTheMaterialLibrary) {
  ExportMesh em;
  addBox(em, {0, 0, 0}, 1.0, 1);
  em.leaves[1] = {"plate", {0.5f, 0.5f, 0.5f}};
  const std::string path = tempPath("part 256.obj");
  writeMeshFile(path, em);
  expectContains(readWholeFile(path), {"mtllib ", "part_256.mtl\n"});
  EXPECT_EQ(readWholeFile(path).find("part 256.mtl"), std::string::npos);
  EXPECT_TRUE(exists(tempPath("part_256.mtl")));
  EXPECT_FALSE(exists(tempPath("part 256.mtl")));
}

TEST(MeshWritersPly, RoundTripsWithVertexColours) {
  const std::string path = tempPath("scene.ply");
  writeAndCheck(path);
  const std::string bytes = readWholeFile(path);
  const size_t end = bytes.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = bytes.substr(0, end);
  expectContains(header,
                 {"format binary_little_endian 1.0", "comment unit millimetre", "element vertex 20",
                  "property uchar red", "property uchar green", "property uchar blue",
                  "element face 28", "property list uchar int vertex_indices"});
  // Vertex records: 3 doubles and 3 colour bytes. Vertex 0 is the red cube's, 8 the blue's,
  // 16 the green tetrahedron's.
  const size_t body = end + 11;
  auto colour = [&](size_t v) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + body + v * 27 + 24);
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  EXPECT_EQ(colour(0), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(colour(8), (std::array<int, 3>{0, 0, 255}));
  EXPECT_EQ(colour(16), (std::array<int, 3>{0, 255, 0}));
}

TEST(MeshWriters3mf, RoundTripsWithColorGroupAndUnit) {
  const std::string path = tempPath("scene.3mf");
  MeshReadReport report;
  writeAndCheck(path);
  readMeshFileRaw(path, &report);
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();

  const std::string bytes = readWholeFile(path);
  const zipio::ZipReader zip(path, bytes);
  EXPECT_TRUE(zip.has("[Content_Types].xml"));
  EXPECT_TRUE(zip.has("_rels/.rels"));
  const std::string model = zip.read("3D/3dmodel.model", 1 << 20);
  expectContains(
      model,
      {"unit=\"millimeter\"",
       "xmlns:m=\"http://schemas.microsoft.com/3dmanufacturing/material/2015/02\"",
       "<m:colorgroup id=\"1\">", "<m:color color=\"#0000FF\"/>", "<m:color color=\"#FF0000\"/>",
       "<m:color color=\"#00FF00\"/>", "<vertex x=\"3\" y=\"0.5\" z=\"-1\"/>"});
  EXPECT_EQ(countOf(model, "<triangle "), 28u);
  EXPECT_EQ(countOf(model, "pid=\"1\" p1=\"1\""), 12u);  // the red cube (leaf 7, colour 1)
  EXPECT_EQ(countOf(model, "pid=\"1\" p1=\"0\""), 12u);
  EXPECT_EQ(countOf(model, "pid=\"1\" p1=\"2\""), 4u);

  // The same bytes through the preparing reader.
  const TriangleMesh prepared = readMeshFile(path);
  EXPECT_NEAR(signedVolume(prepared), kSceneVolume, 1e-9);
}

TEST(MeshWriters3mf, UnitsMapToThe3mfNames) {
  for (const auto& [scene, expected] :
       std::map<std::string, std::string>{{"inch", "inch"},
                                          {"Centimetre", "centimeter"},
                                          {"metre", "meter"},
                                          {"foot", "foot"},
                                          {"micron", "micron"}}) {
    ExportMesh em = colouredScene();
    em.unit = scene;
    const std::string path = tempPath("unit.3mf");
    writeMeshFile(path, em);
    const std::string bytes = readWholeFile(path);
    const std::string model = zipio::ZipReader(path, bytes).read("3D/3dmodel.model", 1 << 20);
    expectContains(model, {"unit=\"" + expected + "\""});
    MeshReadReport report;
    readMeshFileRaw(path, &report);
    ASSERT_EQ(report.warnings.size(), 1u) << scene;
    expectContains(report.warnings[0], {expected, "not converted"});
  }
}

TEST(MeshWriters3mf, UnknownUnitIsAnErrorAndWritesNothing) {
  ExportMesh em = colouredScene();
  em.unit = "furlong";
  const std::string path = tempPath("furlong.3mf");
  expectContains(errorOf([&] { writeMeshFile(path, em); }), {path, "furlong", "3MF"});
  EXPECT_FALSE(exists(path));
  EXPECT_TRUE(temporaryFilesOf(path).empty());
}

// ---- Atomicity, progress and errors ----

const char* const kFormats[] = {".stl", ".obj", ".ply", ".3mf"};

TEST(MeshWritersAtomic, AlreadyCancelledWritesNothing) {
  for (const char* ext : kFormats) {
    const std::string path = tempPath(std::string("cancelled") + ext);
    Progress progress;
    progress.cancel();
    EXPECT_THROW(writeMeshFile(path, colouredScene(), &progress), Cancelled) << ext;
    EXPECT_FALSE(exists(path)) << ext;
    EXPECT_TRUE(temporaryFilesOf(path).empty()) << ext;
    EXPECT_FALSE(exists(tempPath("cancelled.mtl"))) << ext;
  }
}

TEST(MeshWritersAtomic, CancelledMidwayLeavesTheOldFileAndNoTemp) {
  const ExportMesh em = largeMesh();
  for (const char* ext : kFormats) {
    const std::string path = tempPath(std::string("midway") + ext);
    writeFileAtomically(path, [](std::ostream& out) { out << "old content"; });
    std::vector<double> fractions;
    Progress* self = nullptr;
    Progress progress([&](const std::string& stage, double fraction) {
      EXPECT_EQ(stage.rfind("write ", 0), 0u) << stage;
      fractions.push_back(fraction);
      self->cancel();  // stop at the next check, after writing has begun
    });
    self = &progress;
    EXPECT_THROW(writeMeshFile(path, em, &progress), Cancelled) << ext;
    EXPECT_EQ(fractions.size(), 1u) << ext;
    EXPECT_EQ(readWholeFile(path), "old content") << ext;
    EXPECT_TRUE(temporaryFilesOf(path).empty()) << ext;
    EXPECT_FALSE(exists(tempPath("midway.mtl"))) << ext;
  }
}

TEST(MeshWritersAtomic, LargeMeshReportsProgressAndRoundTrips) {
  const ExportMesh em = largeMesh();
  for (const char* ext : kFormats) {
    const std::string path = tempPath(std::string("large") + ext);
    std::vector<double> fractions;
    Progress progress([&](const std::string&, double f) { fractions.push_back(f); });
    writeMeshFile(path, em, &progress);
    EXPECT_GE(fractions.size(), 2u) << ext;
    for (size_t i = 1; i < fractions.size(); ++i) EXPECT_GE(fractions[i], fractions[i - 1]);
    const TriangleMesh back = readMeshFileRaw(path);
    EXPECT_EQ(back.triangles.size(), em.mesh.triangles.size()) << ext;
    EXPECT_TRUE(checkMesh(back).watertight()) << ext;
  }
}

TEST(MeshWritersErrors, UnwritablePathNamesIt) {
  for (const char* ext : kFormats) {
    const std::string path = std::string("/nonexistent-strata-folder/out") + ext;
    expectContains(errorOf([&] { writeMeshFile(path, colouredScene()); }), {path});
  }
}

TEST(MeshWritersErrors, UnknownExtensionListsTheSupportedOnes) {
  const std::string path = tempPath("model.step");
  expectContains(errorOf([&] { writeMeshFile(path, colouredScene()); }),
                 {path, "'.step'", ".stl", ".obj", ".ply", ".3mf"});
  expectContains(errorOf([&] { writeMeshFile(tempPath("noextension"), colouredScene()); }),
                 {"noextension", "supported"});
  EXPECT_FALSE(exists(path));
}

TEST(MeshWritersErrors, MalformedExportMeshIsRefused) {
  const std::string path = tempPath("bad.stl");
  ExportMesh noStyle = colouredScene();
  noStyle.leaves.erase(9);
  expectContains(errorOf([&] { writeMeshFile(path, noStyle); }), {path, "leaf id 9"});
  ExportMesh badIndex = colouredScene();
  badIndex.mesh.triangles[5][1] = 99;
  expectContains(errorOf([&] { writeMeshFile(path, badIndex); }), {path, "vertex 99"});
  ExportMesh shortLeaves = colouredScene();
  shortLeaves.triangleLeaf.pop_back();
  expectContains(errorOf([&] { writeMeshFile(path, shortLeaves); }), {path, "leaf ids"});
  expectContains(errorOf([&] { writeMeshFile(path, ExportMesh()); }), {path, "no triangles"});
  ExportMesh nan = colouredScene();
  nan.mesh.positions[2].y = std::nan("");
  expectContains(errorOf([&] { writeMeshFile(path, nan); }), {path, "vertex 2", "not finite"});
  EXPECT_FALSE(exists(path));
}

TEST(MeshWritersRaw, ReadsWithoutRepairs) {
  // An inside-out cube with a repeated vertex: the raw reader keeps both as written.
  const std::string path = tempPath("inverted.obj");
  std::string obj;
  for (const auto& c : kCubeCorners) {
    obj += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) +
           "\n";
  }
  obj += "v 0 0 0\n";
  for (const auto& t : kCubeTriangles) {
    obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[2] + 1) + " " +
           std::to_string(t[1] + 1) + "\n";
  }
  writeFileAtomically(path, [&](std::ostream& out) { out << obj; });
  const TriangleMesh raw = readMeshFileRaw(path);
  EXPECT_EQ(raw.positions.size(), 9u);
  EXPECT_NEAR(signedVolume(raw), -1.0, 1e-12);
  MeshReadReport report;
  const TriangleMesh prepared = readMeshFile(path, {}, &report);
  EXPECT_NEAR(signedVolume(prepared), 1.0, 1e-12);
  expectContains(errorOf([&] { readMeshFileRaw(tempPath("missing.stl")); }), {"missing.stl"});
}

// ---- The 3MF reader ----

const char* const kModelHead =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<model unit=\"millimeter\" "
    "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n";

// A unit cube object with the given id (lines: one per vertex and triangle).
std::string cubeObject(int id, const std::string& extraTriangle = "") {
  std::string s = "<object id=\"" + std::to_string(id) + "\" type=\"model\"><mesh><vertices>\n";
  for (const auto& c : kCubeCorners) {
    s += "<vertex x=\"" + std::to_string(c[0]) + "\" y=\"" + std::to_string(c[1]) + "\" z=\"" +
         std::to_string(c[2]) + "\"/>\n";
  }
  s += "</vertices><triangles>\n";
  for (const auto& t : kCubeTriangles) {
    s += "<triangle v1=\"" + std::to_string(t[0]) + "\" v2=\"" + std::to_string(t[1]) + "\" v3=\"" +
         std::to_string(t[2]) + "\"/>\n";
  }
  s += extraTriangle + "</triangles></mesh></object>\n";
  return s;
}

std::string cubeModel(const std::string& build = "<item objectid=\"1\"/>",
                      const std::string& extraTriangle = "") {
  return std::string(kModelHead) + "<resources>\n" + cubeObject(1, extraTriangle) +
         "</resources>\n<build>" + build + "</build>\n</model>\n";
}

void expect3mfError(const std::string& bytes, std::initializer_list<std::string> parts) {
  expectContains(errorOf([&] { readMeshBytes("part.3mf", bytes); }), parts);
}

TEST(MeshWriters3mfRead, ReadsAPackagedCube) {
  MeshReadReport report;
  const TriangleMesh mesh = readMeshBytes("cube.3mf", fuzz::packageModel(cubeModel()), {}, &report);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_NEAR(signedVolume(mesh), 1.0, 1e-12);
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_EQ(report.fileFaces, 12u);
}

TEST(MeshWriters3mfRead, AppliesBuildAndComponentTransforms) {
  // Object 2 places object 1 twice (one mirrored in x); the item scales by 2 and moves by 10.
  const std::string model =
      std::string(kModelHead) + "<resources>\n" + cubeObject(1) +
      "<object id=\"2\"><components>"
      "<component objectid=\"1\"/>"
      "<component objectid=\"1\" transform=\"-1 0 0 0 1 0 0 0 1 -2 0 0\"/>"
      "</components></object>\n</resources>\n"
      "<build><item objectid=\"2\" transform=\"2 0 0 0 2 0 0 0 2 10 0 0\"/></build></model>\n";
  const TriangleMesh mesh = readMeshBytes("parts.3mf", fuzz::packageModel(model));
  EXPECT_EQ(mesh.triangles.size(), 24u);
  EXPECT_NEAR(signedVolume(mesh), 16.0, 1e-9);  // orientation kept through the mirror
  const Bounds b = meshBounds(mesh);
  EXPECT_NEAR(b.min.x, 10.0 - 6.0, 1e-12);
  EXPECT_NEAR(b.max.x, 12.0, 1e-12);
}

TEST(MeshWriters3mfRead, NotAZip) {
  expect3mfError("hello, I am text", {"part.3mf", "not a zip"});
  expect3mfError("", {"part.3mf", "not a zip"});
  expect3mfError("PK\x03\x04 and then nothing that makes sense at all", {"part.3mf", "not a zip"});
}

TEST(MeshWriters3mfRead, MissingModelPart) {
  expect3mfError(fuzz::storedZip({{"readme.txt", "hi"}}), {"part.3mf", "missing 3D model part"});
  const std::string rels =
      "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">\n"
      "<Relationship Target=\"/3D/elsewhere.model\" Id=\"r\" "
      "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>"
      "</Relationships>";
  expect3mfError(fuzz::storedZip({{"_rels/.rels", rels}}),
                 {"part.3mf: _rels/.rels: line 2:", "/3D/elsewhere.model", "not in the archive"});
}

TEST(MeshWriters3mfRead, FallsBackToTheDefaultModelPart) {
  MeshReadReport report;
  const std::string zip = fuzz::storedZip({{"3D/3dmodel.model", cubeModel()}});
  EXPECT_EQ(readMeshBytes("norels.3mf", zip, {}, &report).triangles.size(), 12u);
  ASSERT_EQ(report.warnings.size(), 1u);
  expectContains(report.warnings[0], {"norels.3mf", "_rels/.rels", "3D/3dmodel.model"});
}

TEST(MeshWriters3mfRead, CorruptEntryIsAnError) {
  std::string zip = fuzz::packageModel(cubeModel());
  zip[zip.find("<vertex") + 3] = 'X';  // content no longer matches its CRC
  expect3mfError(zip, {"part.3mf: 3D/3dmodel.model", "corrupt"});
}

TEST(MeshWriters3mfRead, BadIndexNamesTheLine) {
  // Line 1 declaration, 2 model, 3 resources, 4 object, 5-12 vertices, 13 triangles start,
  // 14-25 triangles, 26 the bad one.
  expect3mfError(fuzz::packageModel(cubeModel("<item objectid=\"1\"/>",
                                              "<triangle v1=\"0\" v2=\"8\" v3=\"1\"/>\n")),
                 {"part.3mf: 3D/3dmodel.model: line 26:", "v2=8", "out of range", "8 vertices"});
  expect3mfError(fuzz::packageModel(cubeModel("<item objectid=\"1\"/>",
                                              "<triangle v1=\"-1\" v2=\"2\" v3=\"1\"/>\n")),
                 {"line 26:", "v1=-1", "out of range"});
  expect3mfError(fuzz::packageModel(cubeModel("<item objectid=\"1\"/>",
                                              "<triangle v1=\"1.5\" v2=\"2\" v3=\"1\"/>\n")),
                 {"line 26:", "v1 is not an integer", "'1.5'"});
}

TEST(MeshWriters3mfRead, MalformedNumbersAndXml) {
  std::string model = cubeModel();
  const size_t at = model.find("x=\"1.000000\"");
  expect3mfError(fuzz::packageModel(model.substr(0, at) + "x=\"1.0.0\"" + model.substr(at + 12)),
                 {"3D/3dmodel.model: line 6:", "not a number", "'1.0.0'"});
  expect3mfError(fuzz::packageModel(model.substr(0, at) + "x=\"nan\"" + model.substr(at + 12)),
                 {"line 6:", "NaN"});
  expect3mfError(fuzz::packageModel(model.substr(0, model.rfind("</model>"))),
                 {"3D/3dmodel.model: line", "<model> is not closed"});
  expect3mfError(fuzz::packageModel(cubeModel("<item objectid=\"5\"/>")),
                 {"objectid 5", "no object"});
  expect3mfError(fuzz::packageModel(cubeModel("")), {"places no <item>"});
  expect3mfError(fuzz::packageModel(cubeModel("<item objectid=\"1\" transform=\"1 0 0\"/>")),
                 {"transform must have 12 numbers"});
  expect3mfError(fuzz::packageModel("<!DOCTYPE model>" + cubeModel()), {"line 1:", "document"});
  std::string required = cubeModel();
  required.insert(required.find("<model ") + 7,
                  "xmlns:b=\"http://schemas.microsoft.com/3dmanufacturing/beamlattice/2017/02\" "
                  "requiredextensions=\"b\" ");
  expect3mfError(fuzz::packageModel(required), {"line 2:", "beamlattice", "cannot read"});
}

}  // namespace
}  // namespace strata
