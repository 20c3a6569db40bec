// STL, binary and ASCII. Binary: an 80-byte header, a little-endian uint32 facet count, then
// 50 bytes per facet (normal, three vertices as float32, a 16-bit attribute); the count must
// account for the file size exactly. ASCII: solid / facet normal / outer loop / vertex x3 /
// endloop / endfacet / endsolid, keywords case-insensitive, several solids allowed.
// A file is binary when its count matches its size, or when it does not start with "solid"
// followed by text. Facet normals are ignored (winding decides orientation). Every facet has
// three vertices of its own; the readers of mesh_io.h weld identical positions (the format's
// `unindexed` flag).
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_readers.h"
#include "engine/io/reader_checks.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace meshio {
namespace {

constexpr size_t kHeaderBytes = 80;
constexpr size_t kFacetBytes = 50;

uint32_t readU32(const char* bytes) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes);
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

uint32_t readU32(const std::string& bytes, size_t at) {
  return readU32(bytes.data() + at);
}

float readF32(const char* bytes) {
  const uint32_t bits = readU32(bytes);
  float value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

// The three corners of the 50-byte facet record at `facet`; false if a coordinate is not
// finite (the caller names the first such byte: requireFiniteFacet).
bool decodeFacet(const char* facet, glm::dvec3* corners) {
  bool finite = true;
  for (int v = 0; v < 3; ++v)
    for (int k = 0; k < 3; ++k) {
      corners[v][k] = readF32(facet + 12 + 12 * v + 4 * k);
      finite = finite && std::isfinite(corners[v][k]);
    }
  return finite;
}

// Throws the reader's error for the first non-finite coordinate of the facet at byte `at` of
// the file (`facet` its record).
void requireFiniteFacet(const std::string& name, const char* facet, size_t at) {
  for (size_t k = 12; k < 48; k += 4) requireFiniteAtByte(name, at + k, readF32(facet + k));
}

// Lowers `*first` to `candidate` (several threads).
void keepFirst(std::atomic<uint64_t>* first, uint64_t candidate) {
  uint64_t seen = first->load();
  while (candidate < seen && !first->compare_exchange_weak(seen, candidate)) {
  }
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
  if (count > maxInputTriangles()) throw Error(tooManyTrianglesMessage(name, count));
  // Facets are fixed-size: decoded in parallel; the first non-finite coordinate (in file order)
  // is then reported exactly as a sequential read would.
  TriangleMesh mesh;
  mesh.positions.resize(count * 3);
  mesh.triangles.resize(count);
  std::atomic<uint64_t> firstBad{count};
  parallelFor(0, int64_t(count), 65536, [&](int64_t first, int64_t last) {
    for (int64_t f = first; f < last; ++f) {
      const char* facet = bytes.data() + kHeaderBytes + 4 + kFacetBytes * size_t(f);
      if (!decodeFacet(facet, &mesh.positions[3 * size_t(f)])) keepFirst(&firstBad, uint64_t(f));
      const uint32_t base = static_cast<uint32_t>(3 * f);
      mesh.triangles[size_t(f)] = {base, base + 1, base + 2};
    }
  });
  if (firstBad.load() < count) {
    const size_t at = kHeaderBytes + 4 + kFacetBytes * size_t(firstBad.load());
    requireFiniteFacet(name, bytes.data() + at, at);
  }
  report->fileFaces = count;
  return mesh;
}

// solid / facet normal / outer loop / vertex x3 / endloop / endfacet / endsolid, as a state
// machine over the file's lines: one method per expected keyword.
class AsciiStlParser {
 public:
  AsciiStlParser(const std::string& name, MeshReadReport* report) : name_(name), report_(report) {}

  TriangleMesh parse(const std::string& bytes) {
    LineReader lines(bytes);
    std::string_view line;
    size_t lastLine = 0;
    while (lines.next(line)) {
      lastLine = lines.lineNumber();
      splitTokens(line, tokens_, /*hashComments=*/false);
      if (!tokens_.empty()) readLine(lastLine);
    }
    if (expect_ != Expect::AfterSolid) {
      failAtLine(name_, lastLine + 1,
                 std::string("unexpected end of file (truncated?): expected ") + expected());
    }
    return std::move(mesh_);
  }

 private:
  enum class Expect { Solid, FacetOrEnd, OuterLoop, Vertex, EndFacet, AfterSolid };

  const char* expected() const {
    switch (expect_) {
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
  }

  [[noreturn]] void unexpected(size_t lineNo) const {
    failAtLine(name_, lineNo,
               std::string("expected ") + expected() + ", found " + quoted(tokens_[0]));
  }

  bool keywordIs(const char* keyword) const { return equalsIgnoreCase(tokens_[0], keyword); }

  void readLine(size_t lineNo) {
    switch (expect_) {
      case Expect::Solid:
      case Expect::AfterSolid:
        if (!keywordIs("solid")) unexpected(lineNo);
        expect_ = Expect::FacetOrEnd;
        break;
      case Expect::FacetOrEnd:
        if (keywordIs("endsolid")) {
          expect_ = Expect::AfterSolid;
        } else if (keywordIs("facet")) {
          expect_ = Expect::OuterLoop;  // the normal is ignored: winding decides orientation
        } else {
          unexpected(lineNo);
        }
        break;
      case Expect::OuterLoop:
        if (!(tokens_.size() == 2 && keywordIs("outer") && equalsIgnoreCase(tokens_[1], "loop"))) {
          unexpected(lineNo);
        }
        loop_.clear();
        expect_ = Expect::Vertex;
        break;
      case Expect::Vertex:
        readVertexOrEndLoop(lineNo);
        break;
      case Expect::EndFacet:
        if (!keywordIs("endfacet")) unexpected(lineNo);
        expect_ = Expect::FacetOrEnd;
        break;
    }
  }

  void readVertexOrEndLoop(size_t lineNo) {
    if (keywordIs("vertex")) {
      if (tokens_.size() != 4) {
        failAtLine(name_, lineNo,
                   "vertex needs 3 coordinates, found " + std::to_string(tokens_.size() - 1));
      }
      glm::dvec3 p;
      for (int k = 0; k < 3; ++k) p[k] = parseCoordinate(name_, lineNo, tokens_[1 + k]);
      loop_.push_back(p);
    } else if (keywordIs("endloop")) {
      addFacet(lineNo);
      expect_ = Expect::EndFacet;
    } else {
      unexpected(lineNo);
    }
  }

  // The loop's vertices as a facet, fan-triangulated from its first vertex.
  void addFacet(size_t lineNo) {
    if (loop_.size() < 3) {
      failAtLine(name_, lineNo, "facet has " + std::to_string(loop_.size()) + " vertices, needs 3");
    }
    const uint32_t base = static_cast<uint32_t>(mesh_.positions.size());
    mesh_.positions.insert(mesh_.positions.end(), loop_.begin(), loop_.end());
    for (uint32_t k = 1; k + 1 < loop_.size(); ++k) {
      mesh_.triangles.push_back({base, base + k, base + k + 1});
    }
    ++report_->fileFaces;
  }

  const std::string& name_;
  MeshReadReport* report_;
  Expect expect_ = Expect::Solid;
  TriangleMesh mesh_;
  std::vector<std::string_view> tokens_;  // of the current line
  std::vector<glm::dvec3> loop_;          // of the current facet
};

}  // namespace

bool visitStlBlocks(const std::string& path, const TriangleBlockVisitor& visit,
                    const Progress* progress) {
  InputFile file(path);
  if (file.size() < kHeaderBytes + 4) return false;
  char head[kHeaderBytes + 4];
  file.readExactly(head, sizeof(head));
  const uint64_t count = readU32(head + kHeaderBytes);
  // What parseStl calls binary when the count matches the size; anything else it decides on
  // the whole file (ASCII, or an error naming the mismatch).
  if (kHeaderBytes + 4 + kFacetBytes * count != file.size()) return false;
  constexpr uint64_t kPieceFacets = uint64_t(1) << 18;  // 13 MB a read
  constexpr int64_t kBlockFacets = 4096;                // a visit
  std::string piece(size_t(std::min(count, kPieceFacets) * kFacetBytes), '\0');
  for (uint64_t done = 0; done < count;) {
    if (progress) progress->check();
    const uint64_t n = std::min(kPieceFacets, count - done);
    file.readExactly(piece.data(), size_t(n * kFacetBytes));
    std::atomic<uint64_t> firstBad{n};
    parallelFor(0, int64_t(n), kBlockFacets, [&](int64_t first, int64_t last) {
      std::vector<glm::dvec3> corners(size_t(3 * kBlockFacets));
      for (int64_t b = first; b < last; b += kBlockFacets) {
        const int64_t e = std::min(last, b + kBlockFacets);
        glm::dvec3* out = corners.data();
        for (int64_t f = b; f < e; ++f)
          if (!decodeFacet(piece.data() + kFacetBytes * size_t(f), &out[3 * size_t(f - b)]))
            keepFirst(&firstBad, uint64_t(f));
        visit(done + uint64_t(b), corners.data(), size_t(e - b));
      }
    });
    if (firstBad.load() < n) {
      const size_t at = size_t(kHeaderBytes + 4 + kFacetBytes * (done + firstBad.load()));
      requireFiniteFacet(path, piece.data() + kFacetBytes * size_t(firstBad.load()), at);
    }
    done += n;
  }
  return true;
}

TriangleMesh parseStl(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  // An ASCII STL after a UTF-8 byte order mark (Windows editors write one); a binary STL whose
  // header happens to start with those bytes keeps them (its count matches its size).
  if (hasUtf8Bom(bytes)) {
    const bool sizeMatches =
        bytes.size() >= kHeaderBytes + 4 &&
        kHeaderBytes + 4 + kFacetBytes * uint64_t(readU32(bytes, kHeaderBytes)) == bytes.size();
    const std::string text = bytes.substr(3);
    if (!sizeMatches && startsWithSolid(text) && looksLikeText(text))
      return parseStl(name, text, report);
  }
  bool binary = true;
  if (bytes.size() >= kHeaderBytes + 4) {
    const uint64_t count = readU32(bytes, kHeaderBytes);
    const bool sizeMatches = kHeaderBytes + 4 + kFacetBytes * count == bytes.size();
    binary = sizeMatches || !(startsWithSolid(bytes) && looksLikeText(bytes));
  } else {
    binary = !startsWithSolid(bytes);
  }
  TriangleMesh mesh;
  if (binary) {
    mesh = parseBinary(name, bytes, report);
  } else {
    const std::optional<std::string> lf = lfCopyIfCrOnlyLineEnds(bytes);
    mesh = AsciiStlParser(name, report).parse(lf ? *lf : bytes);
  }
  report->fileVertices = mesh.positions.size();
  requireMeasurableExtent(name, mesh);
  return mesh;
}

}  // namespace meshio
}  // namespace strata
