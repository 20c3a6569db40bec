// A finished surface ready to be written: triangles in scene units, each tagged with the leaf
// of the CSG tree its surface came from, and the leaves' names and colours.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/geometry/mesh.h"

namespace strata {

struct LeafStyle {
  std::string name;
  glm::vec3 color{0.8f, 0.8f, 0.8f};  // linear RGB in [0, 1]
};

struct ExportMesh {
  TriangleMesh mesh;                     // scene units, outward oriented
  std::vector<uint32_t> triangleLeaf;    // per triangle: the leaf id (size = triangles)
  std::map<uint32_t, LeafStyle> leaves;  // every leaf id used by triangleLeaf
  std::string unit = "millimetre";       // length unit of the coordinates
};

}  // namespace strata
