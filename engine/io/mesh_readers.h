// Private to engine/io: the format parsers behind readMeshBytes, each named by its entry in the
// table of mesh_formats.h, and the strict text scanning they share. Each parser turns a whole
// file held in memory into an indexed triangle mesh exactly as the file describes it (no
// welding across vertices, no repairs), and throws strata::Error "<name>: line <n>: <what>" or
// "<name>: byte <n>: <what>" for anything malformed.
// Parsers fill report->fileVertices / fileFaces and may append warnings; report is never null.
// Synchronous, no shared state: any thread may call them.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "engine/geometry/mesh.h"
#include "engine/io/mesh_io.h"

namespace strata {
namespace meshio {

TriangleMesh parseObj(const std::string& name, const std::string& bytes, MeshReadReport* report);
// STL positions are unindexed in the file: each facet gets three vertices of its own.
TriangleMesh parseStl(const std::string& name, const std::string& bytes, MeshReadReport* report);
// A binary STL's facets in blocks, read in pieces (the format's MeshBlockReader): false for an
// ASCII STL or a count that does not match the size (parseStl then reads or refuses it).
bool visitStlBlocks(const std::string& path, const TriangleBlockVisitor& visit,
                    const Progress* progress);
TriangleMesh parsePly(const std::string& name, const std::string& bytes, MeshReadReport* report);
// A binary PLY's triangles in blocks (the format's MeshBlockReader): the faces read in pieces,
// the vertices they use read on demand a page at a time (few at once for a file whose faces
// use nearby vertices, as the streamed export writes them). False, with nothing visited, for
// an ascii PLY or one with elements or face properties besides the vertices and their index
// lists, or whose vertices do not fit the file (parsePly then reads or refuses it); errors
// name the byte as parsePly does.
bool visitPlyBlocks(const std::string& path, const TriangleBlockVisitor& visit,
                    const Progress* progress);
TriangleMesh parseOff(const std::string& name, const std::string& bytes, MeshReadReport* report);
// 3MF: a zip package; the geometry its build places, in the model's unit (read_3mf.cpp).
TriangleMesh parse3mf(const std::string& name, const std::string& bytes, MeshReadReport* report);

// ---- Shared helpers (defined in mesh_io.cpp) ----

[[noreturn]] void failAtLine(const std::string& name, size_t line, const std::string& what);
[[noreturn]] void failAtByte(const std::string& name, size_t byte, const std::string& what);
void addWarning(MeshReadReport* report, const std::string& name, const std::string& what);

// A token quoted for a message, shortened to a readable length: 'abc'.
std::string quoted(std::string_view token);
// Whether `bytes` start with a UTF-8 byte order mark (EF BB BF), which the text formats skip.
inline bool hasUtf8Bom(std::string_view bytes) {
  return bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xEF &&
         static_cast<unsigned char>(bytes[1]) == 0xBB &&
         static_cast<unsigned char>(bytes[2]) == 0xBF;
}

// Walks text line by line ('\n' or "\r\n"); numbers are 1-based. `startByte` lets a reader
// continue after a header it parsed itself, numbering from `startLine`.
class LineReader {
 public:
  explicit LineReader(std::string_view text, size_t startByte = 0, size_t startLine = 0)
      : text_(text), pos_(startByte), line_(startLine) {}
  // The next line without its terminator; false at end of text.
  bool next(std::string_view& line);
  size_t lineNumber() const { return line_; }  // of the line last returned
  size_t byteOffset() const { return pos_; }   // just past the line last returned

 private:
  std::string_view text_;
  size_t pos_;
  size_t line_;
};

// Splits on spaces and tabs (and other ASCII whitespace). When `hashComments` is set, '#' and
// everything after it is dropped first.
void splitTokens(std::string_view line, std::vector<std::string_view>& tokens, bool hashComments);

// Whole-token parses: no trailing characters, a leading '+' allowed. parseNumber accepts
// nan/inf spellings (so callers can report them precisely); false for anything unparsable.
bool parseNumber(std::string_view token, double& value);
bool parseInteger(std::string_view token, long long& value);

// A coordinate at a text line: throws "line n: ..." when unparsable or not finite.
double parseCoordinate(const std::string& name, size_t line, std::string_view token);
// Throws "byte n: ..." when a binary coordinate is NaN or infinite.
void requireFiniteAtByte(const std::string& name, size_t byte, double value);

bool equalsIgnoreCase(std::string_view a, std::string_view b);

}  // namespace meshio
}  // namespace strata
