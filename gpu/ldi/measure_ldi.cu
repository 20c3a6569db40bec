#include <cub/device/device_reduce.cuh>

#include <cstring>

#include "gpu/ldi/csr_build.cuh"
#include "gpu/ldi/measure_ldi.cuh"

namespace strata {
namespace {

// Per ray: the inside length, the area its surfels stand for, and its thinnest wall as a key
// that orders by thickness, then by ray (a non-negative float's bits order as the float), with
// the wall's middle depth.
__global__ void measureRays(const uint32_t* offsets, const Surfel* surfels, int64_t rays, int axis,
                            double* length, double* area, uint64_t* wallKey, float* wallDepth) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    float at = 0.0f;
    const float wall =
        rayThinnestWall(surfels + offsets[r], offsets[r + 1] - offsets[r], axis, &at);
    wallKey[r] = (uint64_t(__float_as_uint(wall)) << 32) | uint64_t(r);
    wallDepth[r] = at;
    double l = 0.0, a = 0.0;
    for (uint32_t k = offsets[r]; k < offsets[r + 1]; ++k) {
      const Surfel s = surfels[k];
      l += surfelEnters(s.tag) ? -double(s.depth) : double(s.depth);
      float n[3];
      decodeNormal(s.normal, n);
      a += 1.0 / (fabs(n[0]) + fabs(n[1]) + fabs(n[2]));
    }
    length[r] = l;
    area[r] = a;
  }
}

// `values` reduced by `reduce` (a cub::DeviceReduce entry point: Sum, Min) and read back.
template <typename T, typename Reduce>
T reduceToHost(const T* values, int64_t count, const DeviceStream& stream, Reduce reduce) {
  DeviceBuffer<T> result(1, stream);
  size_t tempBytes = 0;
  STRATA_CUDA_CHECK(reduce(nullptr, tempBytes, values, result.data(), count, stream.get()));
  DeviceBuffer<unsigned char> temp(tempBytes, stream);
  STRATA_CUDA_CHECK(reduce(temp.data(), tempBytes, values, result.data(), count, stream.get()));
  T host{};
  STRATA_CUDA_CHECK(
      cudaMemcpyAsync(&host, result.data(), sizeof(T), cudaMemcpyDeviceToHost, stream.get()));
  stream.synchronize();
  return host;
}

double sum(const double* values, int64_t count, const DeviceStream& stream) {
  return reduceToHost(values, count, stream, [](void* temp, size_t& bytes, auto... rest) {
    return cub::DeviceReduce::Sum(temp, bytes, rest...);
  });
}

uint64_t minimum(const uint64_t* values, int64_t count, const DeviceStream& stream) {
  return reduceToHost(values, count, stream, [](void* temp, size_t& bytes, auto... rest) {
    return cub::DeviceReduce::Min(temp, bytes, rest...);
  });
}

}  // namespace

LdiMeasure measureOnDevice(const DeviceLdi& ldi, const DeviceStream& stream) {
  LdiMeasure m;
  const Grid& grid = ldi.grid();
  const double h = grid.h;
  for (int axis = 0; axis < 3; ++axis) {
    const DeviceAxisLdi& a = ldi.axes[axis];
    const int64_t rays = a.whole ? grid.rayCount(axis) : a.window.rayCount();  // stored rays
    if (rays == 0) continue;
    DeviceBuffer<double> length(static_cast<size_t>(rays), stream),
        area(static_cast<size_t>(rays), stream);
    DeviceBuffer<uint64_t> wallKey(static_cast<size_t>(rays), stream);
    DeviceBuffer<float> wallDepth(static_cast<size_t>(rays), stream);
    measureRays<<<blocksFor(rays, 256), 256, 0, stream.get()>>>(
        ldi.axes[axis].offsets.data(), ldi.axes[axis].surfels.data(), rays, axis, length.data(),
        area.data(), wallKey.data(), wallDepth.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    m.axisVolume[axis] = sum(length.data(), rays, stream) * h * h * h;
    m.area += sum(area.data(), rays, stream) * h * h;
    // The thinnest wall of the axis (the first ray of a tie, as measureLdi).
    const uint64_t key = minimum(wallKey.data(), rays, stream);
    const uint32_t bits = uint32_t(key >> 32);
    float wall = 0.0f;
    std::memcpy(&wall, &bits, sizeof(wall));
    if (double(wall) * h < m.thinnestWall) {
      const int64_t ray = int64_t(key & 0xffffffffu);
      float depth = 0.0f;
      STRATA_CUDA_CHECK(cudaMemcpyAsync(&depth, wallDepth.data() + ray, sizeof(float),
                                        cudaMemcpyDeviceToHost, stream.get()));
      stream.synchronize();
      m.thinnestWall = double(wall) * h;
      m.thinnestAt = rayPoint(grid, axis, a.whole, a.window, ray, depth);
    }
    m.surfels += ldi.axes[axis].surfels.size();
  }
  m.volume = (m.axisVolume[0] + m.axisVolume[1] + m.axisVolume[2]) / 3.0;
  return m;
}

}  // namespace strata
