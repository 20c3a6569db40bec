// Writing finished surfaces (ExportMesh: triangles in scene units, each tagged with its CSG
// leaf, and the leaves' names and colours) as STL, OBJ + MTL, PLY or 3MF.
//
// Formats, chosen by the extension of `path` (case-insensitive) through the table in
// mesh_formats.h:
//   .stl  binary STL: 80-byte header naming Strata and the unit, a unit facet normal computed
//         from each triangle's winding, attribute 0. Coordinates as float32; no colours.
//   .obj  OBJ with a companion "<basename>.mtl" beside it (`mtllib <basename>.mtl`; white space
//         in the basename becomes '_' in the MTL's name, which mtllib cannot quote): one
//         material per leaf, named after the leaf (sanitised to [A-Za-z0-9_-], made unique),
//         Kd its colour; faces grouped by leaf under `usemtl`. Coordinates printed with %.9g.
//   .ply  binary little-endian PLY: double x y z and uchar red green blue per vertex (a vertex
//         takes the colour of the leaf of the first triangle that uses it), faces as a list of
//         uchar count and int indices.
//   .3mf  3MF package (zip): one object whose triangles carry pid/p1 into an m:colorgroup (3MF
//         materials extension) holding one colour per leaf; the model's unit is the scene unit
//         (millimetre, centimetre, metre, inch, foot, micron; others are refused). %.9g.
// Colours: LeafStyle colours are linear RGB; every format receives them sRGB-encoded, as 3MF
// requires and as viewers show PLY bytes and MTL Kd values (8 bits per channel in PLY and 3MF).
// The unit is recorded in every format (STL header, OBJ/PLY comments, 3MF unit attribute);
// coordinates are never scaled.
//
// Every file is written atomically (engine/util/atomic_file.h): a failed or cancelled export
// leaves no new file and no temporary file behind, and an existing file untouched. The OBJ and
// its MTL are one atomic set: both are replaced or neither. Synchronous; any thread; `progress`
// (may be null) is checked every 65536 elements and before anything is written, and receives stage
// "write <format>" with its fraction.
//
// To verify a written file: engine/export/check_written.h (checkMesh on storedMesh below, and
// the file read back with readMeshFileVerbatim compared with it), or read it back with
// readMeshFileRaw (engine/io/mesh_io.h), which repairs nothing, and run checkMesh on it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "engine/geometry/export_mesh.h"
#include "engine/io/mesh_formats.h"
#include "engine/util/progress.h"

namespace strata {

// Throws strata::Error naming `path` for an unknown extension ("<path>: cannot write mesh format
// '.ext' (supported: .stl, ...)", listing the writable ones), a malformed ExportMesh (no
// triangles, an index out of range, a non-finite coordinate, a leaf id without a style,
// triangleLeaf of the wrong size), a unit 3MF cannot express, or a file that cannot be written;
// throws Cancelled when `progress` is cancelled.
void writeMeshFile(const std::string& path, const ExportMesh& mesh, Progress* progress = nullptr);

// `mesh` as reading the file writeMeshFile(path, ...) wrote gives it back: the same triangles,
// positions rounded as the format stores them (float32 for .stl, %.9g for .obj and .3mf, exact
// for .ply). In place, in parallel: pass the mesh by std::move where it is not needed after.
// Throws strata::Error for an extension no format writes.
TriangleMesh storedMesh(const std::string& path, TriangleMesh mesh);

// How the format of `path` rounds a coordinate it stores (storedMesh's rounding, one value).
// Throws strata::Error for an extension no format writes.
StoredCoordinate storedCoordinate(const std::string& path);

// Binary STL in pieces (the streamed export, engine/export/streamed_export.h; writeMeshFile
// writes with the same): the 84 bytes before the facets (the header naming the unit, the facet
// count), a coordinate's range (throws strata::Error naming `path` where float32 cannot hold
// it), and one facet's kStlFacetBytes: its unit normal from the winding, the corners as float32.
constexpr size_t kStlFacetBytes = 50;
std::string binaryStlHeader(const std::string& unit, uint32_t facets);
void checkStlCoordinates(const std::string& path, const glm::dvec3& p);
void encodeStlFacet(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, char* out);

// Binary PLY in pieces (the streamed export; writeMeshFile writes with the same): the header
// naming the unit and the counts, one vertex's kPlyVertexBytes (x, y, z as little-endian
// doubles, then red, green, blue) and one triangle's kPlyFaceBytes (the count 3, then three
// little-endian int32 indices). A vertex's colour is that of the leaf of the first triangle
// that uses it (plyColour of its style), plyUnusedColour() for one no triangle uses.
constexpr size_t kPlyVertexBytes = 27;
constexpr size_t kPlyFaceBytes = 13;
std::string binaryPlyHeader(const std::string& unit, uint64_t vertices, uint64_t faces);
std::array<uint8_t, 3> plyColour(const LeafStyle& style);
std::array<uint8_t, 3> plyUnusedColour();
void encodePlyVertex(const glm::dvec3& p, const std::array<uint8_t, 3>& colour, char* out);
void encodePlyFace(const std::array<uint32_t, 3>& corners, char* out);

}  // namespace strata
