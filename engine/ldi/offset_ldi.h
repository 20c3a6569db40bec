// Offsets of the solid an LDI describes (CPU reference): the solid grown (d > 0) or shrunk
// (d < 0) by the Euclidean distance |d|, {p : sd(p) <= d} with sd the signed distance to its
// surface (negative inside). Shells and roundings are built from it: a shell of thickness t is
// S minus offset(S, -t); rounding with radius r (opening) is offset(offset(S, -r), r); a fillet
// (closing) offset(offset(S, r), -r).
//
// Method (cost independent of d, linear in the window's nodes):
//   1. For each axis a, every node gets the squared distance along its a-line to the nearest
//      surfel of that line: exact, from the surfels' continuous depths.
//   2. A separable exact Euclidean distance transform over the two other axes (the lower
//      envelope of parabolas, Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled
//      Functions", 2012) turns that into each node's distance to the nearest surfel of any
//      a-line. Taking the smallest over the three axes measures the distance to a sampling of
//      the surface that is dense everywhere (each patch is sampled at most a cell apart along the
//      axis its normal is closest to), so for a node at distance D the error is about
//      (h / sqrt 2)^2 / (2 D) at worst. An envelope is a min-plus convolution and distributes
//      over the minimum, so the x and z rays share their y envelope: five envelopes in all,
//      min(Ey(min(Ez Sx, Ex Sz)), Ez Ex Sy). Distances beyond a band of |d| + 4 cells are
//      stored as far (offsetBandSquared): the result never reads them, and lines that lie
//      wholly beyond it cost the envelopes nothing.
//   3. Signs from the x-rays (inside where the ray's last surfel before the node enters), and
//      the result's surfels where sd - d changes sign between neighbouring nodes of each ray,
//      at the linear interpolation, with the normal of sd's central-difference gradient and the
//      leaf of the nearest surface sample (for colours).
// Memory: 17 bytes per node of the grid window (the running minimum and a working copy, each a
// distance and a leaf, and the inside flags), on top of the LDIs: 2.3 GB at 512^3.
//
// Threads: runs on all worker threads (parallelFor); `progress` is checked between lines.
#pragma once

#include <memory>

#include "engine/ldi/ldi.h"
#include "engine/util/progress.h"

namespace strata {

// The offset by `distance` (scene units) of `in`'s solid, on in's grid. What lies beyond the
// grid is cut at its boundary (the caller gives a grid with room for a growth).
std::shared_ptr<Ldi> offsetLdi(const Ldi& in, double distance, Progress* progress = nullptr);

}  // namespace strata
