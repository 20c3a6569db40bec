// Meshes that exercise the export's component steps, shared by its tests.
#pragma once

#include <memory>

#include "engine/document/node.h"
#include "engine/document/scene.h"
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

// Two bars (5 x 5 across) along x, one from -50 to `gapFrom`, the other from `gapTo` to 50: the
// scene's bounds, and so its grids, do not depend on the gap. At `resolution` cells.
Scene barsWithAGap(double gapFrom, double gapTo, int resolution);
// Bars whose gap the export's estimate cannot see and the export can (bodiesDifferSentence):
// 0.3 of a cell of the estimate's last probe wide, centred between two of its nodes (so none
// lies in it), at least two of the export's cells wide. For `resolution` above kProbeAbove.
// Sets *probeCells (when not null) to the probe's cells along the longest side.
Scene barsCloserThanTheProbesCell(int resolution, int* probeCells = nullptr);

}  // namespace strata::test
