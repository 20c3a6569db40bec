#include <cub/device/device_scan.cuh>

#include "gpu/ldi/combine_ldi.cuh"
#include "gpu/ldi/csr_build.cuh"

namespace strata {
namespace {

struct ChildView {
  const uint32_t* offsets;
  const Surfel* surfels;
};

__global__ void countEvents(const ChildView* children, int childCount, int64_t rays,
                            uint64_t* eventOffsets) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    uint64_t n = 0;
    if (r < rays)
      for (int c = 0; c < childCount; ++c) n += children[c].offsets[r + 1] - children[c].offsets[r];
    eventOffsets[r] = n;
  }
}

__global__ void combineRays(const ChildView* children, int childCount, int64_t rays, RayOp op,
                            const uint64_t* eventOffsets, RayEvent* events, Surfel* out,
                            uint32_t* counts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    RayEvent* ev = events + eventOffsets[r];
    int n = 0;
    // Gather in child order, then a stable insertion sort by depth: the same order as the
    // CPU's std::stable_sort over the same concatenation.
    for (int c = 0; c < childCount; ++c) {
      for (uint32_t k = children[c].offsets[r]; k < children[c].offsets[r + 1]; ++k) {
        const Surfel s = children[c].surfels[k];
        RayEvent e{s.depth, s.normal, s.tag, uint32_t(c)};
        int m = n - 1;
        while (m >= 0 && e.depth < ev[m].depth) {
          ev[m + 1] = ev[m];
          --m;
        }
        ev[m + 1] = e;
        ++n;
      }
    }
    counts[r] = uint32_t(combineRayEvents(op, childCount, ev, n, out + eventOffsets[r]));
  }
}

}  // namespace

std::shared_ptr<DeviceLdi> emptyOnDevice(const Grid& grid, cudaStream_t stream) {
  auto ldi = std::make_shared<DeviceLdi>(grid);
  for (int axis = 0; axis < 3; ++axis) {
    auto& offsets = ldi->axes[axis].offsets;
    offsets.resize(size_t(grid.rayCount(axis)) + 1);
    STRATA_CUDA_CHECK(cudaMemsetAsync(offsets.data(), 0, offsets.bytes(), stream));
  }
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  return ldi;
}

std::shared_ptr<DeviceLdi> combineOnDevice(RayOp op,
                                           const std::vector<const DeviceLdi*>& children,
                                           const Grid& grid, cudaStream_t stream) {
  if (children.empty()) return emptyOnDevice(grid, stream);
  auto ldi = std::make_shared<DeviceLdi>(grid);
  const int childCount = int(children.size());
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t rays = grid.rayCount(axis);
    std::vector<ChildView> views;
    for (const DeviceLdi* c : children)
      views.push_back(ChildView{c->axes[axis].offsets.data(), c->axes[axis].surfels.data()});
    DeviceBuffer<ChildView> deviceViews;
    deviceViews.upload(views, stream);
    DeviceBuffer<uint64_t> eventOffsets(size_t(rays) + 1);
    countEvents<<<blocksFor(rays + 1, 256), 256, 0, stream>>>(deviceViews.data(), childCount,
                                                              rays, eventOffsets.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    size_t tempBytes = 0;
    STRATA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, tempBytes, eventOffsets.data(),
                                                    eventOffsets.data(), rays + 1, stream));
    DeviceBuffer<unsigned char> temp(tempBytes);
    STRATA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), tempBytes, eventOffsets.data(),
                                                    eventOffsets.data(), rays + 1, stream));
    uint64_t totalEvents = 0;
    STRATA_CUDA_CHECK(cudaMemcpyAsync(&totalEvents, eventOffsets.data() + rays, sizeof(uint64_t),
                                      cudaMemcpyDeviceToHost, stream));
    STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
    DeviceBuffer<RayEvent> events(static_cast<size_t>(totalEvents));
    DeviceBuffer<Surfel> scratch(static_cast<size_t>(totalEvents));
    DeviceBuffer<uint32_t> counts(static_cast<size_t>(rays));
    combineRays<<<blocksFor(rays, 128), 128, 0, stream>>>(deviceViews.data(), childCount, rays, op,
                                                          eventOffsets.data(), events.data(),
                                                          scratch.data(), counts.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    DeviceAxisLdi& out = ldi->axes[axis];
    const uint64_t total = scanCounts(counts.data(), rays, &out.offsets, stream, "Boolean");
    compactRays(scratch.data(), eventOffsets.data(), counts.data(), rays, &out, total, stream);
    STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  }
  return ldi;
}

}  // namespace strata
