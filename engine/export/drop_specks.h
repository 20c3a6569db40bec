// Specks the grid cannot resolve, left out of an export.
//
// Where a solid is thinner than a cell, dual contouring can wrap a node or two in a closed
// component of a dozen triangles and no volume to speak of (1e-10 of the part), or leave such
// a bubble in a solid. A component is left out when the grid does not resolve it, by either
// of two rules that name no tuned size:
//   - its sides are not resolved: none of its triangles is dual to an edge whose inside node
//     all three rays agree is inside (a speck that encloses no node the grid is sure of), or
//     none to an edge whose outside node all three agree is outside, or that lies on the
//     grid's outer faces (a bubble that excludes none): CellTriangle::resolved
//     (contour_cells.h);
//   - it fits within one cell: its vertices span less than the cell size h along every axis.
// A feature at least a cell across along some axis, with a node the grid is sure of on each
// side, is kept, whatever its shape; what was left out is counted in the export's report. The
// triangles of an open mesh (Node::meshOpen) count as resolved: its rays through its holes are
// left empty, so no node of its inside has all three rays agreeing (contour_scene.cpp).
// Where every component would go (the whole result is thinner than a cell), none does.
//
// Synchronous; parallel inside (parallel_for.h); the result does not depend on the thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/geometry/export_mesh.h"

namespace strata {

struct DroppedSpecks {
  int components = 0;    // closed components left out
  size_t triangles = 0;  // their triangles
};

// "3 specks the grid cannot resolve left out (36 triangles: ...)", or "" when none were: what
// the command line's report and the editor's export window say of them.
std::string droppedSpecksSentence(const DroppedSpecks& dropped);

// Removes from `mesh` every component (triangles joined through shared vertices) that the grid
// does not resolve (see above), given each triangle's CellTriangle::resolved bits, and the
// vertices only those used (and any no triangle uses); the rest keep their order. `resolved`
// and mesh->triangleLeaf are shortened alike.
// `cell` is h in the mesh's units.
// `roots`: the mesh's vertex component roots (vertexComponentRoots) when the caller has them;
// computed here otherwise.
// The rule above for one component, shared with the streamed export (streamed_export.h): `bits`
// its triangles' CellTriangle::resolved bits ORed, `vertices` how many it has, (lo, hi) the box
// around them (read only when vertices <= kMeasuredSpeckVertices: a component that fits in a
// box of side h touches at most 2 x 2 x 2 cells, with at most four vertices each and a face
// vertex per split face segment, far fewer than this). True: the component stays.
constexpr uint32_t kMeasuredSpeckVertices = 256;
bool keepComponent(uint8_t bits, uint32_t vertices, const glm::dvec3& lo, const glm::dvec3& hi,
                   double cell);

DroppedSpecks dropUnresolvedSpecks(ExportMesh* mesh, std::vector<uint8_t>* resolved, double cell,
                                   const std::vector<uint32_t>* roots = nullptr);

}  // namespace strata
