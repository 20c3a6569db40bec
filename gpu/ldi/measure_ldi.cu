#include <cub/device/device_reduce.cuh>

#include "gpu/ldi/csr_build.cuh"
#include "gpu/ldi/measure_ldi.cuh"

namespace strata {
namespace {

__global__ void measureRays(const uint32_t* offsets, const Surfel* surfels, int64_t rays,
                            double* length, double* area) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < rays;
       r += int64_t(gridDim.x) * blockDim.x) {
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

double sum(const double* values, int64_t count, const DeviceStream& stream) {
  DeviceBuffer<double> result(1, stream);
  size_t tempBytes = 0;
  STRATA_CUDA_CHECK(
      cub::DeviceReduce::Sum(nullptr, tempBytes, values, result.data(), count, stream.get()));
  DeviceBuffer<unsigned char> temp(tempBytes, stream);
  STRATA_CUDA_CHECK(
      cub::DeviceReduce::Sum(temp.data(), tempBytes, values, result.data(), count, stream.get()));
  double host = 0.0;
  STRATA_CUDA_CHECK(
      cudaMemcpyAsync(&host, result.data(), sizeof(double), cudaMemcpyDeviceToHost, stream.get()));
  stream.synchronize();
  return host;
}

}  // namespace

LdiMeasure measureOnDevice(const DeviceLdi& ldi, const DeviceStream& stream) {
  LdiMeasure m;
  const Grid& grid = ldi.grid();
  const double h = grid.h;
  for (int axis = 0; axis < 3; ++axis) {
    const DeviceAxisLdi& a = ldi.axes[axis];
    const int64_t rays = a.whole ? grid.rayCount(axis) : a.window.rayCount();  // stored rays
    DeviceBuffer<double> length(static_cast<size_t>(rays), stream),
        area(static_cast<size_t>(rays), stream);
    measureRays<<<blocksFor(rays, 256), 256, 0, stream.get()>>>(ldi.axes[axis].offsets.data(),
                                                                ldi.axes[axis].surfels.data(), rays,
                                                                length.data(), area.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    m.axisVolume[axis] = sum(length.data(), rays, stream) * h * h * h;
    m.area += sum(area.data(), rays, stream) * h * h;
    m.surfels += ldi.axes[axis].surfels.size();
  }
  m.volume = (m.axisVolume[0] + m.axisVolume[1] + m.axisVolume[2]) / 3.0;
  return m;
}

}  // namespace strata
