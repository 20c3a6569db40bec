// Object File Format, ascii: a header keyword `OFF` (also `COFF`, `NOFF`, `CNOFF`, `STOFF`...,
// whose extra per-vertex values are read past), the counts `nv nf [ne]` (on the header line or
// the next), nv vertex lines `x y z [extras]`, nf face lines `n i0 ... i(n-1) [colour]`.
// '#' starts a comment. One vertex or face per line; the counts must match the lines exactly.
// Binary OFF and 4OFF / nOFF (other dimensions) are rejected.
#include <cstdint>
#include <limits>

#include "engine/io/mesh_readers.h"
#include "engine/io/reader_checks.h"

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

// The header, then exactly the vertex and face lines its counts announce.
class OffParser {
 public:
  OffParser(const std::string& name, const std::string& bytes, MeshReadReport* report)
      : name_(name), bytes_(bytes), report_(report), lines_(bytes) {}

  TriangleMesh parse() {
    readHeader();
    readVertices();
    readFaces();
    if (nextTokens()) {
      failAtLine(name_, lines_.lineNumber(),
                 "data after the last face: the counts say " + std::to_string(nv_) +
                     " vertices and " + std::to_string(nf_) + " faces");
    }
    report_->fileVertices = static_cast<size_t>(nv_);
    report_->fileFaces = static_cast<size_t>(nf_);
    return std::move(mesh_);
  }

 private:
  // The next line with tokens into tokens_; false at the end of the file.
  bool nextTokens() {
    std::string_view line;
    while (lines_.next(line)) {
      splitTokens(line, tokens_, /*hashComments=*/true);
      if (!tokens_.empty()) return true;
    }
    return false;
  }

  [[noreturn]] void failAtEnd(const std::string& what) const {
    failAtLine(name_, lines_.lineNumber() + 1,
               "unexpected end of file: " + what + " (truncated, or the counts are wrong)");
  }

  // The keyword line, and the counts on it or on the next line.
  void readHeader() {
    if (!nextTokens()) failAtEnd("expected the 'OFF' header");
    if (!isOffKeyword(tokens_[0])) {
      if (tokens_[0].find("OFF") != std::string_view::npos) {
        failAtLine(name_, lines_.lineNumber(), "unsupported OFF variant " + quoted(tokens_[0]));
      }
      failAtLine(name_, lines_.lineNumber(),
                 "not an OFF file (expected 'OFF', found " + quoted(tokens_[0]) + ")");
    }
    std::vector<std::string_view> counts(tokens_.begin() + 1, tokens_.end());
    if (!counts.empty() && counts[0] == "BINARY") {
      failAtLine(name_, lines_.lineNumber(), "binary OFF is not supported");
    }
    if (counts.empty()) {
      if (!nextTokens()) failAtEnd("expected the counts line 'vertices faces edges'");
      counts = tokens_;
    }
    readCounts(counts, lines_.lineNumber());
  }

  void readCounts(const std::vector<std::string_view>& counts, size_t countsLine) {
    long long ne = 0;
    if (counts.size() < 2 || counts.size() > 3 || !parseInteger(counts[0], nv_) ||
        !parseInteger(counts[1], nf_) || (counts.size() == 3 && !parseInteger(counts[2], ne)) ||
        nv_ < 0 || nf_ < 0 || ne < 0) {
      failAtLine(name_, countsLine,
                 "expected counts 'vertices faces edges' (non-negative integers)");
    }
    if (nv_ >= static_cast<long long>(std::numeric_limits<uint32_t>::max())) {
      failAtLine(name_, countsLine, "too many vertices");
    }
    // Every vertex and face needs a line of at least 6 bytes (a rough guard before reserving).
    if (static_cast<unsigned long long>(nv_) > bytes_.size() ||
        static_cast<unsigned long long>(nf_) > bytes_.size()) {
      failAtLine(name_, countsLine,
                 "counts " + std::to_string(nv_) + " vertices, " + std::to_string(nf_) +
                     " faces cannot fit in a file of " + std::to_string(bytes_.size()) + " bytes");
    }
  }

  // x y z [extras], one vertex per line.
  void readVertices() {
    mesh_.positions.reserve(static_cast<size_t>(nv_));
    for (long long i = 0; i < nv_; ++i) {
      if (!nextTokens()) {
        failAtEnd("expected " + std::to_string(nv_) + " vertices, found " + std::to_string(i));
      }
      const size_t lineNo = lines_.lineNumber();
      if (tokens_.size() < 3) {
        failAtLine(name_, lineNo,
                   "vertex needs 3 coordinates, found " + std::to_string(tokens_.size()));
      }
      glm::dvec3 p;
      for (int k = 0; k < 3; ++k) p[k] = parseCoordinate(name_, lineNo, tokens_[k]);
      requireNumbers(3, lineNo);
      mesh_.positions.push_back(p);
    }
  }

  // n i0 ... i(n-1) [colour], one face per line, fan-triangulated from its first corner.
  void readFaces() {
    for (long long i = 0; i < nf_; ++i) {
      if (!nextTokens()) {
        failAtEnd("expected " + std::to_string(nf_) + " faces, found " + std::to_string(i));
      }
      const size_t lineNo = lines_.lineNumber();
      const size_t n = readCornerCount(lineNo);
      polygon_.clear();
      for (size_t k = 0; k < n; ++k) polygon_.push_back(readIndex(tokens_[1 + k], lineNo));
      requireNumbers(1 + n, lineNo);  // the colour
      for (size_t k = 1; k + 1 < polygon_.size(); ++k) {
        mesh_.triangles.push_back({polygon_[0], polygon_[k], polygon_[k + 1]});
      }
    }
  }

  // A face line's leading vertex count, checked against the indices that follow it.
  size_t readCornerCount(size_t lineNo) const {
    long long n = 0;
    if (!parseInteger(tokens_[0], n)) {
      failAtLine(name_, lineNo,
                 "expected a face's vertex count, found " + quoted(tokens_[0]) +
                     " (are the counts right?)");
    }
    if (n < 3) {
      failAtLine(name_, lineNo, "face has " + std::to_string(n) + " vertices, needs at least 3");
    }
    if (static_cast<size_t>(n) > tokens_.size() - 1) {
      failAtLine(name_, lineNo,
                 "face of " + std::to_string(n) + " vertices lists only " +
                     std::to_string(tokens_.size() - 1) + " indices");
    }
    return static_cast<size_t>(n);
  }

  uint32_t readIndex(std::string_view token, size_t lineNo) const {
    long long index = 0;
    if (!parseInteger(token, index)) failAtLine(name_, lineNo, "bad vertex index " + quoted(token));
    if (index < 0 || index >= nv_) {
      failAtLine(name_, lineNo,
                 "vertex index " + std::to_string(index) + " is out of range: the file has " +
                     std::to_string(nv_) + " vertices");
    }
    return static_cast<uint32_t>(index);
  }

  // The tokens from `first` on are numbers (read past).
  void requireNumbers(size_t first, size_t lineNo) const {
    for (size_t k = first; k < tokens_.size(); ++k) {
      double ignored;
      if (!parseNumber(tokens_[k], ignored)) {
        failAtLine(name_, lineNo, "not a number: " + quoted(tokens_[k]));
      }
    }
  }

  const std::string& name_;
  const std::string& bytes_;
  MeshReadReport* report_;
  LineReader lines_;
  std::vector<std::string_view> tokens_;  // of the current line
  std::vector<uint32_t> polygon_;         // of the current face
  long long nv_ = 0, nf_ = 0;             // the header's counts
  TriangleMesh mesh_;
};

}  // namespace

TriangleMesh parseOff(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  // A UTF-8 byte order mark before the first line (Windows editors write one): skipped.
  if (hasUtf8Bom(bytes)) return parseOff(name, bytes.substr(3), report);
  const std::optional<std::string> lf = lfCopyIfCrOnlyLineEnds(bytes);
  TriangleMesh mesh = OffParser(name, lf ? *lf : bytes, report).parse();
  requireMeasurableExtent(name, mesh);
  return mesh;
}

}  // namespace meshio
}  // namespace strata
