// Wavefront OBJ, geometry only: `v x y z [w] [r g b ...]` and `f` with i, i/t, i//n or i/t/n
// references (1-based; negative ones count back from the last vertex read so far). Texture
// coordinates, normals, groups, materials and smoothing are ignored; `l` and `p` elements are
// ignored with one warning; any other statement is ignored and counted in a warning.
// Polygons are fan-triangulated from their first corner.
#include <cstdint>
#include <limits>

#include "engine/io/mesh_readers.h"
#include "engine/io/reader_checks.h"

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

// One pass over the file's lines, one method per statement kind.
class ObjParser {
 public:
  ObjParser(const std::string& name, MeshReadReport* report) : name_(name), report_(report) {}

  TriangleMesh parse(const std::string& bytes) {
    LineReader lines(bytes);
    std::string_view line;
    while (lines.next(line)) {
      splitTokens(line, tokens_, /*hashComments=*/true);
      if (!tokens_.empty()) readStatement(lines.lineNumber());
    }
    checkForwardIndices();
    report_->fileVertices = mesh_.positions.size();
    warnAboutIgnoredStatements();
    return std::move(mesh_);
  }

 private:
  void readStatement(size_t lineNo) {
    const std::string_view keyword = tokens_[0];
    if (keyword == "v") {
      readVertex(lineNo);
    } else if (keyword == "f" || keyword == "fo") {
      readFace(lineNo);
    } else if (keyword == "l" || keyword == "p") {
      ++linesAndPoints_;
    } else if (!isIgnoredStatement(keyword) && unknownCount_++ == 0) {
      firstUnknown_ = quoted(keyword);
      firstUnknownLine_ = lineNo;
    }
  }

  // v x y z [w] [r g b ...]
  void readVertex(size_t lineNo) {
    if (tokens_.size() < 4) {
      failAtLine(name_, lineNo,
                 "vertex needs 3 coordinates, found " + std::to_string(tokens_.size() - 1));
    }
    glm::dvec3 p;
    for (int k = 0; k < 3; ++k) p[k] = parseCoordinate(name_, lineNo, tokens_[1 + k]);
    for (size_t k = 4; k < tokens_.size(); ++k) {  // w or colour components: numbers only
      double ignored;
      if (!parseNumber(tokens_[k], ignored)) {
        failAtLine(name_, lineNo, "not a number: " + quoted(tokens_[k]));
      }
    }
    if (mesh_.positions.size() >= std::numeric_limits<uint32_t>::max()) {
      failAtLine(name_, lineNo, "too many vertices");
    }
    mesh_.positions.push_back(p);
  }

  // f ref ref ref ...: fan-triangulated from the first corner.
  void readFace(size_t lineNo) {
    if (tokens_.size() < 4) {
      failAtLine(name_, lineNo,
                 "face needs at least 3 vertices, found " + std::to_string(tokens_.size() - 1));
    }
    polygon_.clear();
    for (size_t k = 1; k < tokens_.size(); ++k) {
      polygon_.push_back(resolveIndex(parseReference(tokens_[k], lineNo), lineNo));
    }
    ++report_->fileFaces;
    for (size_t k = 1; k + 1 < polygon_.size(); ++k) {
      mesh_.triangles.push_back({polygon_[0], polygon_[k], polygon_[k + 1]});
    }
  }

  // The vertex index of a reference i, i/t, i//n or i/t/n, as written (t and n must be empty or
  // integers, and are ignored).
  long long parseReference(std::string_view ref, size_t lineNo) const {
    const size_t slash1 = ref.find('/');
    long long index = 0;
    if (!parseInteger(ref.substr(0, slash1), index)) {
      failAtLine(name_, lineNo, "bad vertex reference " + quoted(ref));
    }
    if (slash1 == std::string_view::npos) return index;
    const std::string_view rest = ref.substr(slash1 + 1);
    const size_t slash2 = rest.find('/');
    const std::string_view texPart = rest.substr(0, slash2);
    const std::string_view normalPart =
        slash2 == std::string_view::npos ? std::string_view() : rest.substr(slash2 + 1);
    long long ignored;
    const bool texOk = texPart.empty() || parseInteger(texPart, ignored);
    const bool normalOk = slash2 == std::string_view::npos ||
                          (!normalPart.empty() && parseInteger(normalPart, ignored));
    if (!texOk || !normalOk || (slash2 == std::string_view::npos && texPart.empty())) {
      failAtLine(name_, lineNo, "bad vertex reference " + quoted(ref));
    }
    return index;
  }

  // The 0-based vertex of a 1-based (or negative, relative) index. Positive indices past the
  // vertices read so far are remembered for checkForwardIndices.
  uint32_t resolveIndex(long long index, size_t lineNo) {
    if (index == 0) {
      failAtLine(name_, lineNo, "vertex index 0 is invalid (OBJ indices start at 1)");
    }
    const long long available = static_cast<long long>(mesh_.positions.size());
    long long resolved;
    if (index < 0) {
      resolved = available + index;
      if (resolved < 0) {
        failAtLine(name_, lineNo,
                   "negative vertex index " + std::to_string(index) + " is out of range: only " +
                       std::to_string(available) + " vertices precede it");
      }
    } else {
      resolved = index - 1;
      if (resolved >= available) pending_.push_back({index, lineNo});
      if (resolved >= static_cast<long long>(std::numeric_limits<uint32_t>::max())) {
        failAtLine(name_, lineNo, "vertex index " + std::to_string(index) + " is out of range");
      }
    }
    return static_cast<uint32_t>(resolved);
  }

  void checkForwardIndices() const {
    const long long total = static_cast<long long>(mesh_.positions.size());
    for (const PendingIndex& p : pending_) {
      if (p.index > total) {
        failAtLine(name_, p.line,
                   "vertex index " + std::to_string(p.index) + " is out of range: the file has " +
                       std::to_string(total) + " vertices");
      }
    }
  }

  void warnAboutIgnoredStatements() {
    if (linesAndPoints_ > 0) {
      addWarning(report_, name_,
                 "ignored " + std::to_string(linesAndPoints_) +
                     " line/point elements ('l', 'p'): only faces make a solid");
    }
    if (unknownCount_ > 0) {
      addWarning(report_, name_,
                 "ignored " + std::to_string(unknownCount_) + " unknown statement(s), the first " +
                     firstUnknown_ + " at line " + std::to_string(firstUnknownLine_));
    }
  }

  const std::string& name_;
  MeshReadReport* report_;
  TriangleMesh mesh_;
  std::vector<std::string_view> tokens_;  // of the current line
  std::vector<uint32_t> polygon_;         // of the current face, resolved
  std::vector<PendingIndex> pending_;
  size_t linesAndPoints_ = 0;
  size_t unknownCount_ = 0;
  std::string firstUnknown_;
  size_t firstUnknownLine_ = 0;
};

}  // namespace

TriangleMesh parseObj(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  // A UTF-8 byte order mark before the first line (Windows editors write one): skipped.
  if (hasUtf8Bom(bytes)) return parseObj(name, bytes.substr(3), report);
  const std::optional<std::string> lf = lfCopyIfCrOnlyLineEnds(bytes);
  TriangleMesh mesh = ObjParser(name, report).parse(lf ? *lf : bytes);
  requireMeasurableExtent(name, mesh);
  return mesh;
}

}  // namespace meshio
}  // namespace strata
