#include <algorithm>
#include <array>
#include <vector>

#include "engine/ldi/grid_mesh.h"
#include "engine/ldi/sample_mesh.h"
#include "engine/ldi/shared_math.h"
#include "engine/util/parallel_for.h"
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

// One leaf of a batch as the kernels see it: its rays among the batch's concatenated rays, its
// jobs (3 per triangle: job axis * triangles + t of the leaf) and triangles among the batch's.
struct BatchLeaf {
  RaySpace space;  // the leaf's own rays (its windows), from 0
  int64_t firstRay;
  int64_t firstJob;
  int64_t firstTriangle;
  int64_t triangles;
  uint32_t leafId;
};

// The last leaf whose `first` member is <= x (leaves without any come before the next that has
// some, with the same first: the last of equals is the one that holds x).
template <typename First>
__device__ int leafOf(const BatchLeaf* leaves, int count, int64_t x, First first) {
  int lo = 0, hi = count;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (first(leaves[mid]) <= x)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

// Every job of the batch: its triangle projected for its axis; work[j] = its candidate rays,
// jobLeaf[j] = its leaf.
__global__ void projectTriangles(const TriangleInput* in, const BatchLeaf* leaves, int leafCount,
                                 int64_t jobs, AxisSetup s, ProjectedTriangle* out,
                                 int32_t* jobLeaf, uint64_t* work) {
  for (int64_t j = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; j <= jobs;
       j += int64_t(gridDim.x) * blockDim.x) {
    if (j == jobs) {
      work[j] = 0;
      continue;
    }
    const int leaf = leafOf(leaves, leafCount, j, [](const BatchLeaf& l) { return l.firstJob; });
    const BatchLeaf& l = leaves[leaf];
    const int64_t local = j - l.firstJob;
    const int axis = int(local / l.triangles);
    const int64_t t = l.firstTriangle + local % l.triangles;
    ProjectedTriangle pt = projectTriangle(in[t].p, in[t].n, axis, s.firstU[axis], s.firstV[axis],
                                           s.raysU[axis], s.raysV[axis]);
    out[j] = pt;
    jobLeaf[j] = leaf;
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

// Every (triangle, candidate ray) pair of every axis of every leaf is one work item, so big
// triangles spread over many threads. kWrite = false counts hits per ray; true writes them at
// their slots.
template <bool kWrite>
__global__ void rasterize(const ProjectedTriangle* tris, const int32_t* jobLeaf,
                          const BatchLeaf* leaves, const uint64_t* scan, int64_t jobs,
                          uint64_t totalWork, uint32_t* counters, const uint64_t* rawOffsets,
                          Surfel* raw) {
  for (uint64_t w = blockIdx.x * uint64_t(blockDim.x) + threadIdx.x; w < totalWork;
       w += uint64_t(gridDim.x) * blockDim.x) {
    const int64_t job = jobOf(scan, jobs, w);
    const BatchLeaf& l = leaves[jobLeaf[job]];
    const int axis = int((job - l.firstJob) / l.triangles);
    const ProjectedTriangle& pt = tris[job];
    const uint64_t local = w - scan[job];
    const int width = pt.rayUMax - pt.rayUMin + 1;
    const int i = pt.rayUMin + int(local % uint64_t(width));
    const int j = pt.rayVMin + int(local / uint64_t(width));
    double depth;
    if (!hitTriangle(pt, i, j, &depth)) continue;
    const int64_t ray = l.firstRay + l.space.rayOf(axis, i, j);
    const uint32_t slot = atomicAdd(&counters[ray], 1u);
    if (kWrite)
      raw[rawOffsets[ray] + slot] =
          Surfel{float(depth), pt.normal, makeSurfelTag(l.leafId, pt.enters)};
  }
}

__global__ void sortAndNormalize(Surfel* raw, const uint64_t* rawOffsets, const BatchLeaf* leaves,
                                 int leafCount, int64_t rays, AxisSetup s, Surfel* normalized,
                                 uint64_t* normalizedOffsets, uint32_t* normalizedCounts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    const BatchLeaf& l =
        leaves[leafOf(leaves, leafCount, r, [](const BatchLeaf& b) { return b.firstRay; })];
    const int axis = l.space.axisOf(r - l.firstRay);
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
    normalizedCounts[r] = uint32_t(normalizeLeafRay(list, n, s.lo[axis], s.hi[axis], l.leafId,
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

// The batch's leaves, rays and triangles, laid out on the host.
struct BatchLayout {
  std::vector<BatchLeaf> leaves;
  RaySpaces rays;
  std::vector<TriangleInput> triangles;
  int64_t jobs = 0;
};

BatchLayout layBatch(const std::vector<const PlacedLeaf*>& placed) {
  BatchLayout b;
  const size_t count = placed.size();
  b.leaves.resize(count);
  int64_t triangles = 0;
  for (size_t k = 0; k < count; ++k) {
    BatchLeaf& leaf = b.leaves[k];
    leaf.space = RaySpace(placed[k]->windows.data());
    leaf.firstRay = b.rays.total;
    leaf.firstJob = b.jobs;
    leaf.firstTriangle = triangles;
    leaf.triangles = int64_t(placed[k]->mesh.triangles.size());
    leaf.leafId = placed[k]->leafId;
    b.rays.add(leaf.space);
    b.jobs += 3 * leaf.triangles;
    triangles += leaf.triangles;
  }
  // Every triangle's corners and normal, filled in parallel by blocks of the batch's triangles.
  b.triangles.resize(size_t(triangles));
  parallelFor(0, triangles, 16384, [&](int64_t first, int64_t last) {
    // The leaf holding triangle `first`: the last whose first triangle is <= it.
    size_t k =
        size_t(std::upper_bound(b.leaves.begin(), b.leaves.end(), first,
                                [](int64_t t, const BatchLeaf& l) { return t < l.firstTriangle; }) -
               b.leaves.begin()) -
        1;
    for (int64_t t = first; t < last; ++t) {
      while (t >= b.leaves[k].firstTriangle + b.leaves[k].triangles) ++k;
      const GridMesh& mesh = placed[k]->mesh;
      const int64_t local = t - b.leaves[k].firstTriangle;
      TriangleInput& in = b.triangles[size_t(t)];
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          in.p[c][d] = mesh.positions[mesh.triangles[size_t(local)][c]][d];
      for (int d = 0; d < 3; ++d) in.n[d] = mesh.normals[size_t(local)][d];
    }
  });
  return b;
}

}  // namespace

uint64_t PlacedLeaf::scratchBytes() const {
  uint64_t rays = 0;
  for (const RayWindow& w : windows) rays += uint64_t(w.rayCount());
  return 60 * rays + 600 * uint64_t(mesh.triangles.size());
}

PlacedLeaf placeLeaf(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                     uint32_t leafId) {
  PlacedLeaf leaf;
  leaf.mesh = toGridUnits(mesh, objectToWorld, grid);
  leaf.leafId = leafId;
  for (int a = 0; a < 3; ++a) {
    leaf.windows[size_t(a)] = meshRayWindow(leaf.mesh, grid, a);
    leaf.whole[size_t(a)] =
        leaf.mesh.triangles.empty() || leaf.windows[size_t(a)].rayCount() * 2 > grid.rayCount(a);
    if (leaf.whole[size_t(a)]) leaf.windows[size_t(a)] = wholeWindow(grid, a);
  }
  return leaf;
}

std::vector<std::shared_ptr<DeviceLdi>> sampleMeshesOnDevice(
    const std::vector<const PlacedLeaf*>& placed, const Grid& grid, const DeviceStream& stream) {
  const BatchLayout layout = layBatch(placed);
  const int leafCount = int(layout.leaves.size());
  std::vector<std::shared_ptr<DeviceLdi>> ldis;
  std::vector<DeviceLdi*> outs;
  for (int k = 0; k < leafCount; ++k) {
    ldis.push_back(std::make_shared<DeviceLdi>(grid, stream));
    outs.push_back(ldis.back().get());
  }
  if (leafCount == 0) return ldis;
  const int64_t rays = layout.rays.total;
  const int64_t jobs = layout.jobs;
  const AxisSetup setup = makeAxisSetup(grid);
  const auto leaves = DeviceBuffer<BatchLeaf>::upload(layout.leaves, stream);
  DeviceBuffer<uint32_t> counters(static_cast<size_t>(rays), stream);
  STRATA_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, counters.bytes(), stream.get()));

  // Projection of every job, and the scan of their candidate rays (one wait for the total).
  const auto input = DeviceBuffer<TriangleInput>::upload(layout.triangles, stream);
  DeviceBuffer<ProjectedTriangle> projected(static_cast<size_t>(jobs), stream);
  DeviceBuffer<int32_t> jobLeaf(static_cast<size_t>(jobs), stream);
  DeviceBuffer<uint64_t> scan(static_cast<size_t>(jobs) + 1, stream);
  projectTriangles<<<blocksFor(jobs + 1, 128), 128, 0, stream.get()>>>(
      input.data(), leaves.data(), leafCount, jobs, setup, projected.data(), jobLeaf.data(),
      scan.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(scan.data(), jobs + 1, stream);
  uint64_t totalWork = 0;
  const uint64_t* workEnd[1] = {scan.data() + jobs};
  readBack(workEnd, &totalWork, 1, stream);

  DeviceBuffer<uint64_t> rawOffsets(static_cast<size_t>(rays) + 1, stream);
  DeviceBuffer<Surfel> raw;
  DeviceBuffer<Surfel> normalized;
  DeviceBuffer<uint64_t> normalizedOffsets;
  if (totalWork > 0) {
    // Pass 1: count hits per ray; scan into raw offsets (one wait for the total).
    rasterize<false><<<itemBlocks(totalWork), 256, 0, stream.get()>>>(
        projected.data(), jobLeaf.data(), leaves.data(), scan.data(), jobs, totalWork,
        counters.data(), nullptr, nullptr);
    STRATA_CUDA_CHECK(cudaGetLastError());
    widenCounts(counters.data(), rays, rawOffsets.data(), stream);
    exclusiveScanAsync(rawOffsets.data(), rays + 1, stream);
    uint64_t rawTotal = 0;
    const uint64_t* rawEnd[1] = {rawOffsets.data() + rays};
    readBack(rawEnd, &rawTotal, 1, stream);

    // Pass 2: write each hit at its ray's next slot.
    raw = DeviceBuffer<Surfel>(static_cast<size_t>(rawTotal), stream);
    STRATA_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, counters.bytes(), stream.get()));
    rasterize<true><<<itemBlocks(totalWork), 256, 0, stream.get()>>>(
        projected.data(), jobLeaf.data(), leaves.data(), scan.data(), jobs, totalWork,
        counters.data(), rawOffsets.data(), raw.data());
    STRATA_CUDA_CHECK(cudaGetLastError());

    // Pass 3: sort and normalise every ray (counters now hold the clean counts).
    normalized = DeviceBuffer<Surfel>(raw.size() + 2 * size_t(rays), stream);
    normalizedOffsets = DeviceBuffer<uint64_t>(static_cast<size_t>(rays), stream);
    sortAndNormalize<<<blocksFor(rays, 128), 128, 0, stream.get()>>>(
        raw.data(), rawOffsets.data(), leaves.data(), leafCount, rays, setup, normalized.data(),
        normalizedOffsets.data(), counters.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  // Then the CSR of every axis of every leaf (one wait for their sizes).
  buildAxesOfMany(layout.rays, counters.data(), normalized.data(), normalizedOffsets.data(), outs,
                  "sampling");
  for (int k = 0; k < leafCount; ++k)
    for (int a = 0; a < 3; ++a) {
      ldis[size_t(k)]->axes[a].whole = placed[size_t(k)]->whole[size_t(a)];
      ldis[size_t(k)]->axes[a].window =
          placed[size_t(k)]->whole[size_t(a)] ? RayWindow{} : placed[size_t(k)]->windows[size_t(a)];
    }
  stream.synchronize();
  return ldis;
}

}  // namespace strata
