// Binary STL: an 80-byte header ("Strata binary STL, unit: <unit>", zero padded; never starting
// with "solid"), a little-endian uint32 facet count, then per facet the unit normal computed
// from the winding (zero for a zero-area facet), three vertices as float32 and attribute 0.
#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "engine/io/mesh_writer_formats.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

void putU32(std::string& out, uint32_t value) {
  const char bytes[4] = {char(value & 0xff), char((value >> 8) & 0xff), char((value >> 16) & 0xff),
                         char((value >> 24) & 0xff)};
  out.append(bytes, 4);
}

}  // namespace

void writeStl(const std::string& path, const ExportMesh& em, Progress* progress) {
  const TriangleMesh& mesh = em.mesh;
  if (mesh.triangles.size() > std::numeric_limits<uint32_t>::max()) {
    throw Error(path + ": too many triangles for STL (" + std::to_string(mesh.triangles.size()) +
                ")");
  }
  for (const glm::dvec3& p : mesh.positions) checkStlCoordinates(path, p);
  writeFileAtomically(path, [&](std::ostream& out) {
    const std::string header = binaryStlHeader(em.unit, uint32_t(mesh.triangles.size()));
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    if (progress) progress->report("write STL", 0.0);
    writeRecords(
        out, mesh.triangles.size(),
        [&](size_t first, size_t last, std::string& bytes) {
          const size_t at = bytes.size();
          bytes.resize(at + (last - first) * kStlFacetBytes);
          char* out = &bytes[at];
          for (size_t t = first; t < last; ++t, out += kStlFacetBytes) {
            const auto& tri = mesh.triangles[t];
            encodeStlFacet(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]],
                           out);
          }
        },
        progress, "write STL", 0, mesh.triangles.size());
    if (progress) progress->check();  // a cancel during the write replaces nothing
  });
}

}  // namespace meshio

std::string binaryStlHeader(const std::string& unit, uint32_t facets) {
  std::string header = "Strata binary STL, unit: " + meshio::oneLine(unit);
  header.resize(80, '\0');
  meshio::putU32(header, facets);
  return header;
}

void checkStlCoordinates(const std::string& path, const glm::dvec3& p) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(p[k]) > double(std::numeric_limits<float>::max())) {
      throw Error(path + ": coordinate " + std::to_string(p[k]) +
                  " does not fit STL's 32-bit floats");
    }
  }
}

void encodeStlFacet(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, char* out) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "STL floats are written as-is");
  glm::dvec3 normal = glm::cross(b - a, c - a);
  const double length = glm::length(normal);
  normal = length > 0.0 && std::isfinite(length) ? normal / length : glm::dvec3(0.0);
  const float facet[12] = {float(normal.x), float(normal.y), float(normal.z), float(a.x),
                           float(a.y),      float(a.z),      float(b.x),      float(b.y),
                           float(b.z),      float(c.x),      float(c.y),      float(c.z)};
  std::memcpy(out, facet, sizeof(facet));
  out[48] = out[49] = '\0';  // attribute 0
}

}  // namespace strata
