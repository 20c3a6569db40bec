// Shells that vertex placement turned inside out, put right.
//
// Dual contouring joins the vertices of the cells around each sign-changing grid edge, so a
// shell's orientation comes from the grid: it encloses its inside nodes (an outer shell, positive
// volume) or a void (negative volume). Each vertex is then moved to its cell's QEF minimiser.
// Where a part is thinner than a cell, the minimisers of all the cells around it crowd onto the
// thin surface and can fold the shell through itself until its signed volume has the wrong
// sign: a closed, manifold mesh that a slicer reads as a void where there is material.
//
// Measured against the same shell with every cell vertex at its cell's centre (the boundary of
// the union of the inside nodes' dual cubes, whose orientation is the grid's own), a shell whose
// volume has a different sign, or none, is pulled towards those centres by halves (1/2, 1/4,
// ... of the way back from the centres) until the signs agree, and at worst to the centres.
// Vertices of cells with several components are pulled halfway between centre and their own
// position instead, so that they stay apart.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "engine/contour/contour_tile.h"
#include "engine/geometry/mesh.h"
#include "engine/ldi/grid.h"
#include "engine/util/parallel_for.h"

namespace strata {

// `mesh` is the indexed contour in scene units on `grid` (the whole grid, not a tile's window);
// `keys` the keys of the contour vertices it was built from (same order: vertex i has key
// keys[i]); `rootOf` its vertices' component roots (vertexComponentRoots). Moves the
// vertices of inverted shells; returns how many shells it moved.
int unfoldInvertedShells(const Grid& grid, const std::vector<uint64_t>& keys,
                         const std::vector<uint32_t>& rootOf, TriangleMesh* mesh);

// The steps above, shared with the streamed export (streamed_export.h), which runs them on a
// mesh it holds a piece at a time.
//
// Whether vertex i of keys sorted in key order shares its cell with another component's vertex
// (their keys are adjacent: cell * 4 + component).
inline bool sharesCell(const std::vector<uint64_t>& keys, size_t i) {
  const uint64_t cell = keys[i] / 4;
  return (i > 0 && keys[i - 1] / 4 == cell) || (i + 1 < keys.size() && keys[i + 1] / 4 == cell);
}
// Where the vertex with `key` at `position` goes at the grid's own placement: its cell's
// centre, or halfway there when `sharedCell`; a face-segment vertex stays.
glm::dvec3 shellAnchor(const Grid& grid, uint64_t key, bool sharedCell, const glm::dvec3& position);
// Six times the signed volume of one triangle, corners relative to a reference point.
double sixVolumeTerm(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
int volumeSign(double x);
// How much of each vertex's offset from its anchor an inverted shell keeps (1/2, 1/4, ...,
// 1/32, else 0): the first at which the shell's six volume (its triangles in order, corners
// indexing anchors and positions, relative to `ref`) has the sign `want`.
double pullBackKeep(const std::vector<std::array<uint32_t, 3>>& triangles,
                    const std::vector<glm::dvec3>& anchors,
                    const std::vector<glm::dvec3>& positions, const glm::dvec3& ref, int want);

// One run of a shell's six volumes (ShellRunSums): the terms of consecutive triangles of one
// shell within one chunk, summed in order from zero.
struct ShellRun {
  static constexpr uint32_t kNone = UINT32_MAX;
  uint32_t shell = kNone;
  double anchored = 0.0, placed = 0.0;
};

// The order in which each shell's six volumes are summed, the one place that fixes it (the
// in-memory unfoldInvertedShells and the streamed export read it): the mesh's triangles in
// chunks of kChunk (by their place in the whole mesh), the terms of consecutive triangles of
// one shell within a chunk summed in order from zero (a run), and the runs handed to `flush` in
// the mesh's order, which adds each to its shell's sums. The triangles come in stretches of any
// length (the streamed export's pieces), in order; each stretch's chunks are summed in parallel
// (parallel_for.h): the same sums, bit for bit, whatever the stretches and the thread count.
class ShellRunSums {
 public:
  static constexpr uint64_t kChunk = 65536;

  // The next `count` triangles of the mesh. term(i, &shell, &anchored, &placed) gives the
  // stretch's triangle i's shell and two terms (called on several threads at once, each i
  // once); flush(const ShellRun&) is called on this thread, in order, for each run completed.
  template <typename Term, typename Flush>
  void add(uint64_t count, const Term& term, const Flush& flush) {
    if (count == 0) return;
    const uint64_t first = next_;
    if (open_.shell != ShellRun::kNone && first % kChunk == 0) {  // a new chunk: the run ends
      flush(open_);
      open_ = ShellRun();
    }
    std::vector<uint64_t> cuts{0};  // the stretch cut where a chunk begins
    for (uint64_t c = (first / kChunk + 1) * kChunk; c < first + count; c += kChunk)
      cuts.push_back(c - first);
    cuts.push_back(count);
    std::vector<std::vector<ShellRun>> runs(cuts.size() - 1);
    parallelFor(0, int64_t(runs.size()), 1, [&](int64_t b, int64_t e) {
      for (int64_t s = b; s < e; ++s) {
        std::vector<ShellRun>& out = runs[size_t(s)];
        // The first segment lies in the chunk of the run left open: it goes on with it.
        if (s == 0 && open_.shell != ShellRun::kNone) out.push_back(open_);
        for (uint64_t i = cuts[size_t(s)]; i < cuts[size_t(s) + 1]; ++i) {
          uint32_t shell = ShellRun::kNone;
          double anchored = 0.0, placed = 0.0;
          term(i, &shell, &anchored, &placed);
          if (out.empty() || out.back().shell != shell) out.push_back({shell, 0.0, 0.0});
          out.back().anchored += anchored;
          out.back().placed += placed;
        }
      }
    });
    // Every run but the stretch's last is complete (a segment's last run ends with its chunk);
    // the last may go on in the next stretch.
    for (size_t s = 0; s < runs.size(); ++s)
      for (size_t r = 0; r < runs[s].size(); ++r) {
        if (s + 1 == runs.size() && r + 1 == runs[s].size()) break;
        flush(runs[s][r]);
      }
    open_ = runs.back().back();
    next_ = first + count;
  }

  // After the last stretch: the run left open.
  template <typename Flush>
  void finish(const Flush& flush) {
    if (open_.shell != ShellRun::kNone) flush(open_);
    open_ = ShellRun();
  }

 private:
  uint64_t next_ = 0;  // the place of the next triangle in the mesh
  ShellRun open_;      // the last stretch's last run
};

}  // namespace strata
