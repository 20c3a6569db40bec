// Binary little-endian PLY: comments naming Strata and the unit; element vertex with double
// x y z and uchar red green blue (the sRGB colour of the leaf of the first triangle using the
// vertex; grey 0.8 for a vertex no triangle uses); element face with a list of uchar count and
// int indices.
#include <cstring>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "engine/io/mesh_writer_formats.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

template <typename T>
void putLittle(std::string& out, T value) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  uint16_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  if (first != 1) {  // a big-endian host: reverse to little-endian
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  out.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

}  // namespace

void writePly(const std::string& path, const ExportMesh& em, Progress* progress) {
  const TriangleMesh& mesh = em.mesh;
  if (mesh.positions.size() > size_t(std::numeric_limits<int32_t>::max())) {
    throw Error(path + ": too many vertices for PLY's int indices (" +
                std::to_string(mesh.positions.size()) + ")");
  }

  // The colour of each vertex: that of the first triangle's leaf that uses it.
  const std::array<uint8_t, 3> unused = srgb8(LeafStyle().color);
  std::vector<std::array<uint8_t, 3>> colours(mesh.positions.size(), unused);
  std::vector<bool> coloured(mesh.positions.size(), false);
  std::map<uint32_t, std::array<uint8_t, 3>> leafColours;
  for (const auto& [id, style] : em.leaves) leafColours[id] = srgb8(style.color);
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
    std::string buffer;
    buffer += "ply\nformat binary_little_endian 1.0\ncomment Strata export\n";
    buffer += "comment unit " + oneLine(em.unit) + "\n";
    buffer += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
    buffer += "property double x\nproperty double y\nproperty double z\n";
    buffer += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    buffer += "element face " + std::to_string(mesh.triangles.size()) + "\n";
    buffer += "property list uchar int vertex_indices\nend_header\n";
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    writeRecords(
        out, mesh.positions.size(),
        [&](size_t first, size_t last, std::string& bytes) {
          for (size_t v = first; v < last; ++v) {
            for (int k = 0; k < 3; ++k) putLittle(bytes, mesh.positions[v][k]);
            bytes.append(reinterpret_cast<const char*>(colours[v].data()), 3);
          }
        },
        progress, "write PLY", done, total);
    done += mesh.positions.size();
    writeRecords(
        out, mesh.triangles.size(),
        [&](size_t first, size_t last, std::string& bytes) {
          for (size_t t = first; t < last; ++t) {
            bytes += static_cast<char>(3);
            for (uint32_t v : mesh.triangles[t]) putLittle(bytes, static_cast<int32_t>(v));
          }
        },
        progress, "write PLY", done, total);
    if (progress) progress->check();  // a cancel during the write replaces nothing
  });
}

}  // namespace meshio
}  // namespace strata
