#include "gpu/ldi/combine_ldi.cuh"
#include "gpu/ldi/csr_build.cuh"

namespace strata {
namespace {

// views[axis * childCount + c] is child c's axis.
__global__ void countEvents(const AxisLdiView* views, int childCount, RaySpace space,
                            uint64_t* eventOffsets) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    uint64_t n = 0;
    if (r < space.total()) {
      const int axis = space.axisOf(r);
      const int64_t ray = r - space.base[axis];
      n = rayEventCount(views + axis * childCount, childCount, ray, int(ray % space.raysU[axis]),
                        int(ray / space.raysU[axis]));
    }
    eventOffsets[r] = n;
  }
}

__global__ void combineRays(const AxisLdiView* views, int childCount, RaySpace space, RayOp op,
                            const uint64_t* eventOffsets, RayEvent* events, Surfel* out,
                            uint32_t* counts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    const int axis = space.axisOf(r);
    const int64_t ray = r - space.base[axis];
    RayEvent* ev = events + eventOffsets[r];
    const int n = gatherRayEvents(views + axis * childCount, childCount, ray,
                                  int(ray % space.raysU[axis]), int(ray / space.raysU[axis]), ev);
    counts[r] = uint32_t(combineRayEvents(op, childCount, ev, n, out + eventOffsets[r]));
  }
}

}  // namespace

std::shared_ptr<DeviceLdi> emptyOnDevice(const Grid& grid, const DeviceStream& stream) {
  auto ldi = std::make_shared<DeviceLdi>(grid, stream);
  for (int axis = 0; axis < 3; ++axis) {
    auto& offsets = ldi->axes[axis].offsets;
    offsets = DeviceBuffer<uint32_t>(static_cast<size_t>(grid.rayCount(axis)) + 1, stream);
    STRATA_CUDA_CHECK(cudaMemsetAsync(offsets.data(), 0, offsets.bytes(), stream.get()));
  }
  stream.synchronize();
  return ldi;
}

std::shared_ptr<DeviceLdi> combineOnDevice(RayOp op, const std::vector<const DeviceLdi*>& children,
                                           const Grid& grid, const DeviceStream& stream) {
  if (children.empty()) return emptyOnDevice(grid, stream);
  auto ldi = std::make_shared<DeviceLdi>(grid, stream);
  const int childCount = int(children.size());
  const RaySpace space(grid);
  const int64_t rays = space.total();
  std::vector<AxisLdiView> views;
  for (int axis = 0; axis < 3; ++axis)
    for (const DeviceLdi* c : children) {
      const DeviceAxisLdi& a = c->axes[axis];
      AxisLdiView v{a.offsets.data(), a.surfels.data()};
      v.whole = a.whole;
      v.u0 = a.window.u0;
      v.v0 = a.window.v0;
      v.uCount = a.window.uCount;
      v.vCount = a.window.vCount;
      views.push_back(v);
    }
  const auto deviceViews = DeviceBuffer<AxisLdiView>::upload(views, stream);

  DeviceBuffer<uint64_t> eventOffsets(static_cast<size_t>(rays) + 1, stream);
  countEvents<<<blocksFor(rays + 1, 256), 256, 0, stream.get()>>>(deviceViews.data(), childCount,
                                                                  space, eventOffsets.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(eventOffsets.data(), rays + 1, stream);
  // Every surfel of every child is one event of its ray: the total is known here, no wait.
  uint64_t totalEvents = 0;
  for (const DeviceLdi* c : children) totalEvents += c->surfelCount();

  DeviceBuffer<RayEvent> events(static_cast<size_t>(totalEvents), stream);
  DeviceBuffer<Surfel> scratch(static_cast<size_t>(totalEvents), stream);
  DeviceBuffer<uint32_t> counts(static_cast<size_t>(rays), stream);
  combineRays<<<blocksFor(rays, 128), 128, 0, stream.get()>>>(
      deviceViews.data(), childCount, space, op, eventOffsets.data(), events.data(), scratch.data(),
      counts.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  buildAxes(space, counts.data(), scratch.data(), eventOffsets.data(), ldi.get(), "Boolean");
  stream.synchronize();
  return ldi;
}

}  // namespace strata
