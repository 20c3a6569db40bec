#include "gpu/cuda_backend.h"

#include <cuda_runtime.h>

#include "engine/ldi/grid_mesh.h"
#include "engine/ldi/offset_math.h"
#include "engine/util/parallel_for.h"
#include "gpu/contour/contour_tile.cuh"
#include "gpu/ldi/combine_ldi.cuh"
#include "gpu/ldi/csr_build.cuh"
#include "gpu/ldi/measure_ldi.cuh"
#include "gpu/ldi/offset_ldi.cuh"
#include "gpu/ldi/sample_mesh.cuh"
#include "gpu/ldi/splats.cuh"
#include "gpu/util/cuda_check.h"
#include "gpu/util/device_memory.h"
#include "gpu/util/device_stream.h"

namespace strata {
namespace {

// Scratch memory one sampling batch may take (PlacedLeaf::scratchBytes).
constexpr uint64_t kBatchBytes = uint64_t(512) << 20;

const DeviceLdi& deviceLdi(const LdiHandle& handle) {
  auto* d = dynamic_cast<const DeviceLdi*>(handle.get());
  if (!d) throw Error("internal: an LDI of another backend was passed to the CUDA backend");
  return *d;
}

// The LDI with every axis whole (a copy when some axis is windowed; see device_ldi.h).
std::shared_ptr<const DeviceLdi> wholeDeviceLdi(const LdiHandle& handle,
                                                const DeviceStream& stream) {
  deviceLdi(handle);  // checks the kind
  return wholeOnDevice(std::static_pointer_cast<const DeviceLdi>(handle), stream);
}

// Streams and ownership: the backend owns one stream (stream_) and queues all its work there,
// from whichever thread calls it (one call at a time, as the Backend interface says). Every
// call returns with the stream drained, so a handle it returns is complete and may be read from
// any stream or thread. Each LDI and splats handle shares stream_ through its buffers, which are
// freed on it: handles may outlive the backend, and the stream goes with the last of them.
//
// Devices: the backend works on one device (`device_`), made current on the calling thread at
// the start of every call that queues work, so any thread may call it (one at a time).
class CudaBackend : public Backend {
 public:
  explicit CudaBackend(int device) : device_(device) {
    STRATA_CUDA_CHECK(cudaSetDevice(device_));
    cudaDeviceProp prop{};
    STRATA_CUDA_CHECK(cudaGetDeviceProperties(&prop, device_));
    name_ = prop.name;
    if (device_ != 0) name_ += ", device " + std::to_string(device_);
    keepFreedDeviceMemory(device_);
    stream_ = DeviceStream::create();
  }

  std::string description() const override { return "cuda (" + name_ + ")"; }

  LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                       uint32_t leafId, Progress& progress) override {
    return sampleMeshes({LeafToSample{&mesh, objectToWorld, leafId}}, grid, progress)[0];
  }

  // Leaves placed on the host in parallel, then sampled in batches of at most kBatchBytes of
  // scratch (at least one leaf each): one pass per batch, whatever its leaf count.
  std::vector<LdiHandle> sampleMeshes(const std::vector<LeafToSample>& leaves, const Grid& grid,
                                      Progress& progress) override {
    onDevice();
    progress.check();
    std::vector<PlacedLeaf> placed(leaves.size());
    parallelFor(0, int64_t(leaves.size()), 1, [&](int64_t b, int64_t e) {
      for (int64_t k = b; k < e; ++k) {
        const LeafToSample& leaf = leaves[size_t(k)];
        placed[size_t(k)] = placeLeaf(*leaf.mesh, leaf.objectToWorld, grid, leaf.leafId);
      }
    });
    std::vector<LdiHandle> out;
    size_t k = 0;
    while (k < placed.size()) {
      progress.check();
      std::vector<const PlacedLeaf*> batch;
      uint64_t bytes = 0;
      for (; k < placed.size(); ++k) {
        const uint64_t leafBytes = placed[k].scratchBytes();
        if (!batch.empty() && bytes + leafBytes > kBatchBytes) break;
        bytes += leafBytes;
        batch.push_back(&placed[k]);
      }
      for (auto& ldi : sampleMeshesOnDevice(batch, grid, stream_)) out.push_back(ldi);
    }
    return out;
  }

  LdiHandle combine(RayOp op, const std::vector<LdiHandle>& children, const Grid& grid,
                    Progress& progress) override {
    onDevice();
    progress.check();
    std::vector<const DeviceLdi*> inputs;
    for (const auto& c : children) {
      inputs.push_back(&deviceLdi(c));
      // As the CPU twin: children on another grid would be read past their rays' ends.
      if (!(inputs.back()->grid() == grid)) throw Error("combining LDIs of different grids");
    }
    return combineOnDevice(op, inputs, grid, stream_);
  }

  LdiHandle empty(const Grid& grid) override {
    onDevice();
    return emptyOnDevice(grid, stream_);
  }

  LdiHandle crop(const LdiHandle& ldi, const Grid& window, Progress& progress) override {
    onDevice();
    progress.check();
    deviceLdi(ldi);  // checks the kind
    return cropOnDevice(std::static_pointer_cast<const DeviceLdi>(ldi), window, stream_);
  }

  LdiHandle rewindow(const LdiHandle& ldi, const Grid& window) override {
    onDevice();
    deviceLdi(ldi);  // checks the kind
    return rewindowOnDevice(std::static_pointer_cast<const DeviceLdi>(ldi), window, stream_);
  }

  LdiHandle offset(const LdiHandle& ldi, double distance, Progress& progress) override {
    onDevice();
    progress.check();
    return offsetOnDevice(*wholeDeviceLdi(ldi, stream_), distance, stream_);
  }
  bool evaluatesModifiers() const override { return true; }

  bool keepsLdisOnHost() const override { return false; }
  uint64_t offsetBytesPerNode() const override { return kOffsetBytesPerNode; }

  // Free device memory, as the driver sees it (the pool's kept blocks not counted).
  uint64_t memoryAvailable() const override {
    onDevice();
    size_t free = 0, total = 0;
    if (cudaMemGetInfo(&free, &total) != cudaSuccess) return 0;
    return uint64_t(free);
  }

  LdiMeasure measure(const LdiHandle& ldi, Progress& progress) override {
    onDevice();
    progress.check();
    return measureOnDevice(deviceLdi(ldi), stream_);
  }

  TileContour contourTile(const LdiHandle& root, const glm::ivec3& globalCells,
                          const glm::ivec3& begin, const glm::ivec3& end,
                          Progress& progress) override {
    onDevice();
    progress.check();
    return contourTileOnDevice(*wholeDeviceLdi(root, stream_), globalCells, begin, end, stream_);
  }

  SplatsHandle splats(const LdiHandle& ldi, Progress& progress) override {
    onDevice();
    progress.check();
    return splatsOnDevice(*wholeDeviceLdi(ldi, stream_), stream_);
  }

  // Queued on the LDI's own stream (its buffers' copies), then waited for.
  std::shared_ptr<const Ldi> download(const LdiHandle& handle) override {
    onDevice();
    const DeviceLdi& d = deviceLdi(handle);
    auto host = std::make_shared<Ldi>();
    host->grid = d.grid();
    for (int a = 0; a < 3; ++a) {
      host->axes[a].whole = d.axes[a].whole;
      host->axes[a].window = d.axes[a].window;
      d.axes[a].offsets.downloadAsync(&host->axes[a].offsets);
      d.axes[a].surfels.downloadAsync(&host->axes[a].surfels);
    }
    d.stream().synchronize();
    return wholeLdi(host);
  }

 private:
  void onDevice() const { STRATA_CUDA_CHECK(cudaSetDevice(device_)); }

  int device_ = 0;
  std::string name_;
  DeviceStream stream_;
};

}  // namespace

bool cudaDeviceAvailable(std::string* why) {
  int count = 0;
  cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    cudaGetLastError();
    if (why)
      *why = std::string("no usable CUDA driver or device (") + cudaGetErrorString(status) + ")";
    return false;
  }
  if (count == 0) {
    if (why) *why = "no CUDA device";
    return false;
  }
  return true;
}

int cudaDeviceCount() {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return count;
}

std::shared_ptr<Backend> makeCudaBackend(int device) {
  std::string why;
  if (!cudaDeviceAvailable(&why)) throw Error("--backend cuda: " + why);
  const int count = cudaDeviceCount();
  if (device < 0 || device >= count)
    throw Error("--backend cuda: no device " + std::to_string(device) + " (" +
                std::to_string(count) + " present)");
  return std::make_shared<CudaBackend>(device);
}

}  // namespace strata
