// The entry logic of the fuzz targets, shared with the FuzzCorpus gtest
// (tests/engine/io/fuzz_corpus_test.cpp) so that every normal test run (and the sanitizer build
// CI does) checks the same no-crash property on fixed inputs. Header-only: the fuzz targets
// are built outside the gtest binary.
//
// The property: any bytes either parse or throw strata::Error. Any other exception, a crash, a
// sanitizer report or a hang is a bug.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/document/expansion.h"
#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/export/contour_scene.h"
#include "engine/geometry/degenerate_repair.h"
#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/io/scene_file.h"
#include "engine/kinds/primitives.h"
#include "engine/util/error.h"
#include "engine/util/progress.h"

namespace strata {
namespace fuzz {

// CRC-32 (IEEE 802.3, as zip uses).
inline uint32_t crc32(std::string_view bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t crc = 0xFFFFFFFFu;
  for (char ch : bytes) crc = table[(crc ^ static_cast<uint8_t>(ch)) & 0xFF] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

// A zip archive holding `entries` (name, content) uncompressed ("stored"), written here rather
// than with libzip so tests can build packages byte by byte, including broken ones.
inline std::string storedZip(const std::vector<std::pair<std::string, std::string>>& entries) {
  auto put16 = [](std::string& out, uint32_t v) {
    out += static_cast<char>(v & 0xFF);
    out += static_cast<char>((v >> 8) & 0xFF);
  };
  auto put32 = [&](std::string& out, uint32_t v) {
    put16(out, v & 0xFFFF);
    put16(out, v >> 16);
  };
  const uint32_t kDosDate = (0 << 9) | (1 << 5) | 1;  // 1980-01-01
  std::string zip;
  std::string central;
  for (const auto& [name, content] : entries) {
    const uint32_t offset = static_cast<uint32_t>(zip.size());
    const uint32_t crc = crc32(content);
    const uint32_t size = static_cast<uint32_t>(content.size());
    put32(zip, 0x04034b50);
    put16(zip, 20);  // version needed
    put16(zip, 0);   // flags
    put16(zip, 0);   // stored
    put16(zip, 0);   // time
    put16(zip, kDosDate);
    put32(zip, crc);
    put32(zip, size);
    put32(zip, size);
    put16(zip, static_cast<uint32_t>(name.size()));
    put16(zip, 0);  // extra
    zip += name;
    zip += content;

    put32(central, 0x02014b50);
    put16(central, 20);  // made by
    put16(central, 20);  // needed
    put16(central, 0);
    put16(central, 0);
    put16(central, 0);
    put16(central, kDosDate);
    put32(central, crc);
    put32(central, size);
    put32(central, size);
    put16(central, static_cast<uint32_t>(name.size()));
    put16(central, 0);  // extra
    put16(central, 0);  // comment
    put16(central, 0);  // disk
    put16(central, 0);  // internal attributes
    put32(central, 0);  // external attributes
    put32(central, offset);
    central += name;
  }
  const uint32_t centralOffset = static_cast<uint32_t>(zip.size());
  zip += central;
  put32(zip, 0x06054b50);
  put16(zip, 0);
  put16(zip, 0);
  put16(zip, static_cast<uint32_t>(entries.size()));
  put16(zip, static_cast<uint32_t>(entries.size()));
  put32(zip, static_cast<uint32_t>(central.size()));
  put32(zip, centralOffset);
  put16(zip, 0);
  return zip;
}

// A 3MF package around `modelXml`: content types, the model relationship, the model part.
inline std::string packageModel(const std::string& modelXml) {
  return storedZip(
      {{"[Content_Types].xml",
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types "
        "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default "
        "Extension=\"model\" "
        "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>\n"},
       {"_rels/.rels",
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships "
        "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship "
        "Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
        "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></"
        "Relationships>\n"},
       {"3D/3dmodel.model", modelXml}});
}

// Mesh readers. Byte 0 picks the input: bits 0-2 (mod 6) the format, 0 .obj, 1 .stl, 2 .ply,
// 3 .off, 4 .3mf (the rest is the package), 5 .3mf (the rest is the model XML, packaged here
// so that mutations reach the XML parser past the zip's CRC); bit 7 sets allowOpen.
inline void runMeshReaders(const uint8_t* data, size_t size) {
  if (size == 0) return;
  static const char* const kNames[6] = {"fuzz.obj", "fuzz.stl", "fuzz.ply",
                                        "fuzz.off", "fuzz.3mf", "fuzz.3mf"};
  const int format = (data[0] & 7) % 6;
  MeshReadOptions options;
  options.allowOpen = (data[0] & 0x80) != 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (format == 5) bytes = packageModel(bytes);
  try {
    MeshReadReport report;
    readMeshBytes(kNames[format], bytes, options, &report);
  } catch (const Error&) {
    // A readable error is the expected outcome for malformed input.
  }
}

// Scene files: the bytes as scene JSON. Mesh paths resolve against a folder that does not
// exist, so mesh nodes fail to load with an Error unless the path is absolute.
inline void runSceneFile(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    SceneLoadReport report;
    parseScene(text, "fuzz.strata.json", "/nonexistent-strata-fuzz-folder", &report);
  } catch (const Error&) {
  }
}

// Reads fuzz bytes as numbers; zeros once they run out.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  // A number in [lo, hi] in 256 steps.
  double in(double lo, double hi) { return lo + (hi - lo) * byte() / 255.0; }
  // Three numbers in [lo, hi], read x, y, z in that order. (Reads inside one call's argument
  // list would be unordered: gcc and clang would build different trees from the same bytes,
  // and a finding of the clang-built fuzzer would not reproduce in the gcc-built tests.)
  glm::dvec3 vec(double lo, double hi) {
    const double x = in(lo, hi);
    const double y = in(lo, hi);
    const double z = in(lo, hi);
    return {x, y, z};
  }
  bool done() const { return at_ >= size_; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

// A closed octahedron around the origin with its six corners moved by the bytes: a tiny mesh
// that may fold through itself, prepared as the readers prepare theirs.
inline std::shared_ptr<const TriangleMesh> jitteredOctahedron(ByteReader& in) {
  auto mesh = std::make_shared<TriangleMesh>();
  const glm::dvec3 corners[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                 {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  for (const glm::dvec3& c : corners) {
    const double scale = in.in(0.2, 1.5);
    mesh->positions.push_back(c * scale + in.vec(-0.6, 0.6));
  }
  mesh->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                     {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  prepareMesh(*mesh);
  return mesh;
}

// A node the bytes describe: an operation of 1-3 children (down to `depth` levels) or a leaf
// (a primitive of the table with scaled default parameters, or a jittered octahedron), placed
// by a transform of the bytes.
inline NodePtr fuzzNode(ByteReader& in, int depth, NodeId& nextId) {
  auto node = std::make_shared<Node>();
  node->id = nextId++;
  const uint8_t pick = in.byte();
  const auto& table = primitiveTable();
  if (depth > 0 && pick % 3 == 0) {
    node->kind = NodeKind(pick / 3 % 3);  // Union, Intersection, Difference
    const int children = 1 + in.byte() % 3;
    for (int c = 0; c < children; ++c) node->children.push_back(fuzzNode(in, depth - 1, nextId));
  } else if (pick % 3 == 1) {
    node->kind = NodeKind::Mesh;
    node->mesh = jitteredOctahedron(in);
  } else {
    const PrimitiveInfo& info = table[size_t(pick / 3) % table.size()];
    node->kind = info.kind;
    node->params = scaledPrimitiveParams(info.kind, info.defaults, in.in(0.2, 2.0));
    node->params.segments = in.byte() % 2 ? 0 : 3 + in.byte() % 20;
  }
  node->transform.translate = in.vec(-1, 1);
  node->transform.rotateDegrees = in.vec(0, 360);
  node->transform.scale = in.vec(0.3, 2);
  if (in.byte() % 4 == 0) node->transform.scale.x = -node->transform.scale.x;  // a mirror
  return node;
}

// Whole pipeline: the bytes build a small tree (fuzzNode, up to 3 levels), which is sampled,
// combined and contoured on the CPU at 8 to 47 cells, in tiles of 8 to 23 cells, then readied for
// a file as an export does (triangles without area as the format stores them repaired,
// degenerate_repair.h) for one of the formats' roundings (exact, float32 or nine digits). The
// property: the result is empty or, as the format stores it, a closed, manifold, oriented mesh
// without degenerate triangles; every failure is a strata::Error. Returns whether a mesh came out.
inline bool runPipeline(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  NodeId nextId = 1;
  Scene scene;
  scene.root = fuzzNode(in, 3, nextId);
  scene.settings.resolution = 8 + in.byte() % 40;
  ContourOptions options;
  options.tileCells = 8 + in.byte() % 16;
  const char* const formats[3] = {"fuzz.ply", "fuzz.stl", "fuzz.obj"};
  const std::string path = formats[in.byte() % 3];
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  ExportMesh mesh;
  try {
    mesh = contourScene(scene, evaluator, options, progress);
  } catch (const Error&) {
    return false;
  }
  if (mesh.mesh.triangles.empty()) return false;
  repairDegenerateTriangles(&mesh.mesh, storedCoordinate(path), &mesh.triangleLeaf);
  const MeshCheck c = checkMesh(storedMesh(path, mesh.mesh));
  if (!c.watertight() || c.degenerateTriangles != 0 || !(c.volume > 0.0)) {
    std::fprintf(stderr,
                 "pipeline: %s not a closed manifold: %zu boundary, %zu non-manifold, %zu "
                 "misoriented edges, %zu degenerate triangles, volume %g\n",
                 path.c_str(), size_t(c.boundaryEdges), size_t(c.nonManifoldEdges),
                 size_t(c.misorientedEdges), size_t(c.degenerateTriangles), c.volume);
    std::abort();
  }
  return true;
}

// Instance expansion: the bytes build a DAG of up to 24 nodes where node k is a box or an
// operation over 1 to 6 instances of earlier nodes (so instances may multiply exponentially), with
// a leaf limit of 1 to 1021. The property: checkExpansion answers in O(nodes) and either refuses
// with strata::Error or returns a count within the limit, which then bounds what an evaluation
// at 8 cells visits; no evaluation runs longer than the fuzzer's -timeout. Returns whether the
// scene was accepted (and evaluated).
inline bool runExpansion(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  const int nodes = 1 + in.byte() % 24;
  const uint64_t limit = 1 + uint64_t(in.byte()) * 4;
  std::vector<std::shared_ptr<Node>> made;
  NodeId nextId = 1;
  auto top = std::make_shared<Node>();
  top->id = nextId++;
  top->kind = NodeKind::Union;
  for (int k = 0; k < nodes; ++k) {
    auto node = std::make_shared<Node>();
    node->id = nextId++;
    if (made.empty() || in.byte() % 8 == 0) {
      node->kind = NodeKind::Box;
      node->transform.translate = in.vec(-2, 2);
    } else {
      node->kind = NodeKind(in.byte() % 3);
      const int children = 1 + in.byte() % 6;
      for (int c = 0; c < children; ++c) {
        auto instance = std::make_shared<Node>();
        instance->id = nextId++;
        instance->kind = NodeKind::Instance;
        // Mostly the last few nodes: chains that multiply at every level.
        const size_t back = in.byte() % (made.size() < 3 ? made.size() : 3);
        instance->instanceOf = made[made.size() - 1 - back]->id;
        instance->transform.translate = glm::dvec3(in.in(-1, 1), 0.0, 0.0);
        node->children.push_back(instance);
      }
    }
    node->visible = in.byte() % 8 != 0;
    made.push_back(node);
    top->children.push_back(node);
  }
  Scene scene;
  scene.root = top;
  scene.settings.resolution = 8;
  scene.settings.maxLeaves = limit;
  TreeExpansion measured;
  try {
    measured = checkExpansion(scene.root, limit);
  } catch (const Error&) {
    return false;  // refused before any work: the expected answer to an explosion
  }
  if (measured.leaves > limit) {
    std::fprintf(stderr, "expansion: %llu leaves accepted over the limit %llu\n",
                 (unsigned long long)measured.leaves, (unsigned long long)limit);
    std::abort();
  }
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  try {
    evaluator.evaluate(scene, EvalOptions{}, progress);
  } catch (const Error&) {
  }
  return true;
}

}  // namespace fuzz
}  // namespace strata
