// The mesh file formats, once: a table with one entry per format (its label, extensions,
// parser, writer and the notes the usage text shows). Everything that names formats derives
// from it: readMeshFile / readMeshBytes / readMeshFileRaw (mesh_io.h) and writeMeshFile
// (mesh_writers.h) dispatch through it, and the command line's extension check and usage text
// (app/) and the editor's file dialog filters (ui/) list what it holds.
//
// Adding a format:
//   1. its parser (read_<format>.cpp, declared in mesh_readers.h) and/or its writer
//      (write_<format>.cpp, declared in mesh_writer_formats.h), private to engine/io;
//   2. one entry in the table in mesh_formats.cpp.
// Nothing else needs an edit: the command line, its usage text, the file dialogs and the tests
// of tests/engine/io/mesh_formats_test.cpp (a write-and-read round trip of every writable
// format) follow the table. Worth adding beside: the format's own strictness tests, a fuzz
// selector in tests/fuzz/fuzz_entries.h, and its line in the prose that describes formats (the
// README, the notes at the top of mesh_io.h and mesh_writers.h).
//
// Extensions are lower-case without the dot ("stl"); paths match them case-insensitively.
// Synchronous, no mutable state: any thread may call these.
#pragma once

#include <string>
#include <vector>

#include "engine/geometry/export_mesh.h"
#include "engine/geometry/mesh.h"
#include "engine/io/mesh_io.h"
#include "engine/util/progress.h"

namespace strata {

// Parses a whole file held in memory into a mesh exactly as the file describes it (see
// mesh_readers.h); `name` is used in messages. Throws strata::Error.
using MeshParser = TriangleMesh (*)(const std::string& name, const std::string& bytes,
                                    MeshReadReport* report);
// Writes a validated ExportMesh to `path` atomically (see mesh_writer_formats.h).
using MeshWriter = void (*)(const std::string& path, const ExportMesh& mesh, Progress* progress);

// A coordinate as the format stores it: what reading the written file back gives for `value`
// (float32 for STL, "%.9g" for the text formats, double for PLY).
using StoredCoordinate = double (*)(double value);

// Visits the triangles of the file at `path` in blocks without holding it (visitFileTriangles,
// mesh_io.h); false when the file is not in the form this reader streams.
using MeshBlockReader = bool (*)(const std::string& path, const TriangleBlockVisitor& visit,
                                 const Progress* progress);

// Reading a format (import, readMeshFile) or writing it (export, writeMeshFile).
enum class MeshAccess { Read, Write };

struct MeshFormat {
  const char* label = "";               // "STL": names the format's filter in file dialogs
  std::vector<std::string> extensions;  // lower-case, no dot; the first is the usual one
  MeshParser parse = nullptr;           // nullptr: not readable
  MeshWriter write = nullptr;           // nullptr: not writable
  const char* readNote = "";            // usage text, what is read: "ascii or binary" or ""
  const char* writeNote = "";           // usage text, what is written: "binary" or ""
  // Written file size per triangle of a closed mesh (about half as many vertices), for the
  // estimate before an export; measured on Strata's own exports (bone scaffold and
  // armadillo - bunny at 256 cells, 2026-11-23). 0 when not writable.
  double bytesPerTriangle = 0.0;
  // The file lists each triangle's corners by position, not by index (STL): its parser gives
  // every triangle three vertices of its own, and the readers of mesh_io.h weld them.
  bool unindexed = false;
  StoredCoordinate stored = nullptr;  // nullptr when not writable
  MeshBlockReader blocks = nullptr;   // nullptr: read whole only
  bool supports(MeshAccess access) const {
    return access == MeshAccess::Read ? parse != nullptr : write != nullptr;
  }
};

// Every format, in the order messages and usage text list them.
const std::vector<MeshFormat>& meshFormats();

// The extension of the last path component, lower-cased (ASCII), without the dot: "stl" for
// "dir.v2/Part.STL"; "" when there is none ("README", "dir.d/file", "file.").
std::string lowerExtension(const std::string& path);

// The format of a path by its extension, or nullptr when no format has it.
const MeshFormat* meshFormatForPath(const std::string& path);
// The same, only when that format can be read (or written); nullptr otherwise.
const MeshFormat* meshFormatFor(const std::string& path, MeshAccess access);

// Every extension of the readable (writable) formats, in table order: {"stl", "obj", ...}.
std::vector<std::string> meshExtensions(MeshAccess access);

// The extensions for a message, dotted and joined: ".stl, .obj, .ply or .3mf" (the last one
// joined by `lastJoin`, ", " for ".stl, .obj, .ply, .3mf").
std::string meshExtensionList(MeshAccess access, const char* lastJoin = " or ");

// One line for usage text, each extension with its note: ".stl (binary), .obj (+ .mtl, a
// material per leaf), ... or .3mf (...)". Callers wrap it.
std::string meshFormatUsage(MeshAccess access);

}  // namespace strata
