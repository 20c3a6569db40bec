#include <cub/device/device_scan.cuh>

#include <vector>

#include "engine/ldi/sample_mesh.h"
#include "engine/ldi/shared_math.h"
#include "gpu/ldi/csr_build.cuh"
#include "gpu/ldi/sample_mesh.cuh"

namespace strata {
namespace {

struct TriangleInput {
  double p[3][3];  // corners, global grid units
  double n[3];     // unit outward normal
};

struct AxisSetup {
  int axis;
  int64_t firstU, firstV;
  int raysU, raysV;
};

__global__ void projectTriangles(const TriangleInput* in, int64_t count, AxisSetup s,
                                 ProjectedTriangle* out, uint64_t* work) {
  for (int64_t t = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; t <= count;
       t += int64_t(gridDim.x) * blockDim.x) {
    if (t == count) {
      work[t] = 0;
      continue;
    }
    ProjectedTriangle pt = projectTriangle(in[t].p, in[t].n, s.axis, s.firstU, s.firstV, s.raysU,
                                           s.raysV);
    out[t] = pt;
    int64_t w = int64_t(pt.rayUMax - pt.rayUMin + 1) * int64_t(pt.rayVMax - pt.rayVMin + 1);
    work[t] = pt.rayUMax < pt.rayUMin ? 0 : uint64_t(w);
  }
}

// The triangle whose work range holds item w: the last t with scan[t] <= w.
__device__ int64_t triangleOf(const uint64_t* scan, int64_t count, uint64_t w) {
  int64_t lo = 0, hi = count;  // scan[lo] <= w < scan[hi]
  while (hi - lo > 1) {
    int64_t mid = (lo + hi) / 2;
    if (scan[mid] <= w)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

template <bool kWrite>
__global__ void rasterize(const ProjectedTriangle* tris, const uint64_t* scan, int64_t count,
                          uint64_t totalWork, int raysU, uint32_t leafId, uint32_t* counters,
                          const uint64_t* rawOffsets, Surfel* raw) {
  for (uint64_t w = blockIdx.x * uint64_t(blockDim.x) + threadIdx.x; w < totalWork;
       w += uint64_t(gridDim.x) * blockDim.x) {
    const int64_t t = triangleOf(scan, count, w);
    const ProjectedTriangle& pt = tris[t];
    const uint64_t local = w - scan[t];
    const int width = pt.rayUMax - pt.rayUMin + 1;
    const int i = pt.rayUMin + int(local % uint64_t(width));
    const int j = pt.rayVMin + int(local / uint64_t(width));
    double depth;
    if (!hitTriangle(pt, i, j, &depth)) continue;
    const int64_t ray = int64_t(i) + int64_t(j) * raysU;
    const uint32_t slot = atomicAdd(&counters[ray], 1u);
    if (kWrite)
      raw[rawOffsets[ray] + slot] = Surfel{float(depth), pt.normal, makeSurfelTag(leafId, pt.enters)};
  }
}

__device__ bool surfelLessDevice(const Surfel& a, const Surfel& b) {
  if (a.depth != b.depth) return a.depth < b.depth;
  if (a.tag != b.tag) return a.tag < b.tag;
  return a.normal < b.normal;
}

__global__ void sortAndNormalize(Surfel* raw, const uint64_t* rawOffsets, int64_t rays, float lo,
                                 float hi, uint32_t leafId, uint32_t minus, uint32_t plus,
                                 Surfel* normalized, uint64_t* normalizedOffsets,
                                 uint32_t* normalizedCounts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    Surfel* list = raw + rawOffsets[r];
    const int n = int(rawOffsets[r + 1] - rawOffsets[r]);
    // Insertion sort: lists are short, and the order matches the CPU's std::sort exactly
    // because the comparison is a total order on distinct keys.
    for (int k = 1; k < n; ++k) {
      Surfel x = list[k];
      int m = k - 1;
      while (m >= 0 && surfelLessDevice(x, list[m])) {
        list[m + 1] = list[m];
        --m;
      }
      list[m + 1] = x;
    }
    const uint64_t at = rawOffsets[r] + 2 * uint64_t(r);
    normalizedOffsets[r] = at;
    normalizedCounts[r] =
        uint32_t(normalizeLeafRay(list, n, lo, hi, leafId, minus, plus, normalized + at));
  }
}

uint64_t exclusiveScan64(uint64_t* data, int64_t count, cudaStream_t stream) {
  size_t tempBytes = 0;
  STRATA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, tempBytes, data, data, count, stream));
  DeviceBuffer<unsigned char> temp(tempBytes);
  STRATA_CUDA_CHECK(
      cub::DeviceScan::ExclusiveSum(temp.data(), tempBytes, data, data, count, stream));
  uint64_t total = 0;
  STRATA_CUDA_CHECK(cudaMemcpyAsync(&total, data + count - 1, sizeof(uint64_t),
                                    cudaMemcpyDeviceToHost, stream));
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  return total;
}

__global__ void widen(const uint32_t* counts, int64_t rays, uint64_t* out) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= rays;
       r += int64_t(gridDim.x) * blockDim.x)
    out[r] = r < rays ? counts[r] : 0;
}

}  // namespace

std::shared_ptr<DeviceLdi> sampleMeshOnDevice(const GridMesh& mesh, const Grid& grid,
                                              uint32_t leafId, cudaStream_t stream) {
  auto ldi = std::make_shared<DeviceLdi>(grid);
  const int64_t count = int64_t(mesh.triangles.size());
  std::vector<TriangleInput> host(static_cast<size_t>(count));
  for (int64_t t = 0; t < count; ++t) {
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) host[size_t(t)].p[c][k] = mesh.positions[mesh.triangles[t][c]][k];
    for (int k = 0; k < 3; ++k) host[size_t(t)].n[k] = mesh.normals[size_t(t)][k];
  }
  DeviceBuffer<TriangleInput> input;
  input.upload(host, stream);
  DeviceBuffer<ProjectedTriangle> projected(static_cast<size_t>(count));
  DeviceBuffer<uint64_t> work(size_t(count) + 1);

  for (int axis = 0; axis < 3; ++axis) {
    const int u = grid.uAxis(axis), v = grid.vAxis(axis);
    const AxisSetup setup{axis, grid.first[u], grid.first[v], grid.raysU(axis), grid.raysV(axis)};
    const int64_t rays = grid.rayCount(axis);
    DeviceAxisLdi& out = ldi->axes[axis];
    if (count == 0) {
      out.offsets.resize(size_t(rays) + 1);
      STRATA_CUDA_CHECK(
          cudaMemsetAsync(out.offsets.data(), 0, out.offsets.bytes(), stream));
      continue;
    }
    projectTriangles<<<blocksFor(count + 1, 128), 128, 0, stream>>>(input.data(), count, setup,
                                                                   projected.data(), work.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    const uint64_t totalWork = exclusiveScan64(work.data(), count + 1, stream);

    DeviceBuffer<uint32_t> counters(static_cast<size_t>(rays));
    STRATA_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, counters.bytes(), stream));
    const unsigned blocks = blocksFor(int64_t(totalWork < (1u << 30) ? totalWork : (1u << 30)), 256);
    rasterize<false><<<blocks, 256, 0, stream>>>(projected.data(), work.data(), count, totalWork,
                                                 setup.raysU, leafId, counters.data(), nullptr,
                                                 nullptr);
    STRATA_CUDA_CHECK(cudaGetLastError());
    DeviceBuffer<uint64_t> rawOffsets(size_t(rays) + 1);
    widen<<<blocksFor(rays + 1, 256), 256, 0, stream>>>(counters.data(), rays, rawOffsets.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    const uint64_t rawTotal = exclusiveScan64(rawOffsets.data(), rays + 1, stream);
    DeviceBuffer<Surfel> raw(static_cast<size_t>(rawTotal));
    STRATA_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, counters.bytes(), stream));
    rasterize<true><<<blocks, 256, 0, stream>>>(projected.data(), work.data(), count, totalWork,
                                                setup.raysU, leafId, counters.data(),
                                                rawOffsets.data(), raw.data());
    STRATA_CUDA_CHECK(cudaGetLastError());

    // Sort and normalise into a scratch with room for two synthetic surfels per ray.
    DeviceBuffer<Surfel> normalized(static_cast<size_t>(rawTotal + 2 * uint64_t(rays)));
    DeviceBuffer<uint64_t> normalizedOffsets(static_cast<size_t>(rays));
    const float lo = clipLo(grid, axis), hi = clipHi(grid, axis);
    const uint32_t minus = encodeNormal(axis == 0 ? -1.f : 0.f, axis == 1 ? -1.f : 0.f,
                                        axis == 2 ? -1.f : 0.f);
    const uint32_t plus = encodeNormal(axis == 0 ? 1.f : 0.f, axis == 1 ? 1.f : 0.f,
                                       axis == 2 ? 1.f : 0.f);
    sortAndNormalize<<<blocksFor(rays, 128), 128, 0, stream>>>(
        raw.data(), rawOffsets.data(), rays, lo, hi, leafId, minus, plus, normalized.data(),
        normalizedOffsets.data(), counters.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    const uint64_t total = scanCounts(counters.data(), rays, &out.offsets, stream, "sampling");
    compactRays(normalized.data(), normalizedOffsets.data(), counters.data(), rays, &out, total,
                stream);
  }
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  return ldi;
}

}  // namespace strata
