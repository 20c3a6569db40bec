// Reading closed triangle meshes from OBJ, STL (ascii and binary), PLY (ascii and binary), OFF
// and 3MF (the geometry its build places; see read_3mf.cpp). The format is picked by the
// file's extension through the table in mesh_formats.h.
//
// Every reader is strict: malformed numbers, NaN/Inf coordinates, out-of-range or negative
// indices (OBJ's relative negative indices are resolved, then range-checked), truncated files,
// headers whose counts disagree with the data, and empty meshes throw strata::Error with a
// message of the form "<path>: line <n>: <what>" (text formats) or "<path>: byte <n>: <what>"
// (binary formats). Polygons with more than three vertices are fan-triangulated.
//
// After parsing, the mesh is prepared for sampling (see prepareMesh in mesh_check.h):
// vertices with identical coordinates are welded, degenerate triangles removed (counted),
// orientation made consistent and outward (an inverted mesh is flipped with a warning), and an
// open or non-manifold mesh is rejected unless MeshReadOptions::allowOpen is set.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/geometry/mesh.h"
#include "engine/util/error.h"
#include "engine/util/progress.h"

namespace strata {

struct MeshReadOptions {
  bool allowOpen = false;  // accept open / non-manifold meshes (sampling may then leak)
  double unitScale = 1.0;  // multiply every coordinate (e.g. 25.4 for inch files into mm)
  // Checked between reading the file, parsing it and preparing the mesh (throws Cancelled):
  // a dialog's read of a large file given up with the dialog. Not owned; may be null.
  const Progress* progress = nullptr;
};

// A mesh that is not a closed oriented surface, refused (MeshReadOptions::allowOpen unset): it
// may be taken anyway as an open mesh (the scene's "open" mark, --allow-open).
class OpenMeshRefused : public Error {
 public:
  explicit OpenMeshRefused(const std::string& message) : Error(message) {}
};

struct MeshReadReport {
  std::vector<std::string> warnings;  // each names the file and what was repaired or suspicious
  size_t fileVertices = 0;            // as read, before welding
  size_t fileFaces = 0;               // polygons as read, before triangulation
  // Where the mesh is not a closed oriented surface and was accepted (MeshReadOptions::
  // allowOpen): what is wrong with it ("3 open (boundary) edges"); empty for a closed mesh.
  std::string openProblem;
};

// The most triangles a mesh file may hold (through 3MF components: place), checked before the
// mesh is prepared, and for binary STL and 3MF before anything is allocated; process-wide, set
// by the command line's --max-triangles; lifted on a thread where an InputLimitLifted lives
// (engine/util/atomic_file.h: reading back a file Strata wrote). Any thread.
constexpr uint64_t kDefaultMaxInputTriangles = 100'000'000;
uint64_t maxInputTriangles();
void setMaxInputTriangles(uint64_t triangles);
// The error for `count` triangles over the limit: names the file, both numbers and the option.
std::string tooManyTrianglesMessage(const std::string& name, uint64_t count);

// Reads by extension (case-insensitive; the readable formats of mesh_formats.h). Throws
// strata::Error, for an unknown extension "<path>: unknown mesh format '.ext' (expected .stl,
// ... or .3mf)".
TriangleMesh readMeshFile(const std::string& path, const MeshReadOptions& options = {},
                          MeshReadReport* report = nullptr);

// The same from bytes already in memory; `name` is used in messages and picks the format by
// its extension. Used by the fuzz targets and tests.
TriangleMesh readMeshBytes(const std::string& name, const std::string& bytes,
                           const MeshReadOptions& options = {}, MeshReadReport* report = nullptr);

// Reads by extension exactly as the file describes the mesh: NO repairs (no welding beyond the
// weld of identical positions that STL's unindexed format needs, no reorientation, no removal
// of degenerate triangles, no unit scale, no closedness check). For verifying what a writer
// wrote (engine/io/mesh_writers.h) with checkMesh. Throws strata::Error for a file that cannot
// be read or parsed, or that holds no triangles.
TriangleMesh readMeshFileRaw(const std::string& path, MeshReadReport* report = nullptr);

// The same without even STL's weld: the triangles as the file lists them, each STL facet with
// three vertices of its own. For comparing a written file with the mesh meant (check_written.h)
// without the cost of welding. With `progress`, checks for cancellation between reading the file
// and parsing it (throws Cancelled).
TriangleMesh readMeshFileVerbatim(const std::string& path, MeshReadReport* report = nullptr,
                                  const Progress* progress = nullptr);

// One block of a file's triangles as readMeshFileVerbatim would list them: triangles
// [first, first + count) of the file, corner v of triangle first + i at corners[3 * i + v].
// Called from several threads at once, blocks in any order; `corners` lives for the call.
using TriangleBlockVisitor =
    std::function<void(uint64_t first, const glm::dvec3* corners, size_t count)>;

// The file's triangles in blocks, read in pieces and never held whole (a few MB at a time),
// where its format lists them as fixed-size records (binary STL): the verbatim read at the
// speed of memory and in constant memory. False, with nothing visited, for any other file
// (another format, an ASCII STL, a binary STL whose facet count does not match its size):
// read it with readMeshFileVerbatim, which also names what is wrong with it. Throws
// strata::Error as the reader would for a non-finite coordinate (naming its byte), or when the
// file cannot be read or changes while read; Cancelled from `progress` between pieces.
bool visitFileTriangles(const std::string& path, const TriangleBlockVisitor& visit,
                        const Progress* progress = nullptr);

}  // namespace strata
