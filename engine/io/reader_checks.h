// Private to engine/io: checks every text mesh reader (OBJ, OFF, ascii STL, PLY) applies to a
// whole file before or after parsing it. Synchronous, no shared state: any thread may call them.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "engine/geometry/mesh.h"

namespace strata {
namespace meshio {

// Text whose first line ends with a lone CR (classic Mac OS line ends), which LineReader does
// not split on: a copy with every CR turned into LF. The copy has the same length, so byte
// offsets still hold (a binary PLY body is read from the original), and LineReader numbers the
// file's CR-ended lines. nullopt for any other text, after looking at its first line only.
std::optional<std::string> lfCopyIfCrOnlyLineEnds(std::string_view text);

// Throws strata::Error "<name>: ..." when the mesh's volume and area cannot be measured in
// double: the vertices its triangles use span more than kMaxMeasurableExtent (mesh_check.h),
// or all its positions span less than kMinMeasurableExtent or lie at one point (looking at all
// positions is quick; it misses a tiny mesh beside a stray vertex no triangle uses). Meshes
// without triangles pass (the caller says that they are empty).
void requireMeasurableExtent(const std::string& name, const TriangleMesh& mesh);

}  // namespace meshio
}  // namespace strata
