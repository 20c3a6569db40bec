// STL, binary and ASCII. Binary: an 80-byte header, a little-endian uint32 facet count, then
// 50 bytes per facet (normal, three vertices as float32, a 16-bit attribute); the count must
// account for the file size exactly. ASCII: solid / facet normal / outer loop / vertex x3 /
// endloop / endfacet / endsolid, keywords case-insensitive, several solids allowed.
// A file is binary when its count matches its size, or when it does not start with "solid"
// followed by text. Facet normals are ignored (winding decides orientation). Identical
// positions are welded into shared vertices.
#include <cstdint>
#include <cstring>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_readers.h"

namespace strata {
namespace meshio {
namespace {

constexpr size_t kHeaderBytes = 80;
constexpr size_t kFacetBytes = 50;

uint32_t readU32(const std::string& bytes, size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

float readF32(const std::string& bytes, size_t at) {
  const uint32_t bits = readU32(bytes, at);
  float value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

bool startsWithSolid(const std::string& bytes) {
  size_t i = 0;
  while (i < bytes.size() &&
         (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n'))
    ++i;
  return bytes.size() - i >= 5 && equalsIgnoreCase(std::string_view(bytes).substr(i, 5), "solid");
}

// Text has no NUL bytes and no other control characters besides whitespace.
bool looksLikeText(const std::string& bytes) {
  const size_t n = std::min<size_t>(bytes.size(), 4096);
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c < 32 && c != '\n' && c != '\r' && c != '\t' && c != '\v' && c != '\f') return false;
  }
  return true;
}

TriangleMesh parseBinary(const std::string& name, const std::string& bytes,
                         MeshReadReport* report) {
  if (bytes.size() < kHeaderBytes + 4) {
    failAtByte(name, bytes.size(),
               "file is too short for a binary STL (" + std::to_string(bytes.size()) +
                   " bytes; the header and facet count need 84)");
  }
  const uint64_t count = readU32(bytes, kHeaderBytes);
  const uint64_t expected = kHeaderBytes + 4 + kFacetBytes * count;
  if (expected != bytes.size()) {
    failAtByte(name, kHeaderBytes,
               "binary STL facet count " + std::to_string(count) + " needs a file of " +
                   std::to_string(expected) + " bytes, but the file has " +
                   std::to_string(bytes.size()) + " bytes (truncated, or the count is wrong)");
  }
  TriangleMesh mesh;
  mesh.positions.reserve(count * 3);
  mesh.triangles.reserve(count);
  for (uint64_t f = 0; f < count; ++f) {
    const size_t facet = kHeaderBytes + 4 + kFacetBytes * f;
    for (int v = 0; v < 3; ++v) {
      glm::dvec3 p;
      for (int k = 0; k < 3; ++k) {
        const size_t at = facet + 12 + 12 * v + 4 * k;
        p[k] = readF32(bytes, at);
        requireFiniteAtByte(name, at, p[k]);
      }
      mesh.positions.push_back(p);
    }
    const uint32_t base = static_cast<uint32_t>(3 * f);
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  report->fileFaces = count;
  return mesh;
}

TriangleMesh parseAscii(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  enum class Expect { Solid, FacetOrEnd, OuterLoop, Vertex, EndFacet, AfterSolid };
  TriangleMesh mesh;
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  std::vector<glm::dvec3> loop;
  Expect expect = Expect::Solid;
  size_t lastLine = 0;

  auto expected = [&](Expect e) -> std::string {
    switch (e) {
      case Expect::Solid:
        return "'solid'";
      case Expect::FacetOrEnd:
        return "'facet' or 'endsolid'";
      case Expect::OuterLoop:
        return "'outer loop'";
      case Expect::Vertex:
        return "'vertex' or 'endloop'";
      case Expect::EndFacet:
        return "'endfacet'";
      case Expect::AfterSolid:
        return "'solid' or the end of the file";
    }
    return "";
  };

  std::string_view line;
  while (lines.next(line)) {
    const size_t lineNo = lines.lineNumber();
    lastLine = lineNo;
    splitTokens(line, tokens, /*hashComments=*/false);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    auto unexpected = [&]() {
      failAtLine(name, lineNo, "expected " + expected(expect) + ", found " + quoted(keyword));
    };

    switch (expect) {
      case Expect::Solid:
      case Expect::AfterSolid:
        if (!equalsIgnoreCase(keyword, "solid")) unexpected();
        expect = Expect::FacetOrEnd;
        break;
      case Expect::FacetOrEnd:
        if (equalsIgnoreCase(keyword, "endsolid")) {
          expect = Expect::AfterSolid;
        } else if (equalsIgnoreCase(keyword, "facet")) {
          expect = Expect::OuterLoop;  // the normal is ignored: winding decides orientation
        } else {
          unexpected();
        }
        break;
      case Expect::OuterLoop:
        if (!(tokens.size() == 2 && equalsIgnoreCase(keyword, "outer") &&
              equalsIgnoreCase(tokens[1], "loop")))
          unexpected();
        loop.clear();
        expect = Expect::Vertex;
        break;
      case Expect::Vertex:
        if (equalsIgnoreCase(keyword, "vertex")) {
          if (tokens.size() != 4) {
            failAtLine(name, lineNo,
                       "vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
          }
          glm::dvec3 p;
          for (int k = 0; k < 3; ++k) p[k] = parseCoordinate(name, lineNo, tokens[1 + k]);
          loop.push_back(p);
        } else if (equalsIgnoreCase(keyword, "endloop")) {
          if (loop.size() < 3) {
            failAtLine(name, lineNo,
                       "facet has " + std::to_string(loop.size()) + " vertices, needs 3");
          }
          const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
          mesh.positions.insert(mesh.positions.end(), loop.begin(), loop.end());
          for (uint32_t k = 1; k + 1 < loop.size(); ++k) {
            mesh.triangles.push_back({base, base + k, base + k + 1});
          }
          ++report->fileFaces;
          expect = Expect::EndFacet;
        } else {
          unexpected();
        }
        break;
      case Expect::EndFacet:
        if (!equalsIgnoreCase(keyword, "endfacet")) unexpected();
        expect = Expect::FacetOrEnd;
        break;
    }
  }
  if (expect != Expect::AfterSolid) {
    failAtLine(name, lastLine + 1,
               "unexpected end of file (truncated?): expected " + expected(expect));
  }
  return mesh;
}

}  // namespace

TriangleMesh parseStl(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  bool binary = true;
  if (bytes.size() >= kHeaderBytes + 4) {
    const uint64_t count = readU32(bytes, kHeaderBytes);
    const bool sizeMatches = kHeaderBytes + 4 + kFacetBytes * count == bytes.size();
    binary = sizeMatches || !(startsWithSolid(bytes) && looksLikeText(bytes));
  } else {
    binary = !startsWithSolid(bytes);
  }
  TriangleMesh mesh = binary ? parseBinary(name, bytes, report) : parseAscii(name, bytes, report);
  report->fileVertices = mesh.positions.size();
  weldIdenticalPositions(mesh);
  return mesh;
}

}  // namespace meshio
}  // namespace strata
