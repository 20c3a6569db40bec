// Classic Mac OS line ends become LF in a copy; meshes too large or too small to measure in
// double are refused with the span of their coordinates.
#include "engine/io/reader_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/geometry/mesh_check.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

}  // namespace

std::optional<std::string> lfCopyIfCrOnlyLineEnds(std::string_view text) {
  const size_t firstEnd = text.find_first_of("\r\n");
  if (firstEnd == std::string_view::npos || text[firstEnd] == '\n') return std::nullopt;
  const size_t afterCrs = text.find_first_not_of('\r', firstEnd);
  if (afterCrs == std::string_view::npos || text[afterCrs] == '\n') return std::nullopt;
  std::string copy(text);
  std::replace(copy.begin() + firstEnd, copy.end(), '\r', '\n');
  return copy;
}

void requireMeasurableExtent(const std::string& name, const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return;
  // All positions first, quickly; the vertices the triangles use only when those span too
  // much, so that a stray unused vertex (which prepareMesh drops) is no reason to refuse.
  double extent = largestExtent(mesh.positions);
  if (extent > kMaxMeasurableExtent) extent = largestUsedExtent(mesh);
  if (extent > kMaxMeasurableExtent) {
    const std::string span = std::isinf(extent) ? "more than 1.8e+308" : shortNumber(extent);
    throw Error(name + ": coordinates span " + span + ", more than " +
                shortNumber(kMaxMeasurableExtent) +
                ": the mesh's volume and area would overflow a double; rescale the mesh");
  }
  if (extent > 0.0 && extent < kMinMeasurableExtent) {
    throw Error(name + ": coordinates span only " + shortNumber(extent) + ", less than " +
                shortNumber(kMinMeasurableExtent) +
                ": the mesh's volume and area would underflow a double; rescale the mesh");
  }
  if (extent == 0.0) {
    const glm::dvec3& p = mesh.positions[mesh.triangles[0][0]];
    std::string what = name + ": all vertices lie at one point (" + shortNumber(p.x) + ", " +
                       shortNumber(p.y) + ", " + shortNumber(p.z) + "): the mesh has no size";
    if (p.x != 0.0 || p.y != 0.0 || p.z != 0.0) {
      what +=
          " (coordinates this far from the origin keep only 16 significant digits: a solid "
          "there must span more than about 1e-15 of its distance from the origin)";
    }
    throw Error(what);
  }
}

}  // namespace meshio
}  // namespace strata
