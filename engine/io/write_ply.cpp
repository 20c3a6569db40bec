// Binary little-endian PLY: comments naming Strata and the unit; element vertex with double
// x y z and uchar red green blue (the sRGB colour of the leaf of the first triangle using the
// vertex; grey 0.8 for a vertex no triangle uses); element face with a list of uchar count and
// int indices. The encodings are mesh_writers.h's, shared with the streamed export.
#include <cstring>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "engine/io/mesh_writer_formats.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace {

// `value` at `out`, little-endian whatever the host.
template <typename T>
void putLittle(T value, char* out) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  uint16_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  if (first != 1) {  // a big-endian host: reverse to little-endian
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  std::memcpy(out, raw, sizeof(T));
}

}  // namespace

std::string binaryPlyHeader(const std::string& unit, uint64_t vertices, uint64_t faces) {
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment Strata export\n";
  header += "comment unit " + meshio::oneLine(unit) + "\n";
  header += "element vertex " + std::to_string(vertices) + "\n";
  header += "property double x\nproperty double y\nproperty double z\n";
  header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "element face " + std::to_string(faces) + "\n";
  header += "property list uchar int vertex_indices\nend_header\n";
  return header;
}

std::array<uint8_t, 3> plyColour(const LeafStyle& style) {
  return meshio::srgb8(style.color);
}

std::array<uint8_t, 3> plyUnusedColour() {
  return meshio::srgb8(LeafStyle().color);
}

void encodePlyVertex(const glm::dvec3& p, const std::array<uint8_t, 3>& colour, char* out) {
  for (int k = 0; k < 3; ++k) putLittle(p[k], out + 8 * k);
  std::memcpy(out + 24, colour.data(), 3);
}

void encodePlyFace(const std::array<uint32_t, 3>& corners, char* out) {
  out[0] = char(3);
  for (int k = 0; k < 3; ++k) putLittle(int32_t(corners[size_t(k)]), out + 1 + 4 * k);
}

namespace meshio {

void writePly(const std::string& path, const ExportMesh& em, Progress* progress) {
  const TriangleMesh& mesh = em.mesh;
  if (mesh.positions.size() > size_t(std::numeric_limits<int32_t>::max())) {
    throw Error(path + ": too many vertices for PLY's int indices (" +
                std::to_string(mesh.positions.size()) + ")");
  }

  // The colour of each vertex: that of the first triangle's leaf that uses it.
  std::vector<std::array<uint8_t, 3>> colours(mesh.positions.size(), plyUnusedColour());
  std::vector<bool> coloured(mesh.positions.size(), false);
  std::map<uint32_t, std::array<uint8_t, 3>> leafColours;
  for (const auto& [id, style] : em.leaves) leafColours[id] = plyColour(style);
  // Progress counts the colouring pass and the writing (vertices, then faces) as one stage.
  const size_t total = 2 * mesh.triangles.size() + mesh.positions.size();
  size_t done = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    reportEvery(progress, "write PLY", done++, total);
    for (uint32_t v : mesh.triangles[t]) {
      if (coloured[v]) continue;
      coloured[v] = true;
      colours[v] = leafColours.at(em.triangleLeaf[t]);
    }
  }

  writeFileAtomically(path, [&](std::ostream& out) {
    const std::string header =
        binaryPlyHeader(em.unit, mesh.positions.size(), mesh.triangles.size());
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    writeRecords(
        out, mesh.positions.size(),
        [&](size_t first, size_t last, std::string& bytes) {
          const size_t at = bytes.size();
          bytes.resize(at + (last - first) * kPlyVertexBytes);
          for (size_t v = first; v < last; ++v)
            encodePlyVertex(mesh.positions[v], colours[v],
                            &bytes[at + (v - first) * kPlyVertexBytes]);
        },
        progress, "write PLY", done, total);
    done += mesh.positions.size();
    writeRecords(
        out, mesh.triangles.size(),
        [&](size_t first, size_t last, std::string& bytes) {
          const size_t at = bytes.size();
          bytes.resize(at + (last - first) * kPlyFaceBytes);
          for (size_t t = first; t < last; ++t)
            encodePlyFace(mesh.triangles[t], &bytes[at + (t - first) * kPlyFaceBytes]);
        },
        progress, "write PLY", done, total);
    if (progress) progress->check();  // a cancel during the write replaces nothing
  });
}

}  // namespace meshio
}  // namespace strata
