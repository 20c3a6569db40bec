// CPU sampling of a closed triangle mesh into a three-axis LDI (the reference implementation;
// gpu/ldi/sample_mesh.cuh is its CUDA twin and shares shared_math.h).
#pragma once

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <memory>

#include "engine/geometry/mesh.h"
#include "engine/ldi/ldi.h"
#include "engine/util/progress.h"

namespace strata {

// Samples `mesh` placed by `objectToWorld` on the rays of `grid`, on all worker threads.
// Every surfel is tagged with `leafId`. A mirroring matrix reverses the winding so normals stay
// outward. The result is clean (sorted, alternating, inside where the winding number is
// non-zero) and clipped to one cell beyond the grid along each ray. Throws strata::Error for
// non-finite or absurdly distant geometry, Cancelled when progress is cancelled.
std::shared_ptr<Ldi> sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld,
                                const Grid& grid, uint32_t leafId, Progress* progress = nullptr);

// The clip range along a ray of `axis`, in global grid units: one cell beyond the window.
inline float clipLo(const Grid& grid, int axis) {
  return float(grid.first[axis] - 1);
}
inline float clipHi(const Grid& grid, int axis) {
  return float(grid.first[axis] + grid.cells[axis] + 1);
}

// Helpers shared with combine_ldi.cpp: builds the CSR of one axis from per-ray clean lists
// produced chunk by chunk.
struct RayChunkOutput {
  std::vector<uint32_t> counts;  // per ray of the chunk
  HostArray<Surfel> surfels;     // the chunk's rays, concatenated
};
// Concatenates chunk outputs (chunk c covers rays [c * raysPerChunk, ...)) into `axis`.
void assembleAxis(std::vector<RayChunkOutput>& chunks, int64_t rayCount, AxisLdi* axis,
                  const char* what);

}  // namespace strata
