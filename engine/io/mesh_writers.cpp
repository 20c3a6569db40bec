// writeMeshFile: validate the ExportMesh, pick the writer by extension (the table in
// mesh_formats.h). Also the helpers the format writers share (mesh_writer_formats.h).
#include "engine/io/mesh_writers.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

#include "engine/io/mesh_formats.h"
#include "engine/io/mesh_writer_formats.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace meshio {

void reportEvery(Progress* progress, const std::string& stage, size_t index, size_t total) {
  if (!progress || index % kProgressStride != 0) return;
  progress->report(stage, total == 0 ? 1.0 : double(index) / double(total));
}

void writeRecords(std::ostream& out, size_t count, const AppendRecords& append, Progress* progress,
                  const std::string& stage, size_t done, size_t total) {
  const size_t blocks = (count + kProgressStride - 1) / kProgressStride;
  const size_t perGroup = size_t(std::max(1, workerCount())) * 2;
  std::vector<std::string> buffers(std::min(blocks, perGroup));
  for (size_t group = 0; group < blocks; group += perGroup) {
    const size_t groupEnd = std::min(blocks, group + perGroup);
    parallelFor(int64_t(group), int64_t(groupEnd), 1, [&](int64_t first, int64_t last) {
      for (int64_t block = first; block < last; ++block) {
        std::string& bytes = buffers[size_t(block) - group];
        bytes.clear();
        append(size_t(block) * kProgressStride,
               std::min(count, size_t(block + 1) * kProgressStride), bytes);
      }
    });
    for (size_t block = group; block < groupEnd; ++block) {
      const std::string& bytes = buffers[block - group];
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    if (progress)
      progress->report(
          stage, total == 0
                     ? 1.0
                     : double(done + std::min(count, groupEnd * kProgressStride)) / double(total));
  }
}

void appendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, 9);
  out.append(buffer, result.ptr);
}

double storedAsFloat(double value) {
  return double(float(value));
}

double storedAsNineDigits(double value) {
  char buffer[32];
  const auto printed =
      std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, 9);
  double parsed = 0.0;
  std::from_chars(buffer, printed.ptr, parsed);
  return parsed;
}

double storedExactly(double value) {
  return value;
}

double linearToSrgb(double linear) {
  const double c = std::isnan(linear) ? 0.0 : std::min(1.0, std::max(0.0, linear));
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

std::array<uint8_t, 3> srgb8(const glm::vec3& linear) {
  std::array<uint8_t, 3> bytes{};
  for (int i = 0; i < 3; ++i) {
    bytes[i] = static_cast<uint8_t>(std::lround(linearToSrgb(linear[i]) * 255.0));
  }
  return bytes;
}

std::string oneLine(const std::string& text) {
  std::string line = text;
  for (char& ch : line) {
    if (static_cast<unsigned char>(ch) < 32 || ch == 127) ch = '?';
  }
  return line;
}

}  // namespace meshio

namespace {

void validate(const std::string& path, const ExportMesh& mesh) {
  const auto& m = mesh.mesh;
  if (m.triangles.empty()) throw Error(path + ": nothing to write (the mesh has no triangles)");
  if (mesh.triangleLeaf.size() != m.triangles.size()) {
    throw Error(path + ": cannot write: " + std::to_string(mesh.triangleLeaf.size()) +
                " leaf ids for " + std::to_string(m.triangles.size()) + " triangles");
  }
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const glm::dvec3& p = m.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw Error(path + ": cannot write: vertex " + std::to_string(i) + " is not finite");
    }
  }
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    for (uint32_t v : m.triangles[t]) {
      if (v >= m.positions.size()) {
        throw Error(path + ": cannot write: triangle " + std::to_string(t) + " uses vertex " +
                    std::to_string(v) + " of " + std::to_string(m.positions.size()));
      }
    }
    if (!mesh.leaves.count(mesh.triangleLeaf[t])) {
      throw Error(path + ": cannot write: triangle " + std::to_string(t) + " has leaf id " +
                  std::to_string(mesh.triangleLeaf[t]) + ", which has no style");
    }
  }
}

}  // namespace

namespace {

const MeshFormat& writableFormat(const std::string& path) {
  const MeshFormat* format = meshFormatFor(path, MeshAccess::Write);
  if (!format) {
    const std::string ext = lowerExtension(path);
    throw Error(path + ": cannot write mesh format '" + (ext.empty() ? "" : "." + ext) +
                "' (supported: " + meshExtensionList(MeshAccess::Write, ", ") + ")");
  }
  return *format;
}

}  // namespace

void writeMeshFile(const std::string& path, const ExportMesh& mesh, Progress* progress) {
  const MeshFormat& format = writableFormat(path);
  if (progress) progress->check();
  validate(path, mesh);
  format.write(path, mesh, progress);
}

TriangleMesh storedMesh(const std::string& path, TriangleMesh mesh) {
  const StoredCoordinate stored = storedCoordinate(path);
  parallelFor(0, int64_t(mesh.positions.size()), 65536, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) {
      glm::dvec3& p = mesh.positions[size_t(i)];
      p = glm::dvec3(stored(p.x), stored(p.y), stored(p.z));
    }
  });
  return mesh;
}

StoredCoordinate storedCoordinate(const std::string& path) {
  return writableFormat(path).stored;
}

}  // namespace strata
