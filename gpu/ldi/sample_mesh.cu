#include <vector>

#include "engine/ldi/grid_mesh.h"
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
    const int64_t ray = space.rayOf(axis, i, j);
    const uint32_t slot = atomicAdd(&counters[ray], 1u);
    if (kWrite)
      raw[rawOffsets[ray] + slot] =
          Surfel{float(depth), pt.normal, makeSurfelTag(leafId, pt.enters)};
  }
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
      while (m >= 0 && surfelLess(x, list[m])) {
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

AxisSetup makeAxisSetup(const Grid& grid) {
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
  return setup;
}

// The (triangle, candidate ray) work of all three axes: each triangle projected per axis and
// the exclusive scan of their candidate ray counts (job j = axis * triangles + t).
struct RasterWork {
  int64_t triangles = 0;
  DeviceBuffer<ProjectedTriangle> projected;
  DeviceBuffer<uint64_t> scan;  // 3 * triangles + 1
  uint64_t total = 0;           // items over all jobs
};

RasterWork projectMesh(const GridMesh& mesh, const AxisSetup& setup, const DeviceStream& stream) {
  RasterWork w;
  w.triangles = int64_t(mesh.triangles.size());
  const int64_t count = w.triangles;
  std::vector<TriangleInput> host(static_cast<size_t>(count));
  for (int64_t t = 0; t < count; ++t) {
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        host[size_t(t)].p[c][k] = mesh.positions[mesh.triangles[size_t(t)][c]][k];
    for (int k = 0; k < 3; ++k) host[size_t(t)].n[k] = mesh.normals[size_t(t)][k];
  }
  const auto input = DeviceBuffer<TriangleInput>::upload(host, stream);
  w.projected = DeviceBuffer<ProjectedTriangle>(static_cast<size_t>(3 * count), stream);
  w.scan = DeviceBuffer<uint64_t>(static_cast<size_t>(3 * count) + 1, stream);
  projectTriangles<<<blocksFor(3 * count + 1, 128), 128, 0, stream.get()>>>(
      input.data(), count, setup, w.projected.data(), w.scan.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(w.scan.data(), 3 * count + 1, stream);
  const uint64_t* workEnd[1] = {w.scan.data() + 3 * count};
  readBack(workEnd, &w.total, 1, stream);
  return w;
}

// Every ray's raw hits, unsorted: ray R's at rawOffsets[R] .. rawOffsets[R + 1] of the result.
// counters (one per ray) are scratch, left holding each ray's hit count.
DeviceBuffer<Surfel> rasterizeHits(const RasterWork& w, const RaySpace& space, uint32_t leafId,
                                   uint32_t* counters, DeviceBuffer<uint64_t>* rawOffsets,
                                   const DeviceStream& stream) {
  const int64_t rays = space.total();
  // Pass 1: count hits per ray; scan into raw offsets.
  STRATA_CUDA_CHECK(cudaMemsetAsync(counters, 0, size_t(rays) * sizeof(uint32_t), stream.get()));
  rasterize<false><<<itemBlocks(w.total), 256, 0, stream.get()>>>(
      w.projected.data(), w.scan.data(), w.triangles, w.total, space, leafId, counters, nullptr,
      nullptr);
  STRATA_CUDA_CHECK(cudaGetLastError());
  *rawOffsets = DeviceBuffer<uint64_t>(static_cast<size_t>(rays) + 1, stream);
  widenCounts(counters, rays, rawOffsets->data(), stream);
  exclusiveScanAsync(rawOffsets->data(), rays + 1, stream);
  uint64_t rawTotal = 0;
  const uint64_t* rawEnd[1] = {rawOffsets->data() + rays};
  readBack(rawEnd, &rawTotal, 1, stream);

  // Pass 2: write each hit at its ray's next slot.
  DeviceBuffer<Surfel> raw(static_cast<size_t>(rawTotal), stream);
  STRATA_CUDA_CHECK(cudaMemsetAsync(counters, 0, size_t(rays) * sizeof(uint32_t), stream.get()));
  rasterize<true><<<itemBlocks(w.total), 256, 0, stream.get()>>>(
      w.projected.data(), w.scan.data(), w.triangles, w.total, space, leafId, counters,
      rawOffsets->data(), raw.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  return raw;
}

}  // namespace

std::shared_ptr<DeviceLdi> sampleMeshOnDevice(const GridMesh& mesh, const Grid& grid,
                                              uint32_t leafId, const DeviceStream& stream) {
  auto ldi = std::make_shared<DeviceLdi>(grid, stream);
  // Per axis, the rays the mesh can reach: an axis whose window covers at most half of the
  // grid's rays is sampled and kept windowed (a small leaf costs its size, not the grid's), the
  // others whole, as the CPU backend does.
  RayWindow windows[3];
  bool whole[3];
  for (int a = 0; a < 3; ++a) {
    windows[a] = meshRayWindow(mesh, grid, a);
    whole[a] = mesh.triangles.empty() || windows[a].rayCount() * 2 > grid.rayCount(a);
    if (whole[a]) windows[a] = wholeWindow(grid, a);
  }
  const RaySpace space(windows);
  const int64_t rays = space.total();
  const AxisSetup setup = makeAxisSetup(grid);
  DeviceBuffer<uint32_t> counters(static_cast<size_t>(rays), stream);
  auto settle = [&] {
    for (int a = 0; a < 3; ++a) {
      ldi->axes[a].whole = whole[a];
      ldi->axes[a].window = whole[a] ? RayWindow{} : windows[a];
    }
  };
  if (mesh.triangles.empty()) {
    STRATA_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, counters.bytes(), stream.get()));
    buildAxes(space, counters.data(), nullptr, nullptr, ldi.get(), "sampling");
    settle();
    stream.synchronize();
    return ldi;
  }
  const RasterWork work = projectMesh(mesh, setup, stream);
  DeviceBuffer<uint64_t> rawOffsets;
  DeviceBuffer<Surfel> raw =
      rasterizeHits(work, space, leafId, counters.data(), &rawOffsets, stream);

  // Pass 3: sort and normalise every ray; then the CSR of each axis.
  DeviceBuffer<Surfel> normalized(raw.size() + 2 * size_t(rays), stream);
  DeviceBuffer<uint64_t> normalizedOffsets(static_cast<size_t>(rays), stream);
  sortAndNormalize<<<blocksFor(rays, 128), 128, 0, stream.get()>>>(
      raw.data(), rawOffsets.data(), space, setup, leafId, normalized.data(),
      normalizedOffsets.data(), counters.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  buildAxes(space, counters.data(), normalized.data(), normalizedOffsets.data(), ldi.get(),
            "sampling");
  settle();
  stream.synchronize();
  return ldi;
}

}  // namespace strata
