#include "gpu/cuda_backend.h"

#include <cuda_runtime.h>

#include "engine/ldi/grid_mesh.h"
#include "gpu/contour/contour_tile.cuh"
#include "gpu/ldi/combine_ldi.cuh"
#include "gpu/ldi/measure_ldi.cuh"
#include "gpu/ldi/sample_mesh.cuh"
#include "gpu/ldi/splats.cuh"
#include "gpu/util/cuda_check.h"
#include "gpu/util/device_memory.h"

namespace strata {
namespace {

const DeviceLdi& deviceLdi(const LdiHandle& handle) {
  auto* d = dynamic_cast<const DeviceLdi*>(handle.get());
  if (!d) throw Error("internal: an LDI of another backend was passed to the CUDA backend");
  return *d;
}

class CudaBackend : public Backend {
 public:
  CudaBackend() {
    STRATA_CUDA_CHECK(cudaSetDevice(0));
    cudaDeviceProp prop{};
    STRATA_CUDA_CHECK(cudaGetDeviceProperties(&prop, 0));
    name_ = prop.name;
    STRATA_CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
  }
  // Each method orders the calling thread's allocations on stream_ (setAllocationStream). The
  // stream goes with the backend: device memory released after that (an LDI or splats handle
  // that outlives its backend, released on this or another thread) must be freed on the legacy
  // stream, so the destroying thread's allocation stream is reset here. (Other threads that
  // called into the backend must not outlive it with handles; the editor's worker joins first.)
  ~CudaBackend() override {
    if (!stream_) return;
    cudaStreamSynchronize(stream_);
    if (allocationStream() == stream_) setAllocationStream(nullptr);
    cudaStreamDestroy(stream_);
  }

  std::string description() const override { return "cuda (" + name_ + ")"; }

  LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                       uint32_t leafId, Progress& progress) override {
    setAllocationStream(stream_);
    progress.check();
    GridMesh placed = toGridUnits(mesh, objectToWorld, grid);
    return sampleMeshOnDevice(placed, grid, leafId, stream_);
  }

  LdiHandle combine(RayOp op, const std::vector<LdiHandle>& children, const Grid& grid,
                    Progress& progress) override {
    setAllocationStream(stream_);
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
    setAllocationStream(stream_);
    return emptyOnDevice(grid, stream_);
  }

  LdiMeasure measure(const LdiHandle& ldi, Progress& progress) override {
    setAllocationStream(stream_);
    progress.check();
    return measureOnDevice(deviceLdi(ldi), stream_);
  }

  TileContour contourTile(const LdiHandle& root, const glm::ivec3& globalCells,
                          const glm::ivec3& begin, const glm::ivec3& end,
                          Progress& progress) override {
    setAllocationStream(stream_);
    progress.check();
    return contourTileOnDevice(deviceLdi(root), globalCells, begin, end, stream_);
  }

  SplatsHandle splats(const LdiHandle& ldi, Progress& progress) override {
    setAllocationStream(stream_);
    progress.check();
    return splatsOnDevice(deviceLdi(ldi), stream_);
  }

  std::shared_ptr<const Ldi> download(const LdiHandle& handle) override {
    setAllocationStream(stream_);
    const DeviceLdi& d = deviceLdi(handle);
    auto host = std::make_shared<Ldi>();
    host->grid = d.grid();
    for (int a = 0; a < 3; ++a) {
      d.axes[a].offsets.download(&host->axes[a].offsets, stream_);
      d.axes[a].surfels.download(&host->axes[a].surfels, stream_);
    }
    STRATA_CUDA_CHECK(cudaStreamSynchronize(stream_));
    return host;
  }

 private:
  std::string name_;
  cudaStream_t stream_ = nullptr;
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

std::shared_ptr<Backend> makeCudaBackend() {
  std::string why;
  if (!cudaDeviceAvailable(&why)) throw Error("--backend cuda: " + why);
  return std::make_shared<CudaBackend>();
}

}  // namespace strata
