// Meshes that exercise the export's component steps, shared by its tests.
#pragma once

#include <memory>

#include "engine/document/node.h"
#include "engine/geometry/mesh.h"

namespace strata::test {

// A faceted torus (`around` x `across` quads, two triangles each): minus a UV sphere, its tube
// meets the sphere at grazing angles, where slivers thinner than a cell hold single grid nodes
// (specks, drop_specks.h).
std::shared_ptr<const TriangleMesh> facetedTorus(double major, double minor, int around,
                                                 int across);

// Found by fuzz_pipeline (tests/fuzz/seeds/pipeline/folded_sliver): an octahedron folded into
// a sliver thinner than a cell, mirrored, placed where at 8 cells its one inside node gives a
// closed shell of 12 triangles whose QEF vertices crowd onto the sliver and turn it inside out
// (unfold_shells.h). The leaf, transformed.
NodePtr foldedSliver();

}  // namespace strata::test
