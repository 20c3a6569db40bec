// Private to engine/io: the per-format writers behind writeMeshFile (mesh_writers.h), each
// named by its entry in the table of mesh_formats.h, and the helpers they share (defined in
// mesh_writers.cpp). Each writer receives an ExportMesh that writeMeshFile has validated
// (indices in range, finite coordinates, one leaf per triangle, every leaf styled, at least one
// triangle) and writes `path` atomically.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

#include "engine/geometry/export_mesh.h"
#include "engine/util/progress.h"

namespace strata {
namespace meshio {

void writeStl(const std::string& path, const ExportMesh& mesh, Progress* progress);
void writeObj(const std::string& path, const ExportMesh& mesh, Progress* progress);
void writePly(const std::string& path, const ExportMesh& mesh, Progress* progress);
void write3mf(const std::string& path, const ExportMesh& mesh, Progress* progress);

// ---- Shared helpers ----

// Elements (vertices or triangles) between two progress reports.
constexpr size_t kProgressStride = 65536;

// When index is a multiple of kProgressStride (0 included): progress->report(stage,
// index / total), which throws Cancelled if cancelled. No-op when progress is null.
void reportEvery(Progress* progress, const std::string& stage, size_t index, size_t total);

// Writes the bytes of `count` records (vertices, triangles) to `out` in order, serialised in
// parallel: append(first, last, bytes) appends the bytes of records [first, last) to `bytes`
// and must depend on nothing but those records. Blocks of kProgressStride records are filled by
// all workers (parallel_for.h) a group at a time and written in order, so memory stays a few
// blocks per worker; after each group progress->report(stage, (done + records written) /
// total), which throws Cancelled if cancelled. Called from one thread.
using AppendRecords = std::function<void(size_t first, size_t last, std::string& bytes)>;
void writeRecords(std::ostream& out, size_t count, const AppendRecords& append, Progress* progress,
                  const std::string& stage, size_t done, size_t total);

// Appends `value` as printf's "%.9g" would, independent of the C locale.
void appendNumber(std::string& out, double value);

// The coordinates the writers store (StoredCoordinate, mesh_formats.h): as float32 (STL),
// as appendNumber prints them (OBJ, 3MF), or exactly (PLY's doubles).
double storedAsFloat(double value);
double storedAsNineDigits(double value);
double storedExactly(double value);

// A linear RGB channel in [0, 1] (clamped) encoded as sRGB: in [0, 1], and in 0..255.
double linearToSrgb(double linear);
std::array<uint8_t, 3> srgb8(const glm::vec3& linear);

// Text safe for a one-line comment: control characters become '?'.
std::string oneLine(const std::string& text);

}  // namespace meshio
}  // namespace strata
