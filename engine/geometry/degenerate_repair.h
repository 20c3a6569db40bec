// Triangles without area, as a file would store them, made into good ones before writing.
//
// A dual contour can place three vertices of a flat region exactly on one line (a symmetric
// part: two vertices mirrored about a diagonal and one on it), and a format that stores fewer
// bits than a double (float32 STL, nine digits in OBJ and 3MF) can round a sliver flat or two
// vertices onto one point. checkMesh counts such triangles as degenerate and the export's check
// then fails. Both are repaired here without moving any vertex:
//   - a triangle whose corners are distinct but collinear (a zero cross product, computed as
//     checkMesh computes it: the edges from its first corner) has its longest edge flipped with
//     the neighbour across it: (a, b, c) and (a, c, d) with b on a-c become (a, b, d) and
//     (b, c, d), the same surface, closed and oriented as before (where no flip gives two good
//     triangles but the cross product from another corner is not zero, a sliver flat only to
//     rounding, its corners are turned instead);
//   - an edge whose two ends are stored at one point is collapsed (its two triangles go, one end
//     takes the other's place) where its ends share no neighbour but the two triangles' third
//     corners (the link condition: the surface stays a 2-manifold of the same topology).
// What neither can repair (a flip that would duplicate an edge or give a new flat triangle, a
// collapse the link condition refuses) is left and counted; the check then reports it.
//
// Synchronous; parallel inside (parallel_for.h). The result does not depend on the thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/geometry/mesh.h"

namespace strata {

struct DegenerateRepair {
  size_t flipped = 0;    // collinear triangles made good by an edge flip
  size_t rotated = 0;    // flat only from their first corner: turned, where no flip could help
  size_t collapsed = 0;  // zero-length edges collapsed (two triangles gone each)
  size_t left = 0;       // degenerate triangles neither could repair
};

// The coordinate a format stores for a double (mesh_formats.h's StoredCoordinate); nullptr for
// the doubles as they are.
using StoredRounding = double (*)(double value);

// Repairs `mesh`'s degenerate triangles as `stored` rounds its positions (see above). Positions
// are not changed. Triangles keep their indices except where a collapse removes two: then the
// rest keep their order, and `triangleData` (one entry per triangle, when not null) is
// shortened alike. Vertices a collapse no longer uses stay (unused).
DegenerateRepair repairDegenerateTriangles(TriangleMesh* mesh, StoredRounding stored,
                                           std::vector<uint32_t>* triangleData = nullptr);

// The same on a part of a mesh (the streamed export, engine/export/streamed_export.h), which
// repairs it as the whole mesh would be repaired there: `ringComplete[v]` (per vertex of `mesh`)
// says that every triangle around v is in the part, with the whole mesh's triangles in their
// order and every flawed one among them. Returns false, with *mesh part-way repaired, where a
// round would read around a vertex whose ring is not complete (the caller then repeats on a
// larger part); true with *report as above otherwise.
bool repairDegenerateTriangles(TriangleMesh* mesh, StoredRounding stored,
                               std::vector<uint32_t>* triangleData,
                               const std::vector<uint8_t>* ringComplete, DegenerateRepair* report);

// Whether a triangle with these corners is flawed (coincident or collinear corners) as `stored`
// rounds them: what the repair above repairs.
bool storedFlawed(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                  StoredRounding stored);

}  // namespace strata
