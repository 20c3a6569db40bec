#include "gpu/ldi/combine_ldi.cuh"
#include "gpu/ldi/csr_build.cuh"

namespace strata {
namespace {

struct ChildView {
  const uint32_t* offsets;
  const Surfel* surfels;
};

// views[axis * childCount + c] is child c's axis.
__global__ void countEvents(const ChildView* views, int childCount, RaySpace space,
                            uint64_t* eventOffsets) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    uint64_t n = 0;
    if (r < space.total()) {
      const int axis = space.axisOf(r);
      const int64_t local = r - space.base[axis];
      for (int c = 0; c < childCount; ++c) {
        const ChildView& v = views[axis * childCount + c];
        n += v.offsets[local + 1] - v.offsets[local];
      }
    }
    eventOffsets[r] = n;
  }
}

__global__ void combineRays(const ChildView* views, int childCount, RaySpace space, RayOp op,
                            const uint64_t* eventOffsets, RayEvent* events, Surfel* out,
                            uint32_t* counts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    const int axis = space.axisOf(r);
    const int64_t local = r - space.base[axis];
    RayEvent* ev = events + eventOffsets[r];
    int n = 0;
    // Gather in child order with a stable insertion by depth: the same order as the CPU's
    // std::stable_sort over the same concatenation.
    for (int c = 0; c < childCount; ++c) {
      const ChildView& v = views[axis * childCount + c];
      for (uint32_t k = v.offsets[local]; k < v.offsets[local + 1]; ++k) {
        const Surfel s = v.surfels[k];
        const RayEvent e{s.depth, s.normal, s.tag, uint32_t(c)};
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
    offsets.resize(static_cast<size_t>(grid.rayCount(axis)) + 1);
    STRATA_CUDA_CHECK(cudaMemsetAsync(offsets.data(), 0, offsets.bytes(), stream));
  }
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  return ldi;
}

std::shared_ptr<DeviceLdi> combineOnDevice(RayOp op, const std::vector<const DeviceLdi*>& children,
                                           const Grid& grid, cudaStream_t stream) {
  if (children.empty()) return emptyOnDevice(grid, stream);
  auto ldi = std::make_shared<DeviceLdi>(grid);
  const int childCount = int(children.size());
  const RaySpace space(grid);
  const int64_t rays = space.total();
  std::vector<ChildView> views;
  for (int axis = 0; axis < 3; ++axis)
    for (const DeviceLdi* c : children)
      views.push_back(ChildView{c->axes[axis].offsets.data(), c->axes[axis].surfels.data()});
  DeviceBuffer<ChildView> deviceViews;
  deviceViews.upload(views, stream);

  DeviceBuffer<uint64_t> eventOffsets(static_cast<size_t>(rays) + 1);
  countEvents<<<blocksFor(rays + 1, 256), 256, 0, stream>>>(deviceViews.data(), childCount, space,
                                                            eventOffsets.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(eventOffsets.data(), rays + 1, stream);
  uint64_t totalEvents = 0;
  const uint64_t* end[1] = {eventOffsets.data() + rays};
  readBack(end, &totalEvents, 1, stream);

  DeviceBuffer<RayEvent> events(static_cast<size_t>(totalEvents));
  DeviceBuffer<Surfel> scratch(static_cast<size_t>(totalEvents));
  DeviceBuffer<uint32_t> counts(static_cast<size_t>(rays));
  combineRays<<<blocksFor(rays, 128), 128, 0, stream>>>(deviceViews.data(), childCount, space, op,
                                                        eventOffsets.data(), events.data(),
                                                        scratch.data(), counts.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  buildAxes(space, counts.data(), scratch.data(), eventOffsets.data(), ldi.get(), stream,
            "Boolean");
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  return ldi;
}

}  // namespace strata
