// Wavefront OBJ, geometry only: `v x y z [w] [r g b ...]` and `f` with i, i/t, i//n or i/t/n
// references (1-based; negative ones count back from the last vertex read so far). Texture
// coordinates, normals, groups, materials and smoothing are ignored; `l` and `p` elements are
// ignored with one warning; any other statement is ignored and counted in a warning.
// Polygons are fan-triangulated from their first corner.
#include <cstdint>
#include <limits>

#include "engine/io/mesh_readers.h"

namespace strata {
namespace meshio {
namespace {

// Statements that carry no solid geometry and are skipped silently.
bool isIgnoredStatement(std::string_view keyword) {
  static const char* const kIgnored[] = {
      "vt",     "vn",         "vp",        "g",      "o",     "s",        "usemtl",
      "mtllib", "usemap",     "maplib",    "cstype", "deg",   "bmat",     "step",
      "curv",   "curv2",      "surf",      "parm",   "trim",  "hole",     "scrv",
      "sp",     "end",        "con",       "mg",     "bevel", "c_interp", "d_interp",
      "lod",    "shadow_obj", "trace_obj", "ctech",  "stech", "call",     "csh"};
  for (const char* k : kIgnored) {
    if (keyword == k) return true;
  }
  return false;
}

// A positive index that refers past the vertices read so far is checked at the end of the file
// (some writers put faces first); its line is kept for the message.
struct PendingIndex {
  long long index;  // 1-based as written
  size_t line;
};

}  // namespace

TriangleMesh parseObj(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  TriangleMesh mesh;
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  std::vector<uint32_t> polygon;
  std::vector<PendingIndex> pending;
  size_t linesAndPoints = 0;
  size_t unknownCount = 0;
  std::string firstUnknown;
  size_t firstUnknownLine = 0;

  std::string_view line;
  while (lines.next(line)) {
    const size_t lineNo = lines.lineNumber();
    splitTokens(line, tokens, /*hashComments=*/true);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];

    if (keyword == "v") {
      if (tokens.size() < 4) {
        failAtLine(name, lineNo,
                   "vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
      }
      glm::dvec3 p;
      for (int k = 0; k < 3; ++k) p[k] = parseCoordinate(name, lineNo, tokens[1 + k]);
      for (size_t k = 4; k < tokens.size(); ++k) {  // w or colour components: numbers only
        double ignored;
        if (!parseNumber(tokens[k], ignored)) {
          failAtLine(name, lineNo, "not a number: " + quoted(tokens[k]));
        }
      }
      if (mesh.positions.size() >= std::numeric_limits<uint32_t>::max()) {
        failAtLine(name, lineNo, "too many vertices");
      }
      mesh.positions.push_back(p);
      continue;
    }

    if (keyword == "f" || keyword == "fo") {
      if (tokens.size() < 4) {
        failAtLine(name, lineNo,
                   "face needs at least 3 vertices, found " + std::to_string(tokens.size() - 1));
      }
      polygon.clear();
      const long long available = static_cast<long long>(mesh.positions.size());
      for (size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view ref = tokens[k];
        const size_t slash1 = ref.find('/');
        const std::string_view vertexPart = ref.substr(0, slash1);
        long long index = 0;
        if (!parseInteger(vertexPart, index)) {
          failAtLine(name, lineNo, "bad vertex reference " + quoted(ref));
        }
        if (slash1 != std::string_view::npos) {  // t and n parts: empty or an integer
          std::string_view rest = ref.substr(slash1 + 1);
          const size_t slash2 = rest.find('/');
          const std::string_view texPart = rest.substr(0, slash2);
          const std::string_view normalPart =
              slash2 == std::string_view::npos ? std::string_view() : rest.substr(slash2 + 1);
          long long ignored;
          const bool texOk = texPart.empty() || parseInteger(texPart, ignored);
          const bool normalOk = slash2 == std::string_view::npos ||
                                (!normalPart.empty() && parseInteger(normalPart, ignored));
          if (!texOk || !normalOk || (slash2 == std::string_view::npos && texPart.empty())) {
            failAtLine(name, lineNo, "bad vertex reference " + quoted(ref));
          }
        }
        if (index == 0) {
          failAtLine(name, lineNo, "vertex index 0 is invalid (OBJ indices start at 1)");
        }
        long long resolved;
        if (index < 0) {
          resolved = available + index;
          if (resolved < 0) {
            failAtLine(name, lineNo,
                       "negative vertex index " + std::to_string(index) +
                           " is out of range: only " + std::to_string(available) +
                           " vertices precede it");
          }
        } else {
          resolved = index - 1;
          if (resolved >= available) pending.push_back({index, lineNo});
          if (resolved >= static_cast<long long>(std::numeric_limits<uint32_t>::max())) {
            failAtLine(name, lineNo, "vertex index " + std::to_string(index) + " is out of range");
          }
        }
        polygon.push_back(static_cast<uint32_t>(resolved));
      }
      ++report->fileFaces;
      for (size_t k = 1; k + 1 < polygon.size(); ++k) {
        mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
      }
      continue;
    }

    if (keyword == "l" || keyword == "p") {
      ++linesAndPoints;
      continue;
    }
    if (isIgnoredStatement(keyword)) continue;
    if (unknownCount++ == 0) {
      firstUnknown = quoted(keyword);
      firstUnknownLine = lineNo;
    }
  }

  const long long total = static_cast<long long>(mesh.positions.size());
  for (const PendingIndex& p : pending) {
    if (p.index > total) {
      failAtLine(name, p.line,
                 "vertex index " + std::to_string(p.index) + " is out of range: the file has " +
                     std::to_string(total) + " vertices");
    }
  }

  report->fileVertices = mesh.positions.size();
  if (linesAndPoints > 0) {
    addWarning(report, name,
               "ignored " + std::to_string(linesAndPoints) +
                   " line/point elements ('l', 'p'): only faces make a solid");
  }
  if (unknownCount > 0) {
    addWarning(report, name,
               "ignored " + std::to_string(unknownCount) + " unknown statement(s), the first " +
                   firstUnknown + " at line " + std::to_string(firstUnknownLine));
  }
  return mesh;
}

}  // namespace meshio
}  // namespace strata
