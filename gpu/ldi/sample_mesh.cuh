// CUDA sampling of a placed mesh into a device LDI: the twin of engine/ldi/sample_mesh.cpp,
// with the same per-ray math (engine/ldi/shared_math.h), so both see exactly the same hits.
//
// One pass over the geometry per axis, as the paper's atomic depth peeling: project the
// triangles, count hits per ray with atomics, scan, write the hits at their offsets, then sort
// and normalise each ray's list. Work is spread over (triangle, ray) pairs through a scan of
// each triangle's ray count, so a large triangle does not serialise a warp.
#pragma once

#include <cuda_runtime.h>

#include <array>
#include <memory>
#include <vector>

#include "engine/ldi/grid_mesh.h"
#include "gpu/ldi/device_ldi.h"

namespace strata {

// A mesh placed on the grid for sampling, with the rays it can reach: per axis a window
// (meshRayWindow), or the whole grid where that window holds more than half of the grid's rays
// or the mesh is empty (then the axis is kept whole, as the CPU backend does).
struct PlacedLeaf {
  GridMesh mesh;
  uint32_t leafId = 0;
  std::array<RayWindow, 3> windows;
  std::array<bool, 3> whole{};
  // Scratch a sampling batch takes for this leaf, about: 60 bytes a ray, 600 a triangle.
  uint64_t scratchBytes() const;
};
PlacedLeaf placeLeaf(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                     uint32_t leafId);

// Samples many placed leaves in one pass, every surfel tagged with its leaf's id: one upload of
// all their triangles, one launch per step over all of them and three waits in all, however many
// leaves there are; each LDI is what the leaf sampled alone gives (the CPU backend's, bit for
// bit). Scratch memory grows with the batch (scratchBytes): the caller sizes batches.
// Synchronous: returns with `stream` drained. Throws strata::Error (DeviceOutOfMemory when the
// device is full).
std::vector<std::shared_ptr<DeviceLdi>> sampleMeshesOnDevice(
    const std::vector<const PlacedLeaf*>& leaves, const Grid& grid, const DeviceStream& stream);

}  // namespace strata
