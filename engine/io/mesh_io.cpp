// readMeshFile / readMeshBytes: pick a parser by extension (the table in mesh_formats.h), scale,
// prepare (weld, drop degenerate triangles, orient outward), report repairs as warnings, and
// refuse meshes that sampling cannot use. Also the strict text scanning shared by the parsers
// (mesh_readers.h).
#include "engine/io/mesh_io.h"

#include <algorithm>
#include <atomic>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_formats.h"
#include "engine/io/mesh_readers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {

namespace {
std::atomic<uint64_t> g_maxInputTriangles{kDefaultMaxInputTriangles};
}

uint64_t maxInputTriangles() {
  if (InputLimitLifted::active()) return ~uint64_t(0) >> 1;  // a file Strata wrote itself
  return g_maxInputTriangles.load();
}

void setMaxInputTriangles(uint64_t triangles) {
  g_maxInputTriangles.store(triangles);
}

std::string tooManyTrianglesMessage(const std::string& name, uint64_t count) {
  return name + ": " + std::to_string(count) + " triangles, more than the limit of " +
         std::to_string(maxInputTriangles()) +
         "; raise it with --max-triangles (e.g. --max-triangles " +
         std::to_string(std::max<uint64_t>(count, maxInputTriangles() * 2)) + ")";
}
namespace meshio {

void failAtLine(const std::string& name, size_t line, const std::string& what) {
  throw Error(name + ": line " + std::to_string(line) + ": " + what);
}

void failAtByte(const std::string& name, size_t byte, const std::string& what) {
  throw Error(name + ": byte " + std::to_string(byte) + ": " + what);
}

void addWarning(MeshReadReport* report, const std::string& name, const std::string& what) {
  report->warnings.push_back(name + ": " + what);
}

std::string quoted(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string text(token.substr(0, kMax));
  if (token.size() > kMax) text += "...";
  for (char& ch : text) {
    if (static_cast<unsigned char>(ch) < 32 || static_cast<unsigned char>(ch) > 126) ch = '?';
  }
  return "'" + text + "'";
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end == text_.size() ? end : end + 1;
  ++line_;
  return true;
}

namespace {
bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}
}  // namespace

void splitTokens(std::string_view line, std::vector<std::string_view>& tokens, bool hashComments) {
  tokens.clear();
  if (hashComments) {
    const size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
  }
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    const size_t begin = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > begin) tokens.push_back(line.substr(begin, i - begin));
  }
}

bool parseNumber(std::string_view token, double& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  auto result = std::from_chars(token.data(), end, value);
  if (result.ptr != end) return false;
  if (result.ec == std::errc::result_out_of_range) {
    // Overflow or underflow: strtod gives +-inf or the nearest tiny value, which the callers
    // then judge (an infinite coordinate is an error, an underflow is a number).
    const std::string copy(token);
    value = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return result.ec == std::errc();
}

bool parseInteger(std::string_view token, long long& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  auto result = std::from_chars(token.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

double parseCoordinate(const std::string& name, size_t line, std::string_view token) {
  double value = 0.0;
  if (!parseNumber(token, value)) failAtLine(name, line, "not a number: " + quoted(token));
  if (std::isnan(value)) failAtLine(name, line, "coordinate is NaN: " + quoted(token));
  if (std::isinf(value)) failAtLine(name, line, "coordinate is infinite (Inf): " + quoted(token));
  return value;
}

void requireFiniteAtByte(const std::string& name, size_t byte, double value) {
  if (std::isnan(value)) failAtByte(name, byte, "coordinate is NaN");
  if (std::isinf(value)) failAtByte(name, byte, "coordinate is infinite (Inf)");
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

}  // namespace meshio

namespace {

std::string plural(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

enum class Corners { Verbatim, WeldUnindexed };

// The parser the extension names (mesh_formats.h), exactly as the file describes the mesh (no
// repairs); with Corners::WeldUnindexed, the corners of an unindexed format (STL) are welded
// where their positions are identical, so that triangles share vertices as in the other formats.
TriangleMesh parseByExtension(const std::string& name, const std::string& bytes,
                              MeshReadReport* report, Corners corners) {
  const MeshFormat* format = meshFormatFor(name, MeshAccess::Read);
  if (!format) {
    const std::string ext = lowerExtension(name);
    throw Error(name + ": unknown mesh format '" + (ext.empty() ? "" : "." + ext) + "' (expected " +
                meshExtensionList(MeshAccess::Read) + ")");
  }
  TriangleMesh mesh = format->parse(name, bytes, report);
  if (mesh.triangles.empty()) throw Error(name + ": contains no triangles");
  if (format->unindexed && corners == Corners::WeldUnindexed) weldIdenticalPositions(mesh);
  return mesh;
}

}  // namespace

TriangleMesh readMeshFileRaw(const std::string& path, MeshReadReport* report) {
  MeshReadReport local;
  return parseByExtension(path, readWholeFile(path), report ? report : &local,
                          Corners::WeldUnindexed);
}

TriangleMesh readMeshFileVerbatim(const std::string& path, MeshReadReport* report,
                                  const Progress* progress) {
  MeshReadReport local;
  const std::string bytes = readWholeFile(path);
  if (progress) progress->check();
  return parseByExtension(path, bytes, report ? report : &local, Corners::Verbatim);
}

bool visitFileTriangles(const std::string& path, const TriangleBlockVisitor& visit,
                        const Progress* progress) {
  const MeshFormat* format = meshFormatFor(path, MeshAccess::Read);
  return format && format->blocks && format->blocks(path, visit, progress);
}

TriangleMesh readMeshFile(const std::string& path, const MeshReadOptions& options,
                          MeshReadReport* report) {
  const std::string bytes = readWholeFile(path);
  if (options.progress) options.progress->check();
  return readMeshBytes(path, bytes, options, report);
}

TriangleMesh readMeshBytes(const std::string& name, const std::string& bytes,
                           const MeshReadOptions& options, MeshReadReport* report) {
  MeshReadReport local;
  MeshReadReport* rep = report ? report : &local;

  if (!std::isfinite(options.unitScale) || options.unitScale <= 0.0) {
    throw Error(name + ": unit scale must be a positive finite number, got " +
                std::to_string(options.unitScale));
  }

  TriangleMesh mesh = parseByExtension(name, bytes, rep, Corners::WeldUnindexed);
  if (options.progress) options.progress->check();
  if (mesh.triangles.size() > maxInputTriangles())
    throw Error(tooManyTrianglesMessage(name, mesh.triangles.size()));

  if (options.unitScale != 1.0) {
    for (auto& p : mesh.positions) {
      p *= options.unitScale;
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw Error(name + ": coordinates overflow after scaling by " +
                    std::to_string(options.unitScale));
      }
    }
  }

  const size_t fileTriangles = mesh.triangles.size();
  PrepareReport prep;
  try {
    prep = prepareMesh(mesh);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
  if (mesh.triangles.empty()) {
    throw Error(name + ": contains no triangles (all " +
                plural(fileTriangles, "triangle was", "triangles were") + " degenerate)");
  }
  if (prep.weldedVertices > 0) {
    meshio::addWarning(
        rep, name,
        "welded " + plural(prep.weldedVertices, "duplicate vertex", "duplicate vertices"));
  }
  if (prep.removedDegenerate > 0) {
    meshio::addWarning(
        rep, name,
        "removed " + plural(prep.removedDegenerate, "degenerate triangle", "degenerate triangles") +
            " (repeated vertex or zero area)");
  }
  if (prep.removedUnreferenced > 0) {
    meshio::addWarning(rep, name,
                       "dropped " + plural(prep.removedUnreferenced, "vertex", "vertices") +
                           " that no triangle uses");
  }
  if (prep.reorientedTriangles > 0) {
    meshio::addWarning(rep, name,
                       "flipped " + plural(prep.reorientedTriangles, "triangle", "triangles") +
                           " to agree with their neighbours (inconsistent orientation)");
  }
  if (prep.shellsTurnedOutward > 0) {
    if (prep.shellsTurnedOutward == size_t(prep.check.components))
      meshio::addWarning(rep, name, "mesh was inside out (normals pointing in); flipped it");
    else
      meshio::addWarning(rep, name,
                         "flipped " + plural(prep.shellsTurnedOutward, "shell", "shells") + " of " +
                             std::to_string(prep.check.components) +
                             " that pointed inward (inside out)");
  }
  if (prep.cavitiesTurnedInward > 0) {
    meshio::addWarning(
        rep, name,
        plural(prep.cavitiesTurnedInward, "closed shell lies", "closed shells lie") +
            " inside another and pointed outward: taken as " +
            (prep.cavitiesTurnedInward == 1 ? "a cavity" : "cavities") +
            " (hollow, by the even-odd nesting rule) and turned inward; a part meant to fill "
            "the other belongs in a node of its own");
  }

  const MeshCheck& check = prep.check;
  if (!check.closed() || !check.manifold() || !check.oriented()) {
    std::string problem = "mesh is not a closed oriented surface:";
    const char* sep = " ";
    if (check.boundaryEdges > 0) {
      problem += sep + plural(check.boundaryEdges, "open (boundary) edge", "open (boundary) edges");
      sep = ", ";
    }
    if (check.nonManifoldEdges > 0) {
      problem += sep + plural(check.nonManifoldEdges, "non-manifold edge", "non-manifold edges");
      sep = ", ";
    }
    if (check.misorientedEdges > 0) {
      problem += sep + plural(check.misorientedEdges, "misoriented edge (non-orientable)",
                              "misoriented edges (non-orientable)");
    }
    if (!options.allowOpen) {
      throw OpenMeshRefused(
          name + ": " + problem +
          "; sampling it would leak. Repair the mesh (close its holes, e.g. in "
          "MeshLab), or take it anyway: \"import it anyway\" in the editor's import "
          "dialog, --allow-open on the command line (strata eval, boolean, export)");
    }
    meshio::addWarning(rep, name,
                       problem +
                           "; accepted as an open mesh (--allow-open, or marked open in "
                           "the scene): sampling may leak");
    if (rep) rep->openProblem = problem.substr(problem.find(':') + 2);
  }
  return mesh;
}

}  // namespace strata
