// Object File Format, ascii: a header keyword `OFF` (also `COFF`, `NOFF`, `CNOFF`, `STOFF`...,
// whose extra per-vertex values are read past), the counts `nv nf [ne]` (on the header line or
// the next), nv vertex lines `x y z [extras]`, nf face lines `n i0 ... i(n-1) [colour]`.
// '#' starts a comment. One vertex or face per line; the counts must match the lines exactly.
// Binary OFF and 4OFF / nOFF (other dimensions) are rejected.
#include <cstdint>
#include <limits>

#include "engine/io/mesh_readers.h"

namespace strata {
namespace meshio {
namespace {

// [ST][C][N]OFF: the variants whose vertices start with x y z.
bool isOffKeyword(std::string_view k) {
  if (k.size() >= 2 && k.substr(0, 2) == "ST") k.remove_prefix(2);
  if (!k.empty() && k[0] == 'C') k.remove_prefix(1);
  if (!k.empty() && k[0] == 'N') k.remove_prefix(1);
  return k == "OFF";
}

}  // namespace

TriangleMesh parseOff(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  TriangleMesh mesh;
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  std::string_view line;

  // The next line with tokens; false at the end of the file.
  auto nextTokens = [&]() {
    while (lines.next(line)) {
      splitTokens(line, tokens, /*hashComments=*/true);
      if (!tokens.empty()) return true;
    }
    return false;
  };
  auto endOfFile = [&](const std::string& what) {
    failAtLine(name, lines.lineNumber() + 1,
               "unexpected end of file: " + what + " (truncated, or the counts are wrong)");
  };

  if (!nextTokens()) endOfFile("expected the 'OFF' header");
  if (!isOffKeyword(tokens[0])) {
    if (tokens[0].find("OFF") != std::string_view::npos) {
      failAtLine(name, lines.lineNumber(), "unsupported OFF variant " + quoted(tokens[0]));
    }
    failAtLine(name, lines.lineNumber(),
               "not an OFF file (expected 'OFF', found " + quoted(tokens[0]) + ")");
  }
  std::vector<std::string_view> counts(tokens.begin() + 1, tokens.end());
  if (!counts.empty() && counts[0] == "BINARY") {
    failAtLine(name, lines.lineNumber(), "binary OFF is not supported");
  }
  if (counts.empty()) {
    if (!nextTokens()) endOfFile("expected the counts line 'vertices faces edges'");
    counts = tokens;
  }
  const size_t countsLine = lines.lineNumber();
  long long nv = 0, nf = 0, ne = 0;
  if (counts.size() < 2 || counts.size() > 3 || !parseInteger(counts[0], nv) ||
      !parseInteger(counts[1], nf) || (counts.size() == 3 && !parseInteger(counts[2], ne)) ||
      nv < 0 || nf < 0 || ne < 0) {
    failAtLine(name, countsLine, "expected counts 'vertices faces edges' (non-negative integers)");
  }
  if (nv >= static_cast<long long>(std::numeric_limits<uint32_t>::max())) {
    failAtLine(name, countsLine, "too many vertices");
  }
  // Every vertex and face needs a line of at least 6 bytes (a rough guard before reserving).
  if (static_cast<unsigned long long>(nv) > bytes.size() ||
      static_cast<unsigned long long>(nf) > bytes.size()) {
    failAtLine(name, countsLine,
               "counts " + std::to_string(nv) + " vertices, " + std::to_string(nf) +
                   " faces cannot fit in a file of " + std::to_string(bytes.size()) + " bytes");
  }

  mesh.positions.reserve(static_cast<size_t>(nv));
  for (long long i = 0; i < nv; ++i) {
    if (!nextTokens()) {
      endOfFile("expected " + std::to_string(nv) + " vertices, found " + std::to_string(i));
    }
    const size_t lineNo = lines.lineNumber();
    if (tokens.size() < 3) {
      failAtLine(name, lineNo,
                 "vertex needs 3 coordinates, found " + std::to_string(tokens.size()));
    }
    glm::dvec3 p;
    for (int k = 0; k < 3; ++k) p[k] = parseCoordinate(name, lineNo, tokens[k]);
    for (size_t k = 3; k < tokens.size(); ++k) {
      double ignored;
      if (!parseNumber(tokens[k], ignored))
        failAtLine(name, lineNo, "not a number: " + quoted(tokens[k]));
    }
    mesh.positions.push_back(p);
  }

  std::vector<uint32_t> polygon;
  for (long long i = 0; i < nf; ++i) {
    if (!nextTokens()) {
      endOfFile("expected " + std::to_string(nf) + " faces, found " + std::to_string(i));
    }
    const size_t lineNo = lines.lineNumber();
    long long n = 0;
    if (!parseInteger(tokens[0], n)) {
      failAtLine(name, lineNo,
                 "expected a face's vertex count, found " + quoted(tokens[0]) +
                     " (are the counts right?)");
    }
    if (n < 3) {
      failAtLine(name, lineNo, "face has " + std::to_string(n) + " vertices, needs at least 3");
    }
    if (static_cast<size_t>(n) > tokens.size() - 1) {
      failAtLine(name, lineNo,
                 "face of " + std::to_string(n) + " vertices lists only " +
                     std::to_string(tokens.size() - 1) + " indices");
    }
    polygon.clear();
    for (long long k = 0; k < n; ++k) {
      long long index = 0;
      const std::string_view token = tokens[1 + k];
      if (!parseInteger(token, index))
        failAtLine(name, lineNo, "bad vertex index " + quoted(token));
      if (index < 0 || index >= nv) {
        failAtLine(name, lineNo,
                   "vertex index " + std::to_string(index) + " is out of range: the file has " +
                       std::to_string(nv) + " vertices");
      }
      polygon.push_back(static_cast<uint32_t>(index));
    }
    for (size_t k = 1 + static_cast<size_t>(n); k < tokens.size(); ++k) {  // colour
      double ignored;
      if (!parseNumber(tokens[k], ignored))
        failAtLine(name, lineNo, "not a number: " + quoted(tokens[k]));
    }
    for (size_t k = 1; k + 1 < polygon.size(); ++k) {
      mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
    }
  }
  if (nextTokens()) {
    failAtLine(name, lines.lineNumber(),
               "data after the last face: the counts say " + std::to_string(nv) + " vertices and " +
                   std::to_string(nf) + " faces");
  }
  report->fileVertices = static_cast<size_t>(nv);
  report->fileFaces = static_cast<size_t>(nf);
  return mesh;
}

}  // namespace meshio
}  // namespace strata
