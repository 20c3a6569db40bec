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

// What the kernels need of the grid, per axis.
struct AxisSetup {
  int64_t firstU[3], firstV[3];
  int raysU[3], raysV[3];
  float lo[3], hi[3];
  uint32_t minus[3], plus[3];  // encoded -axis / +axis normals for clipped ends
};

// Job j = axis * count + t: triangle t projected for `axis`; work[j] = its candidate rays.
__global__ void projectTriangles(const TriangleInput* in, int64_t count, AxisSetup s,
                                 ProjectedTriangle* out, uint64_t* work) {
  const int64_t jobs = 3 * count;
  for (int64_t j = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; j <= jobs;
       j += int64_t(gridDim.x) * blockDim.x) {
    if (j == jobs) {
      work[j] = 0;
      continue;
    }
    const int axis = int(j / count);
    const int64_t t = j % count;
    ProjectedTriangle pt = projectTriangle(in[t].p, in[t].n, axis, s.firstU[axis], s.firstV[axis],
                                           s.raysU[axis], s.raysV[axis]);
    out[j] = pt;
    const int64_t w = int64_t(pt.rayUMax - pt.rayUMin + 1) * int64_t(pt.rayVMax - pt.rayVMin + 1);
    work[j] = pt.rayUMax < pt.rayUMin ? 0 : uint64_t(w);
  }
}

// The job whose work range holds item w: the last j with scan[j] <= w.
__device__ int64_t jobOf(const uint64_t* scan, int64_t jobs, uint64_t w) {
  int64_t lo = 0, hi = jobs;  // scan[lo] <= w < scan[hi]
  while (hi - lo > 1) {
    const int64_t mid = (lo + hi) / 2;
    if (scan[mid] <= w)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

// Every (triangle, candidate ray) pair of every axis is one work item, so big triangles spread
// over many threads. kWrite = false counts hits per ray; true writes them at their slots.
template <bool kWrite>
__global__ void rasterize(const ProjectedTriangle* tris, const uint64_t* scan, int64_t count,
                          uint64_t totalWork, RaySpace space, uint32_t leafId, uint32_t* counters,
                          const uint64_t* rawOffsets, Surfel* raw) {
  for (uint64_t w = blockIdx.x * uint64_t(blockDim.x) + threadIdx.x; w < totalWork;
       w += uint64_t(gridDim.x) * blockDim.x) {
    const int64_t job = jobOf(scan, 3 * count, w);
    const int axis = int(job / count);
    const ProjectedTriangle& pt = tris[job];
    const uint64_t local = w - scan[job];
    const int width = pt.rayUMax - pt.rayUMin + 1;
    const int i = pt.rayUMin + int(local % uint64_t(width));
    const int j = pt.rayVMin + int(local / uint64_t(width));
    double depth;
    if (!hitTriangle(pt, i, j, &depth)) continue;
    const int64_t ray = space.base[axis] + int64_t(i) + int64_t(j) * space.raysU[axis];
    const uint32_t slot = atomicAdd(&counters[ray], 1u);
    if (kWrite)
      raw[rawOffsets[ray] + slot] =
          Surfel{float(depth), pt.normal, makeSurfelTag(leafId, pt.enters)};
  }
}

__device__ bool surfelLessDevice(const Surfel& a, const Surfel& b) {
  if (a.depth != b.depth) return a.depth < b.depth;
  if (a.tag != b.tag) return a.tag < b.tag;
  return a.normal < b.normal;
}

__global__ void sortAndNormalize(Surfel* raw, const uint64_t* rawOffsets, RaySpace space,
                                 AxisSetup s, uint32_t leafId, Surfel* normalized,
                                 uint64_t* normalizedOffsets, uint32_t* normalizedCounts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    const int axis = space.axisOf(r);
    Surfel* list = raw + rawOffsets[r];
    const int n = int(rawOffsets[r + 1] - rawOffsets[r]);
    // Insertion sort: lists are short, and the order equals the CPU's std::sort because the
    // comparison is a total order (equal keys are identical surfels).
    for (int k = 1; k < n; ++k) {
      Surfel x = list[k];
      int m = k - 1;
      while (m >= 0 && surfelLessDevice(x, list[m])) {
        list[m + 1] = list[m];
        --m;
      }
      list[m + 1] = x;
    }
    const uint64_t at = rawOffsets[r] + 2 * uint64_t(r);  // room for two clip surfels per ray
    normalizedOffsets[r] = at;
    normalizedCounts[r] = uint32_t(normalizeLeafRay(list, n, s.lo[axis], s.hi[axis], leafId,
                                                    s.minus[axis], s.plus[axis], normalized + at));
  }
}

unsigned itemBlocks(uint64_t items) {
  return blocksFor(int64_t(items < (uint64_t(1) << 30) ? items : (uint64_t(1) << 30)), 256);
}

}  // namespace

std::shared_ptr<DeviceLdi> sampleMeshOnDevice(const GridMesh& mesh, const Grid& grid,
                                              uint32_t leafId, cudaStream_t stream) {
  auto ldi = std::make_shared<DeviceLdi>(grid);
  const RaySpace space(grid);
  const int64_t rays = space.total();
  const int64_t count = int64_t(mesh.triangles.size());
  AxisSetup setup;
  for (int a = 0; a < 3; ++a) {
    setup.firstU[a] = grid.first[grid.uAxis(a)];
    setup.firstV[a] = grid.first[grid.vAxis(a)];
    setup.raysU[a] = grid.raysU(a);
    setup.raysV[a] = grid.raysV(a);
    setup.lo[a] = clipLo(grid, a);
    setup.hi[a] = clipHi(grid, a);
    float axisDir[3] = {0.f, 0.f, 0.f};
    axisDir[a] = 1.f;
    setup.plus[a] = encodeNormal(axisDir[0], axisDir[1], axisDir[2]);
    setup.minus[a] = encodeNormal(-axisDir[0], -axisDir[1], -axisDir[2]);
  }
  DeviceBuffer<uint32_t> counters(static_cast<size_t>(rays));
  STRATA_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, counters.bytes(), stream));
  if (count == 0) {
    buildAxes(space, counters.data(), nullptr, nullptr, ldi.get(), stream, "sampling");
    STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
    return ldi;
  }

  std::vector<TriangleInput> host(static_cast<size_t>(count));
  for (int64_t t = 0; t < count; ++t) {
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        host[size_t(t)].p[c][k] = mesh.positions[mesh.triangles[size_t(t)][c]][k];
    for (int k = 0; k < 3; ++k) host[size_t(t)].n[k] = mesh.normals[size_t(t)][k];
  }
  DeviceBuffer<TriangleInput> input;
  input.upload(host, stream);
  DeviceBuffer<ProjectedTriangle> projected(static_cast<size_t>(3 * count));
  DeviceBuffer<uint64_t> work(static_cast<size_t>(3 * count) + 1);
  projectTriangles<<<blocksFor(3 * count + 1, 128), 128, 0, stream>>>(
      input.data(), count, setup, projected.data(), work.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(work.data(), 3 * count + 1, stream);
  uint64_t totalWork = 0;
  const uint64_t* workEnd[1] = {work.data() + 3 * count};
  readBack(workEnd, &totalWork, 1, stream);

  // Pass 1: count hits per ray; scan into raw offsets.
  rasterize<false><<<itemBlocks(totalWork), 256, 0, stream>>>(projected.data(), work.data(), count,
                                                              totalWork, space, leafId,
                                                              counters.data(), nullptr, nullptr);
  STRATA_CUDA_CHECK(cudaGetLastError());
  DeviceBuffer<uint64_t> rawOffsets(static_cast<size_t>(rays) + 1);
  widenCounts(counters.data(), rays, rawOffsets.data(), stream);
  exclusiveScanAsync(rawOffsets.data(), rays + 1, stream);
  uint64_t rawTotal = 0;
  const uint64_t* rawEnd[1] = {rawOffsets.data() + rays};
  readBack(rawEnd, &rawTotal, 1, stream);

  // Pass 2: write each hit at its ray's next slot.
  DeviceBuffer<Surfel> raw(static_cast<size_t>(rawTotal));
  STRATA_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, counters.bytes(), stream));
  rasterize<true><<<itemBlocks(totalWork), 256, 0, stream>>>(
      projected.data(), work.data(), count, totalWork, space, leafId, counters.data(),
      rawOffsets.data(), raw.data());
  STRATA_CUDA_CHECK(cudaGetLastError());

  // Pass 3: sort and normalise every ray; then the CSR of each axis.
  DeviceBuffer<Surfel> normalized(static_cast<size_t>(rawTotal + 2 * uint64_t(rays)));
  DeviceBuffer<uint64_t> normalizedOffsets(static_cast<size_t>(rays));
  sortAndNormalize<<<blocksFor(rays, 128), 128, 0, stream>>>(
      raw.data(), rawOffsets.data(), space, setup, leafId, normalized.data(),
      normalizedOffsets.data(), counters.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  buildAxes(space, counters.data(), normalized.data(), normalizedOffsets.data(), ldi.get(), stream,
            "sampling");
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  return ldi;
}

}  // namespace strata
